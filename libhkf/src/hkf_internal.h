/* hkf_internal.h - what the library's source files share (private). */
#ifndef HKF_INTERNAL_H
#define HKF_INTERNAL_H

#include "hkf/hkf.h"

/* HKF_OK, or the hkf_result_t of the first setting that makes no sense. */
int hkf_settings_check(const hkf_settings_t *s);

#endif /* HKF_INTERNAL_H */

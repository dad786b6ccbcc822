/* hkf_internal.h - what the library's source files share (private). */
#ifndef HKF_INTERNAL_H
#define HKF_INTERNAL_H

#include "hkf/hkf.h"

/* HKF_OK, or the hkf_result_t of the first setting that makes no sense. */
int hkf_settings_check(const hkf_settings_t *s);

/* The axis loops run over all HKF_LANES where the compiler turns them into
 * SIMD (the idle fourth lane fills a vector), and over the 3 axes alone on
 * scalar cores (Cortex-M), where the idle lane would only cost time. The
 * idle lane is then never read. */
#if (defined(__SSE2__) || defined(__ARM_NEON) || defined(__AVX__) || defined(__ALTIVEC__)) && HKF_LANES == 4
#define HKF_LOOP_LANES HKF_LANES
#else
#define HKF_LOOP_LANES HKF_AXES
#endif

#endif /* HKF_INTERNAL_H */

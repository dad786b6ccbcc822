/* hkf_internal.h - what the library's source files share (private). */
#ifndef HKF_INTERNAL_H
#define HKF_INTERNAL_H

#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"

/* HKF_OK, or the hkf_result_t of the first setting that makes no sense. */
int hkf_settings_check(const hkf_settings_t *s);

/* HKF_OK, or why one Eq. 8 curve makes no sense (HKF_ERROR_SETTING_SIGMA or _CURVE). */
int hkf_curve_check(const hkf_noise_curve_t *c);

/* The noise calibration's parts that the angles' and the position's hand-overs share
 * (hkf_calibration.c): the settings checked and taken with the floor of n (HKF_OK or the error), and n
 * back to its start (one measurement's lanes: hkf_calibration_take.h). */
int hkf_calibration_begin(hkf_calibration_t *c, const hkf_calibration_settings_t *s, hkf_real_t floor);
void hkf_calibration_restart(hkf_calibration_t *c);

/* The axis loops run over all HKF_LANES where the compiler turns them into
 * SIMD (the idle fourth lane fills a vector), and over the 3 axes alone on
 * scalar cores (Cortex-M), where the idle lane would only cost time. The
 * idle lane is then never read. */
#if (defined(__SSE2__) || defined(__ARM_NEON) || defined(__AVX__) || defined(__ALTIVEC__)) && HKF_LANES == 4
#define HKF_LOOP_LANES HKF_LANES
#else
#define HKF_LOOP_LANES HKF_AXES
#endif

/* Steps shared by hkf_update and hkf_update_pair, inlined into each so that
 * hkf_update's code is what it would be on its own (a Cortex-M0's flash). */
#if defined(__GNUC__)
#define HKF_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define HKF_ALWAYS_INLINE inline
#endif

/* Where the filter finds its settings and the per-lane values the axis loops
 * read: every build keeps its own copy of the settings (hkf_init); the float
 * and double builds also keep lane arrays (contiguous, for SIMD), the
 * fixed-point build reads the copy, to save RAM. */
#if defined(HKF_REAL_FIXED)
#define HKF_SETTINGS(f) (&(f)->settings)
#define HKF_KEEP_SETTINGS(f, s) ((f)->settings = *(s))
#define HKF_Q(f, a) ((f)->settings.process_noise[a])
#define HKF_R_CONST(f, a) ((f)->settings.r_const[a])
#define HKF_MU(f, a) ((f)->settings.noise[a].mu)
#define HKF_NOISE_FLOOR(f, a) ((f)->settings.noise[a].floor)
#else
#define HKF_SETTINGS(f) (&(f)->settings)
#define HKF_KEEP_SETTINGS(f, s) ((f)->settings = *(s))
#define HKF_Q(f, a) ((f)->q[a])
#define HKF_R_CONST(f, a) ((f)->r_const[a])
#define HKF_MU(f, a) ((f)->mu[a])
#define HKF_NOISE_FLOOR(f, a) ((f)->noise_floor[a])
#endif

#endif /* HKF_INTERNAL_H */

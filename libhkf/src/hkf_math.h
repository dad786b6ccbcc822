/*
 * hkf_math.h - the small math layer under the filter (private).
 *
 * The filter code uses only these and + - * on hkf_real_t, so a fixed-point
 * build replaces this file's bodies, not the filter. libm is used for exp only.
 */
#ifndef HKF_MATH_H
#define HKF_MATH_H

#include <math.h>
#include "hkf/hkf_real.h"

#if defined(HKF_REAL_DOUBLE)
static inline hkf_real_t hkf_exp(hkf_real_t x) { return exp(x); }
#define HKF_SERIES_BELOW HKF_REAL(1e-5)
#else
static inline hkf_real_t hkf_exp(hkf_real_t x) { return expf(x); }
#define HKF_SERIES_BELOW HKF_REAL(0.01)
#endif

/* 1 - exp(-u) for u >= 0. For small u, exp(-u) is too close to 1 for the
 * type to resolve the difference (the roll curves multiply it by ~1e5), so a
 * short series is used there: u (1 - u/2 (1 - u/3)), relative error < u^3/24,
 * below the type's epsilon under HKF_SERIES_BELOW. */
static inline hkf_real_t hkf_one_minus_exp_neg(hkf_real_t u)
{
    if (u < HKF_SERIES_BELOW) {
        return u * (HKF_REAL(1.0) - HKF_REAL(0.5) * u * (HKF_REAL(1.0) - u * HKF_REAL(0.33333333333333333)));
    }
    return HKF_REAL(1.0) - hkf_exp(-u);
}

static inline hkf_real_t hkf_div(hkf_real_t a, hkf_real_t b) { return a / b; }

static inline int hkf_is_finite(hkf_real_t x) { return isfinite(x) != 0; }

static inline hkf_real_t hkf_abs(hkf_real_t x) { return x < 0 ? -x : x; }

/* Wraps an angle to [-180, 180). Callers keep |x| below a few times
 * HKF_MAX_ABS_ANGLE, so an int holds the number of turns. */
static inline hkf_real_t hkf_wrap180(hkf_real_t x)
{
    const int turns = (int)((x + HKF_REAL(180.0)) * HKF_REAL(0.0027777777777777778) /* 1/360 */);
    hkf_real_t w = x - HKF_REAL(360.0) * (hkf_real_t)turns;
    if (w < HKF_REAL(-180.0)) {
        w += HKF_REAL(360.0);
    } else if (w >= HKF_REAL(180.0)) {
        w -= HKF_REAL(360.0);
    }
    return w;
}

#endif /* HKF_MATH_H */

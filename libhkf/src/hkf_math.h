/*
 * hkf_math.h - the small math layer under the filter (private).
 *
 * The filter code uses only these and + - * on hkf_real_t, so a fixed-point
 * build replaces this file's bodies, not the filter. libm is used only for
 * exp in the double build.
 */
#ifndef HKF_MATH_H
#define HKF_MATH_H

#include <math.h>
#include <stdint.h>
#include "hkf/hkf_real.h"

#if defined(HKF_REAL_DOUBLE)
/* 1 - exp(-u) for u >= 0. For small u, exp(-u) is too close to 1 for the
 * difference to keep its digits (the roll curves multiply it by ~1e5), so a
 * short series is used there: u (1 - u/2 (1 - u/3)), relative error < u^3/24. */
static inline hkf_real_t hkf_one_minus_exp_neg(hkf_real_t u)
{
    if (u < 1e-5) {
        return u * (1.0 - 0.5 * u * (1.0 - u * 0.33333333333333333));
    }
    return 1.0 - exp(-u);
}
#else
/* 1 - exp(-u) for u >= 0, inline, without libm and without a branch:
 * exp(-u) = 2^n e^g with n = round(-u log2 e) and |g| <= ln2 / 2, and
 * e^g = 1 + q(g), q a degree-6 Taylor polynomial (truncation < 1.2e-7
 * relative, about float's rounding). Then 1 - exp(-u) = (1 - 2^n) - 2^n q;
 * for small u, n = 0 and that is -q, computed directly without cancelling,
 * so the roll curves (lambda ~ 1e5) keep their digits near their centre. */
static inline hkf_real_t hkf_one_minus_exp_neg(hkf_real_t u)
{
    const float t0 = -u * 1.44269504088896341f; /* log2(e) */
    const float t = t0 < -126.0f ? -126.0f : t0; /* below 2^-126 the result is 1 anyway */
    const int32_t n = (int32_t)(t - 0.5f);      /* t <= 0: nearest integer */
    const float g = (t - (float)n) * 0.693147180559945309f;
    const float q = g * (1.0f + g * (0.5f + g * (1.0f / 6.0f + g * (1.0f / 24.0f + g * (1.0f / 120.0f + g * (1.0f / 720.0f))))));
    union { int32_t i; float x; } two_n; /* 2^n from its exponent bits */
    two_n.i = (n + 127) * 8388608;       /* << 23 */
    return (1.0f - two_n.x) - two_n.x * q;
}
#endif

static inline hkf_real_t hkf_div(hkf_real_t a, hkf_real_t b) { return a / b; }

static inline int hkf_is_finite(hkf_real_t x) { return isfinite(x) != 0; }

#if defined(HKF_REAL_DOUBLE)
static inline hkf_real_t hkf_abs(hkf_real_t x) { return fabs(x); }  /* a bit mask, no call */
#else
static inline hkf_real_t hkf_abs(hkf_real_t x) { return fabsf(x); }
#endif

/* Wraps an angle to [-180, 180). Callers keep |x| below a few times
 * HKF_MAX_ABS_ANGLE, so an int holds the number of turns. Most angles are
 * in range already: that costs two comparisons. */
static inline hkf_real_t hkf_wrap180(hkf_real_t x)
{
    int turns;
    hkf_real_t w;
    if (x >= HKF_REAL(-180.0) && x < HKF_REAL(180.0)) {
        return x;
    }
    turns = (int)((x + HKF_REAL(180.0)) * HKF_REAL(0.0027777777777777778) /* 1/360 */);
    w = x - HKF_REAL(360.0) * (hkf_real_t)turns;
    if (w < HKF_REAL(-180.0)) {
        w += HKF_REAL(360.0);
    } else if (w >= HKF_REAL(180.0)) {
        w -= HKF_REAL(360.0);
    }
    return w;
}

#endif /* HKF_MATH_H */

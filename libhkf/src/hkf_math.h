/*
 * hkf_math.h - the small math layer under the filter (private).
 *
 * The filter does all its arithmetic through these: hkf_add, hkf_sub,
 * hkf_mul, a divisor prepared once and used for several quotients, the
 * wrap of an angle, and the rise of a noise curve above its floor (Eq. 8).
 * Comparisons and negation are plain C on hkf_real_t. Each numeric build
 * (float, double, Q16.16 fixed point) is one branch of this file; the filter
 * is one source for all three.
 */
#ifndef HKF_MATH_H
#define HKF_MATH_H

#include <stdint.h>
#include "hkf/hkf.h"

#if !defined(HKF_REAL_FIXED)
#include <math.h>

static inline hkf_real_t hkf_add(hkf_real_t a, hkf_real_t b) { return a + b; }
static inline hkf_real_t hkf_sub(hkf_real_t a, hkf_real_t b) { return a - b; }
static inline hkf_real_t hkf_mul(hkf_real_t a, hkf_real_t b) { return a * b; }

/* a / s for several a: the reciprocal, then one multiply per quotient. */
typedef hkf_real_t hkf_divisor_t;
static inline hkf_divisor_t hkf_divisor(hkf_real_t s) { return HKF_REAL(1.0) / s; }
static inline hkf_real_t hkf_divide(hkf_real_t a, hkf_divisor_t d) { return a * d; }

static inline int hkf_is_finite(hkf_real_t x) { return isfinite(x) != 0; }

/* A 2x2 covariance stays positive semi-definite in float and double (the
 * ranges keep every term finite): nothing to do. */
static inline void hkf_keep_covariance(hkf_real_t *p00, hkf_real_t *p01, hkf_real_t *p11)
{
    (void)p00, (void)p01, (void)p11;
}
#endif

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

static inline hkf_real_t hkf_exp_neg(hkf_real_t u) { return exp(-u); }
static inline hkf_real_t hkf_sqrt(hkf_real_t x) { return sqrt(x); }

static inline hkf_real_t hkf_abs(hkf_real_t x) { return fabs(x); }  /* a bit mask, no call */
#elif !defined(HKF_REAL_FIXED)
/* 1 - exp(-u) for u >= 0, inline, without libm and without a branch:
 * exp(-u) = 2^n e^g with n = round(-u log2 e) and |g| <= ln2 / 2, and
 * e^g = 1 + q(g), q a degree-6 Taylor polynomial (truncation < 1.2e-7
 * relative, about float's rounding). Then 1 - exp(-u) = (1 - 2^n) - 2^n q;
 * for small u, n = 0 and that is -q, computed directly without cancelling,
 * so the roll curves (lambda ~ 1e5) keep their digits near their center. */
typedef struct {
    float two_n, q; /* exp(-u) = 2^n (1 + q) */
} hkf_exp_parts_t;

static inline hkf_exp_parts_t hkf_exp_neg_parts(hkf_real_t u)
{
    const float t0 = -u * 1.44269504088896341f; /* log2(e) */
    const float t = t0 < -126.0f ? -126.0f : t0; /* below 2^-126 the result is 1 anyway */
    const int32_t n = (int32_t)(t - 0.5f);      /* t <= 0: nearest integer */
    const float g = (t - (float)n) * 0.693147180559945309f;
    union { int32_t i; float x; } two_n; /* 2^n from its exponent bits */
    hkf_exp_parts_t p;
    two_n.i = (n + 127) * 8388608;       /* << 23 */
    p.two_n = two_n.x;
    p.q = g * (1.0f + g * (0.5f + g * (1.0f / 6.0f + g * (1.0f / 24.0f + g * (1.0f / 120.0f + g * (1.0f / 720.0f))))));
    return p;
}

static inline hkf_real_t hkf_one_minus_exp_neg(hkf_real_t u)
{
    const hkf_exp_parts_t p = hkf_exp_neg_parts(u);
    return (1.0f - p.two_n) - p.two_n * p.q;
}

/* exp(-u) for u >= 0, the same way; at least 2^-126 (never 0). */
static inline hkf_real_t hkf_exp_neg(hkf_real_t u)
{
    const hkf_exp_parts_t p = hkf_exp_neg_parts(u);
    return p.two_n + p.two_n * p.q;
}

/* sqrt(x) for x >= 0: one instruction where the core has one (x86, Cortex-M4F, M7; the library is
 * built with -fno-math-errno, so sqrtf never sets errno and vectorizes), newlib's routine on a core
 * without an FPU. */
static inline hkf_real_t hkf_sqrt(hkf_real_t x)
{
    return x > 0 ? sqrtf(x) : 0.0f;
}

static inline hkf_real_t hkf_abs(hkf_real_t x) { return fabsf(x); }
#endif

#if !defined(HKF_REAL_FIXED)
/* The curve's constants for the axis loops: floor tau - lambda, lambda, mu
 * and 1 / (2 sigma^2). */
static inline void hkf_curve_prepare(hkf_filter_t *f, int lane, const hkf_noise_curve_t *c)
{
    f->mu[lane] = c->mu;
    f->lambda[lane] = c->lambda;
    f->gauss_scale[lane] = HKF_REAL(1.0) / (HKF_REAL(2.0) * c->sigma * c->sigma);
    f->noise_floor[lane] = c->tau - c->lambda;
}

/* The idle lane's flat curve at `level`. */
static inline void hkf_curve_flat(hkf_filter_t *f, int lane, hkf_real_t level)
{
    f->mu[lane] = 0;
    f->lambda[lane] = 0;
    f->gauss_scale[lane] = 0;
    f->noise_floor[lane] = level;
}

/* Eq. 8 above its floor, u = x - mu:  lambda (1 - exp(-u^2 / (2 sigma^2))). */
static inline hkf_real_t hkf_curve_rise(const hkf_filter_t *restrict f, int lane, hkf_real_t u)
{
    return f->lambda[lane] * hkf_one_minus_exp_neg(u * u * f->gauss_scale[lane]);
}

/* Wraps an angle to [-180, 180). Callers keep |x| below a few times
 * HKF_MAX_ABS_ANGLE, so an int holds the number of turns. Most angles are
 * in range already: that costs one comparison (-180 itself takes the long way to itself). */
static inline hkf_real_t hkf_wrap180(hkf_real_t x)
{
    int turns;
    hkf_real_t w;
    if (hkf_abs(x) < HKF_REAL(180.0)) {
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

#else /* HKF_REAL_FIXED */
/*
 * Q16.16 fixed point, integers only: no libm, no floating point, no division
 * instruction or routine (Cortex-M0 has none). Products are formed in 64 bits
 * and rounded to nearest; every result saturates at +-(2^31 - 1) units
 * (+-32768) instead of wrapping. Right shifts of negative values are
 * arithmetic (GCC and Clang define them so).
 *
 * Range analysis (limits from hkf.h, which hkf_init enforces):
 *   angles      |z| <= 3600; yaw wrapped to +-180; center and mu likewise.
 *               Differences |z - x| <= 7200 fit, and squares of them
 *               saturate only beyond 181 deg (loop closure and the gate
 *               compare squares against theta^2 <= 180^2 = 32400 and gate^2).
 *   variances   R is clamped to r_max <= 16384 deg^2. p00, p11 start at
 *               p0 <= 16384 and grow while coasting by at most q coast_time
 *               and p11 dt^2 per step; beyond 32768 they saturate, which
 *               only makes the next gain 1 (the measurement is believed).
 *   rates       deg/s; a head turns at < 1000, Q16.16 holds 32767.
 *   dt          (0, 10] s at a resolution of 15 us (0.05 % of a 30 Hz
 *               frame). Process noise is formed as ((q dt) dt) dt / 3 so
 *               each intermediate keeps its digits: at 30 Hz and q = 500,
 *               q dt^3 / 3 = 0.0062 deg^2 is 405 units.
 *   gains       k0 = p00 / S, k1 = p01 / S, 1 - k0 = R / S: quotients
 *               correctly rounded (a shift-and-subtract division), since
 *               1 / S alone would keep only ~4 digits for S ~ 10^4.
 *   Eq. 8       in floor / curvature form (hkf.h; curvature in Q8.24): the rise above the floor
 *               is curvature u^2 g(v) with v = u^2 / (2 sigma^2) and
 *               g(v) = (1 - e^-v) / v for v < 1 (a polynomial in Q2.30, so
 *               the small rises near the center keep their digits), and
 *               lambda (1 - e^-v) for v >= 1 (e^-v = (e^-(v/32))^32, the
 *               same polynomial then five squarings). A rise that saturates
 *               (|rise| >= 32768 > 16384 + |floor|) is beyond r_max either way.
 */
#define HKF_FIXED_MAX INT32_MAX

static inline hkf_real_t hkf_saturate(int64_t x)
{
    return x > HKF_FIXED_MAX ? HKF_FIXED_MAX : x < -HKF_FIXED_MAX ? -HKF_FIXED_MAX : (hkf_real_t)x;
}

/* a + b, a - b, a b (rounded), saturated; out of line in hkf_math_fixed.c:
 * inline, each is ~40 bytes of Thumb-1 code at every use (flash on an M0). */
hkf_real_t hkf_add(hkf_real_t a, hkf_real_t b);
hkf_real_t hkf_sub(hkf_real_t a, hkf_real_t b);
hkf_real_t hkf_mul(hkf_real_t a, hkf_real_t b);

static inline hkf_real_t hkf_abs(hkf_real_t x) { return x >= 0 ? x : x == INT32_MIN ? HKF_FIXED_MAX : -x; }
static inline int hkf_is_finite(hkf_real_t x) { (void)x; return 1; }

/* a / s, correctly rounded (hkf_math_fixed.c); s > 0 (S = P + R >= r_min). */
typedef hkf_real_t hkf_divisor_t;
static inline hkf_divisor_t hkf_divisor(hkf_real_t s) { return s > 0 ? s : 1; }
hkf_real_t hkf_divide(hkf_real_t a, hkf_divisor_t d);

/* Keeps [[p00, p01], [p01, p11]] a covariance under saturation and rounding
 * (hkf_math_fixed.c). */
void hkf_keep_covariance(hkf_real_t *p00, hkf_real_t *p01, hkf_real_t *p11);

/* Wraps an angle to [-180, 180) (hkf_math_fixed.c: one copy, out of line, for the flash). */
hkf_real_t hkf_wrap180(hkf_real_t x);

/* Eq. 8's pieces, out of line in hkf_math_fixed.c: the rise above its floor,
 * lambda (1 - e^-v) with v = u^2 / (2 sigma^2), u = x - mu, read from the
 * filter's settings (nothing is prepared: RAM before time). */
uint32_t hkf_g30(uint32_t v); /* (1 - e^-v) / v for 0 <= v <= 1, Q2.30 */

/* exp(-u) for u >= 0 and sqrt(x) for x >= 0, in Q16.16 (hkf_math_fixed.c). */
hkf_real_t hkf_exp_neg(hkf_real_t u);
hkf_real_t hkf_sqrt(hkf_real_t x);
/* The motion adaptation's posterior mu' from its prior pi, d and r (hkf_two_models.h). */
hkf_real_t hkf_two_models_posterior_q16(hkf_real_t pi, hkf_real_t d, hkf_real_t r);
hkf_real_t hkf_curve_rise(const hkf_filter_t *f, int lane, hkf_real_t u);
#endif /* HKF_REAL_FIXED */

/* 1 when the three noise levels are all > 0 and finite, in one test (NaN fails it; a sum of positive
 * levels is finite only when each is); 0 does not name the bad one, so the caller then looks. */
static inline int hkf_noise_levels_ok(const hkf_real_t n[3])
{
#if defined(HKF_REAL_FIXED)
    return (int)(n[0] > 0) & (int)(n[1] > 0) & (int)(n[2] > 0);
#else
    return (int)(n[0] > 0) & (int)(n[1] > 0) & (int)(n[2] > 0) & hkf_is_finite(n[0] + n[1] + n[2]);
#endif
}

#endif /* HKF_MATH_H */

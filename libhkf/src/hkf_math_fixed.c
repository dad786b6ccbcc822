/*
 * hkf_math_fixed.c - the Q16.16 math layer's larger pieces (private; see the
 * range analysis in hkf_math.h): the saturating arithmetic, the exact
 * division, the covariance guard and Eq. 8's curve in integers. Out of line
 * so each exists once in flash and their 64-bit temporaries live in their own
 * stack frames, not in every caller's. Empty in the float and double builds.
 */
#include "hkf_math.h"

#if defined(HKF_REAL_FIXED)
hkf_real_t hkf_add(hkf_real_t a, hkf_real_t b) { return hkf_saturate((int64_t)a + b); }
hkf_real_t hkf_sub(hkf_real_t a, hkf_real_t b) { return hkf_saturate((int64_t)a - b); }
hkf_real_t hkf_mul(hkf_real_t a, hkf_real_t b) { return hkf_saturate(((int64_t)a * b + 32768) >> 16); }

/* round(n / d) for n < d 2^31 and 0 < d < 2^31 (so the quotient is < 2^31):
 * restoring division, one quotient bit per turn, in 32-bit registers. */
static uint32_t udiv_round(uint64_t n, uint32_t d)
{
    uint32_t r = (uint32_t)(n >> 31), low = (uint32_t)n & 0x7FFFFFFFu, q = 0;
    int i;
    for (i = 30; i >= 0; --i) {
        r = (r << 1) | ((low >> i) & 1u); /* r < 2d < 2^32 */
        q <<= 1;
        if (r >= d) {
            r -= d;
            q |= 1u;
        }
    }
    return q + (r >= d - r ? 1u : 0u); /* round half up: 2r >= d */
}

/* a / d, correctly rounded to Q16.16, saturated. */
hkf_real_t hkf_divide(hkf_real_t a, hkf_divisor_t d)
{
    const uint64_t n = (uint64_t)hkf_abs(a) << 16;
    const uint32_t q = (n >> 31) >= (uint64_t)d ? (uint32_t)HKF_FIXED_MAX : udiv_round(n, (uint32_t)d);
    const hkf_real_t m = q > (uint32_t)HKF_FIXED_MAX ? HKF_FIXED_MAX : (hkf_real_t)q;
    return a < 0 ? -m : m;
}

/* Keeps [[p00, p01], [p01, p11]] a covariance when saturation (a variance
 * stopped at 32768 while coasting at the largest q for up to max_dt) or
 * rounding has broken it: variances >= 0 and p01^2 <= p00 p11, by shrinking
 * the correlation to min(p00, p11), which keeps the inequality. Without it
 * the next update made p11 negative (found by fuzz_libhkf_fixed). */
void hkf_keep_covariance(hkf_real_t *p00, hkf_real_t *p01, hkf_real_t *p11)
{
    *p00 = *p00 > 0 ? *p00 : 0;
    *p11 = *p11 > 0 ? *p11 : 0;
    if ((int64_t)*p01 * *p01 > (int64_t)*p00 * *p11) {
        const hkf_real_t most = *p00 < *p11 ? *p00 : *p11;
        *p01 = *p01 < 0 ? -most : most;
    }
}

/* g(v) = (1 - e^-v) / v = sum_k (-v)^k / (k+1)! for 0 <= v <= 1, Q2.30 in
 * and out; the series to v^8 is within 2.8e-7 (2^-21.8). */
uint32_t hkf_g30(uint32_t v)
{
    static const uint32_t c[9] = {1073741824u, 536870912u, 178956971u, 44739243u, 8947849u,
                                  1491308u,    213044u,    26631u,     2959u}; /* 2^30 / (k+1)! */
    uint32_t acc = c[8];
    int k;
    for (k = 7; k >= 0; --k) {
        acc = c[k] - (uint32_t)(((uint64_t)acc * v) >> 30);
    }
    return acc;
}

/* lambda = 2 curvature sigma^2 (Q16.16, saturated: beyond 32768 it only ever
 * meets the r_max clamp) = 2 c24 s2 / 2^24, with s2 = sigma^2 split at bit 20
 * so no product exceeds 2^55. */
static hkf_real_t curve_lambda(const hkf_noise_curve_t *c)
{
    const int64_t s2 = ((int64_t)c->sigma * c->sigma) >> 16; /* sigma^2, Q16.16, < 2^44 */
    const int64_t c24 = c->curvature_q24;
    return hkf_saturate(((c24 * (s2 >> 20)) >> 3) + ((c24 * (s2 & 0xFFFFF)) >> 23));
}

/* 1 / (sqrt(2) sigma) in unsigned Q1.31 (sigma >= 1): round(2^47 / sqrt(2)) / sigma (Q16.16, >= 1), within the
 * division's domain (quotient < 2^31). Formed where Eq. 8 is read, not kept: 12 B of a filter's RAM for a
 * division per axis and step. */
static uint32_t inverse_width(const hkf_noise_curve_t *c)
{
    return udiv_round(99516432383215u, (uint32_t)c->sigma);
}

/* Wraps an angle to [-180, 180): the number of turns from a multiply by
 * 2^40 / (360 * 2^16) (off by at most one), then one correction. */
hkf_real_t hkf_wrap180(hkf_real_t x)
{
    const int64_t half = (int64_t)180 << 16, full = (int64_t)360 << 16;
    int64_t w;
    if (x >= -half && x < half) {
        return x;
    }
    w = x - full * ((((int64_t)x + half) * 46603) >> 40);
    if (w < -half) {
        w += full;
    } else if (w >= half) {
        w -= full;
    }
    return (hkf_real_t)w;
}

/* exp(-u) = (e^-(u/16))^16 in Q2.30: u/16 < 1 through g (e^-v = 1 - v g(v)), then four squarings; 0 from
 * u >= 16 on (e^-16 is 120 units). */
static uint32_t exp_neg_q30(hkf_real_t u)
{
    uint64_t e;
    uint32_t v;
    int k;
    if (u >= (16 << 16)) {
        return 0;
    }
    v = (uint32_t)(u > 0 ? u : 0) << 10; /* u / 16 in Q2.30 */
    e = (1u << 30) - (((uint64_t)v * hkf_g30(v)) >> 30);
    for (k = 0; k < 4; ++k) {
        e = (e * e) >> 30;
    }
    return (uint32_t)e;
}

/* Eq. 8 above its floor, u = x - mu: lambda (1 - e^-v), v = u^2 / (2 sigma^2). */
hkf_real_t hkf_curve_rise(const hkf_filter_t *f, int lane, hkf_real_t u)
{
    const uint64_t au = (uint64_t)hkf_abs(u);
    uint64_t w;
    if (u == 0) {
        return 0; /* the centre (each step's e(mu), hkf_filter.c): no division */
    }
    w = (au * inverse_width(&f->settings.noise[lane])) >> 17; /* |u| / (sqrt(2) sigma), Q.30 */
    if (w < ((uint64_t)1 << 30)) { /* v < 1: curvature u^2 g(v) */
        const int64_t cu = hkf_saturate(((int64_t)f->settings.noise[lane].curvature_q24 * (int64_t)au + (1 << 23)) >> 24);
        const int64_t cu2 = hkf_saturate((cu * (int64_t)au) >> 16);
        return hkf_saturate((cu2 * hkf_g30((uint32_t)((w * w) >> 30))) >> 30);
    } else {
        /* v = (w / 2^30)^2 in Q16.16, >= 1; from 16 on, e^-v (< 1.2e-7) is 0 (exp_neg_q30) */
        const uint64_t w16 = w >> 14;
        const uint32_t e30 = w16 < ((uint64_t)4 << 16) ? exp_neg_q30((hkf_real_t)((w16 * w16) >> 16)) : 0u;
        return hkf_saturate(((int64_t)curve_lambda(&f->settings.noise[lane]) * (int64_t)(((1u << 30) - e30 + 8192u) >> 14) +
                             32768) >> 16);
    }
}

/* exp(-u) in Q16.16 (e^-12 is below half a unit). */
hkf_real_t hkf_exp_neg(hkf_real_t u)
{
    return (hkf_real_t)((exp_neg_q30(u) + 8192u) >> 14);
}

/* The motion adaptation's posterior (hkf_two_models.h), mu' = move / (move + hold) with move = pi r e^min(d, 0)
 * and hold = (1 - pi) e^-max(d, 0), formed in 64 bits with e in Q2.30: where the two models are about even,
 * pi (~ start_rate dt) and e are both small, and a Q16.16 e would keep a few digits (1e-3 is 66 units). */
hkf_real_t hkf_two_models_posterior_q16(hkf_real_t pi, hkf_real_t d, hkf_real_t r)
{
    const uint64_t e = exp_neg_q30(d > 0 ? d : -d);
    const uint64_t p = (uint64_t)(pi > 0 ? (pi < 65536 ? pi : 65536) : 0);
    const uint64_t ratio = (uint64_t)(r > 0 ? (r < (256 << 16) ? r : (256 << 16)) : 0); /* <= 256 */
    uint64_t move = p * ratio, hold = (65536 - p) << 16; /* Q32: <= 2^40, <= 2^32 */
    uint64_t mu = 0;
    int k;
    if (d > 0) {
        hold = (hold * e) >> 30;
    } else {
        move = ((move >> 8) * e) >> 22;
    }
    while (move + hold >= ((uint64_t)1 << 31)) {
        move >>= 1;
        hold >>= 1;
    }
    if (move + hold == 0) {
        return pi;
    }
    hold += move; /* the sum, > 0 and < 2^31; mu' = move / sum, bit by bit (no divide instruction on the M0) */
    for (k = 0; k < 17; ++k) {
        mu <<= 1;
        if (move >= hold) {
            move -= hold;
            mu |= 1u;
        }
        move <<= 1;
    }
    return (hkf_real_t)(mu + (move >= hold)); /* rounded */
}

/* sqrt(x) in Q16.16: the integer root of x 2^16, digit by digit (rounded down). */
hkf_real_t hkf_sqrt(hkf_real_t x)
{
    uint64_t n = (uint64_t)(x > 0 ? x : 0) << 16, root = 0, bit = (uint64_t)1 << 46;
    while (bit > n) {
        bit >>= 2;
    }
    while (bit != 0) {
        if (n >= root + bit) {
            n -= root + bit;
            root = (root >> 1) + bit;
        } else {
            root >>= 1;
        }
        bit >>= 2;
    }
    return (hkf_real_t)root;
}
#else
typedef int hkf_math_fixed_unused_t; /* ISO C: a translation unit is not empty */
#endif

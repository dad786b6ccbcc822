/*
 * hkf_math_fixed.c - the Q16.16 math layer's larger pieces (private; see the
 * range analysis in hkf_math.h): Eq. 8's curve in integers. Out of line so
 * their 64-bit temporaries live in their own stack frame, not in every
 * caller's. Empty in the float and double builds.
 */
#include "hkf_math.h"

#if defined(HKF_REAL_FIXED)
/* g(v) = (1 - e^-v) / v = sum_k (-v)^k / (k+1)! for 0 <= v <= 1, Q2.30 in
 * and out; the series to v^8 is within 2.8e-7 (2^-21.8). */
static uint32_t g30(uint32_t v)
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

/* What Eq. 8 derives from a curve once (floor, curvature, mu and sigma are
 * read from the settings): 1 / (sqrt(2) sigma) in unsigned Q0.32 (sigma >= 1). */
void hkf_curve_prepare(hkf_filter_t *f, int lane, const hkf_noise_curve_t *c)
{
    const uint64_t k = 199032864766430u; /* round(2^48 / sqrt(2)) */
    uint64_t r = 0, q = 0;
    int i;
    for (i = 63; i >= 0; --i) { /* q = k / sigma, once at init */
        r = (r << 1) | ((k >> i) & 1u);
        q <<= 1;
        if (r >= (uint64_t)c->sigma) {
            r -= (uint64_t)c->sigma;
            q |= 1u;
        }
    }
    f->inv_width[lane] = (uint32_t)q;
}

/* Eq. 8 above its floor, u = x - mu: lambda (1 - e^-v), v = u^2 / (2 sigma^2). */
hkf_real_t hkf_curve_rise(const hkf_filter_t *f, int lane, hkf_real_t u)
{
    static const uint32_t exp_neg[24] = { /* e^-k, k = 1..24, unsigned Q0.32 */
        1580030169u, 581260615u, 213833830u, 78665070u, 28939262u, 10646160u, 3916503u, 1440801u,
        530041u,     194991u,    71733u,     26389u,    9708u,     3571u,     1314u,     483u,
        178u,        65u,        24u,        9u,        3u,        1u,        0u,        0u};
    const uint64_t au = (uint64_t)hkf_abs(u);
    const uint64_t w = (au * f->inv_width[lane]) >> 18; /* |u| / (sqrt(2) sigma), Q.30 */
    if (w < ((uint64_t)1 << 30)) { /* v < 1: curvature u^2 g(v) */
        const int64_t cu = hkf_saturate(((int64_t)f->settings->noise[lane].curvature_q24 * (int64_t)au + (1 << 23)) >> 24);
        const int64_t cu2 = hkf_saturate((cu * (int64_t)au) >> 16);
        return hkf_saturate((cu2 * g30((uint32_t)((w * w) >> 30))) >> 30);
    } else {
        const uint64_t w16 = w >> 14;
        uint32_t e30 = 0; /* e^-v, Q2.30 */
        if (w16 < ((uint64_t)5 << 16)) { /* v < 25; beyond, e^-v < 2^-36 */
            const uint32_t v = (uint32_t)((w16 * w16) >> 16);
            const uint32_t frac = (v & 0xFFFFu) << 14; /* Q2.30 */
            const uint32_t e_frac = (1u << 30) - (uint32_t)(((uint64_t)frac * g30(frac)) >> 30);
            e30 = (uint32_t)(((uint64_t)exp_neg[(v >> 16) - 1u] * e_frac) >> 32);
        }
        return hkf_saturate(((int64_t)curve_lambda(&f->settings->noise[lane]) * (int64_t)(((1u << 30) - e30 + 8192u) >> 14) +
                             32768) >> 16);
    }
}
#else
typedef int hkf_math_fixed_unused_t; /* ISO C: a translation unit is not empty */
#endif

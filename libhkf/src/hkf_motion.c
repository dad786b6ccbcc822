/*
 * hkf_motion.c - motion-driven process noise (not in the paper; see q_boost in
 * hkf.h): after each accepted measurement, m follows the normalised
 * innovation's excess over 1. Its own file, so that with q_boost off the
 * update carries none of it (and its frame does not add to hkf_update's on a
 * Cortex-M0).
 */
#include "hkf_internal.h"
#include "hkf_math.h"

/* m += alpha (e - m), alpha = dt / (dt + q_boost_time) in [0, 1],
 * e = y^2 / S - 1 within [0, 10^4]: m stays within [0, 10^4] whatever the
 * input (fuzz_libhkf: a reciprocal of a denormal dt + time overflowed alpha,
 * and m went to -inf). */
void hkf_motion_update(hkf_filter_t *f, const hkf_real_t y[HKF_LANES], const hkf_divisor_t inv_s[HKF_LANES],
                       hkf_real_t dt)
{
    const hkf_real_t most = HKF_REAL(10000.0);
    const hkf_real_t ratio = hkf_divide(dt, hkf_divisor(hkf_add(dt, HKF_SETTINGS(f)->q_boost_time)));
    const hkf_real_t alpha = ratio < HKF_REAL(1.0) ? ratio : HKF_REAL(1.0);
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        const hkf_real_t e = hkf_sub(hkf_divide(hkf_mul(y[a], y[a]), inv_s[a]), HKF_REAL(1.0));
        const hkf_real_t excess = e > 0 ? (e < most ? e : most) : 0;
        f->motion[a] = hkf_add(f->motion[a], hkf_mul(alpha, hkf_sub(excess, f->motion[a])));
    }
}

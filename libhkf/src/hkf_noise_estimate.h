/*
 * hkf_noise_estimate.h - noise calibration, one lane at a time (private):
 * the measured frame-to-frame noise n that scales R, for the angles
 * (hkf_calibration.c, which states it in hkf_calibration.h) and the position
 * (hkf_position.c). Not in the paper.
 */
#ifndef HKF_NOISE_ESTIMATE_H
#define HKF_NOISE_ESTIMATE_H

#include "hkf_internal.h"
#include "hkf_math.h"

/* A low-pass's step weight dt / (dt + time), at most 1: in float the reciprocal of a denormal
 * dt + time overflows (found by fuzz_libhkf), and the weight would be infinite. */
static inline hkf_real_t hkf_step_weight(hkf_real_t dt, hkf_real_t time)
{
    const hkf_real_t ratio = hkf_divide(dt, hkf_divisor(hkf_add(dt, time)));
    return ratio < HKF_REAL(1.0) ? ratio : HKF_REAL(1.0);
}

/* One lane of the noise estimate n (hkf.h), from the second difference d of
 * the raw measurements: power += beta (d^2 / 6 - power) with beta = dt /
 * (dt + noise_time); n = power where that is lower, else n grows by at most
 * the factor rise = 1 + noise_rise dt towards it; n >= *floor (read last). */
static HKF_ALWAYS_INLINE void hkf_noise_lane(hkf_real_t d, hkf_real_t beta, hkf_real_t rise, const hkf_real_t *floor,
                                             hkf_real_t *restrict power, hkf_real_t *restrict n)
{
    const hkf_real_t sample = hkf_mul(hkf_mul(d, d), HKF_REAL(0.16666666666666667));
    const hkf_real_t next = hkf_add(*power, hkf_mul(beta, hkf_sub(sample, *power)));
    const hkf_real_t grown = hkf_mul(*n, rise); /* >= n: so min(grown, power) is power where that is lower */
    const hkf_real_t estimate = grown < next ? grown : next;
    *power = next;
    *n = estimate > *floor ? estimate : *floor;
}

#endif /* HKF_NOISE_ESTIMATE_H */

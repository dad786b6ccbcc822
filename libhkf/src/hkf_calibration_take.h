/*
 * hkf_calibration_take.h - one measurement into the noise calibration (private): the lanes the angles'
 * and the position's hand-overs share (hkf_calibration.c, hkf_position_calibration.c), inlined into each
 * so that the angles' step is what it would be alone. z: the measurement; step: its change from the
 * last (yaw's on the circle); d = step - the last step (hkf_noise_estimate.h: power += beta (d^2 / 6 -
 * power), n towards it, n >= floor).
 */
#ifndef HKF_CALIBRATION_TAKE_H
#define HKF_CALIBRATION_TAKE_H

#include "hkf/hkf_calibration.h"
#include "hkf_internal.h"
#include "hkf_math.h"
#include "hkf_noise_estimate.h"

/* 1 when z is to be taken: the calibration is on and z is a measurement. NULL (a frame without one, or
 * one refused) breaks the second difference. */
static HKF_ALWAYS_INLINE int hkf_calibration_wants(hkf_calibration_t *c, const hkf_real_t *z)
{
    if (z == 0) {
        c->history = 0u;
        return 0;
    }
    return c->settings.noise_time > 0;
}

static HKF_ALWAYS_INLINE void hkf_calibration_take(hkf_calibration_t *c, const hkf_real_t z[3], const hkf_real_t step[HKF_LANES],
                                                   hkf_real_t dt)
{
    int a;
    if (c->history >= 2u) {
        const hkf_real_t beta = hkf_step_weight(dt, c->settings.noise_time);
        const hkf_real_t rise = hkf_add(HKF_REAL(1.0), hkf_mul(c->settings.noise_rise, dt));
        for (a = 0; a < HKF_LOOP_LANES; ++a) {
            hkf_noise_lane(hkf_sub(step[a], c->last_step[a]), beta, rise, &c->floor, &c->power[a], &c->noise[a]);
        }
    }
    for (a = 0; a < HKF_AXES; ++a) {
        c->last_z[a] = z[a];
    }
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        c->last_step[a] = step[a];
    }
    c->history += c->history < 2u ? 1u : 0u;
}

#endif /* HKF_CALIBRATION_TAKE_H */

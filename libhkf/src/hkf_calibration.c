/* hkf_calibration.c - see hkf/hkf_calibration.h. The estimate's lane is hkf_noise_estimate.h's, which the
 * position's own calibration shares. */
#include "hkf/hkf_calibration.h"

#include "hkf_internal.h"
#include "hkf_math.h"
#include "hkf_noise_estimate.h"

const hkf_calibration_settings_t hkf_default_calibration_settings = {
    .noise_time = HKF_REAL(0.3),
    .noise_rise = HKF_REAL(0.2),
};

int hkf_calibration_init(hkf_calibration_t *c, const hkf_calibration_settings_t *s, hkf_filter_t *f)
{
    int a;
    if (c == 0 || s == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!hkf_is_finite(s->noise_time) || !hkf_is_finite(s->noise_rise)) {
        return HKF_ERROR_SETTING_NON_FINITE;
    }
    if (!(s->noise_time >= 0 && s->noise_time <= HKF_REAL_FROM(HKF_MAX_TIME) && s->noise_rise >= 0 &&
          s->noise_rise <= HKF_REAL_FROM(HKF_MAX_NOISE_RISE))) {
        return HKF_ERROR_SETTING_CALIBRATION;
    }
    c->settings = *s;
    c->floor = HKF_SETTINGS(f)->r_min;
    for (a = 0; a < HKF_AXES; ++a) { /* e(mu): the estimator's error on a benchmark */
        c->start[a] = hkf_observation_noise(f, a, HKF_SETTINGS(f)->noise[a].mu);
    }
    return hkf_calibration_reset(c, f);
}

int hkf_calibration_reset(hkf_calibration_t *c, hkf_filter_t *f)
{
    int a;
    if (c == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        c->noise[a] = c->start[a];
        c->power[a] = c->start[a];
        c->last_z[a] = 0;
        c->last_step[a] = 0;
    }
    c->history = 0u;
    return hkf_set_noise(f, c->settings.noise_time > 0 ? c->noise : 0);
}

/* The lanes of the estimate from the raw measurement z: d = (z - z_k-1) - (z_k-1 - z_k-2), yaw's steps on
 * the circle (hkf_noise_estimate.h's lane: power += beta (d^2 / 6 - power), n towards it, n >= floor). */
static void estimate(hkf_calibration_t *c, const hkf_real_t z[3], hkf_real_t dt)
{
    const hkf_real_t now[3] = {z[HKF_AXIS_PITCH], hkf_wrap180(z[HKF_AXIS_YAW]), z[HKF_AXIS_ROLL]}; /* yaw on the circle */
    hkf_real_t step[3];
    int a;
    for (a = 0; a < HKF_AXES; ++a) {
        step[a] = hkf_sub(now[a], c->last_z[a]);
    }
    step[HKF_AXIS_YAW] = hkf_wrap180(step[HKF_AXIS_YAW]);
    if (c->history >= 2u) {
        const hkf_real_t beta = hkf_step_weight(dt, c->settings.noise_time);
        const hkf_real_t rise = hkf_add(HKF_REAL(1.0), hkf_mul(c->settings.noise_rise, dt));
        for (a = 0; a < HKF_AXES; ++a) {
            hkf_noise_lane(hkf_sub(step[a], c->last_step[a]), beta, rise, &c->floor, &c->power[a], &c->noise[a]);
        }
    }
    for (a = 0; a < HKF_AXES; ++a) {
        c->last_z[a] = now[a];
        c->last_step[a] = step[a];
    }
    c->history += c->history < 2u ? 1u : 0u;
}

int hkf_calibration_update(hkf_calibration_t *c, hkf_filter_t *f, const hkf_real_t z[3], hkf_real_t dt)
{
    if (c == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (z == 0) {
        c->history = 0u; /* a missing frame breaks the second difference */
        return HKF_OK;
    }
    if (!(c->settings.noise_time > 0)) {
        return HKF_OK; /* off: f keeps Eq. 8's own R */
    }
    estimate(c, z, dt);
    return hkf_set_noise(f, c->noise);
}

int hkf_calibration_get_noise(const hkf_calibration_t *c, hkf_real_t noise[3])
{
    int a;
    if (c == 0 || noise == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        noise[a] = c->noise[a];
    }
    return HKF_OK;
}

int hkf_calibration_get_state(const hkf_calibration_t *c, hkf_calibration_state_t *state)
{
    int a;
    if (c == 0 || state == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        state->noise[a] = c->noise[a];
        state->power[a] = c->power[a];
    }
    return HKF_OK;
}

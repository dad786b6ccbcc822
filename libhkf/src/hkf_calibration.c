/* hkf_calibration.c - see hkf/hkf_calibration.h: the estimate, and its hand-over to the angle filter
 * (hkf_position_calibration.c hands it to the position's). The estimate's lane is hkf_noise_estimate.h's. */
#include "hkf/hkf_calibration.h"

#include "hkf_internal.h"
#include "hkf_math.h"
#include "hkf_calibration_take.h"

const hkf_calibration_settings_t hkf_default_calibration_settings = {
    .noise_time = HKF_REAL(0.3),
    .noise_rise = HKF_REAL(0.2),
};

int hkf_calibration_begin(hkf_calibration_t *c, const hkf_calibration_settings_t *s, hkf_real_t floor)
{
    if (!hkf_is_finite(s->noise_time) || !hkf_is_finite(s->noise_rise)) {
        return HKF_ERROR_SETTING_NON_FINITE;
    }
    if (!(s->noise_time >= 0 && s->noise_time <= HKF_REAL_FROM(HKF_MAX_TIME) && s->noise_rise >= 0 &&
          s->noise_rise <= HKF_REAL_FROM(HKF_MAX_NOISE_RISE))) {
        return HKF_ERROR_SETTING_CALIBRATION;
    }
    c->settings = *s;
    c->floor = floor;
    return HKF_OK;
}

void hkf_calibration_restart(hkf_calibration_t *c)
{
    int a;
    for (a = 0; a < HKF_LANES; ++a) {
        c->noise[a] = a < HKF_AXES ? c->start[a] : c->floor;
        c->power[a] = c->noise[a];
        c->last_z[a] = 0;
        c->last_step[a] = 0;
    }
    c->history = 0u;
}

int hkf_calibration_init(hkf_calibration_t *c, const hkf_calibration_settings_t *s, hkf_filter_t *f)
{
    int a, result;
    if (c == 0 || s == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = hkf_calibration_begin(c, s, HKF_SETTINGS(f)->r_min);
    if (result != HKF_OK) {
        return result;
    }
    for (a = 0; a < HKF_AXES; ++a) { /* e(mu): the estimator's error on a benchmark */
        c->start[a] = hkf_observation_noise(f, a, HKF_SETTINGS(f)->noise[a].mu);
    }
    return hkf_calibration_reset(c, f);
}

int hkf_calibration_reset(hkf_calibration_t *c, hkf_filter_t *f)
{
    if (c == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    hkf_calibration_restart(c);
    return hkf_set_noise(f, c->settings.noise_time > 0 ? c->noise : 0);
}

/* The angles' steps, yaw's on the circle (the shorter way round, whether z's yaw is wrapped or not). */
static void estimate(hkf_calibration_t *c, const hkf_real_t z[3], hkf_real_t dt)
{
    hkf_real_t step[HKF_LANES];
    int a;
    for (a = 0; a < HKF_AXES; ++a) {
        step[a] = hkf_sub(z[a], c->last_z[a]);
    }
#if HKF_LANES > 3 /* (HKF_AXES is an enum, unseen by the preprocessor) */
    step[3] = 0; /* the idle lane */
#endif
    step[HKF_AXIS_YAW] = hkf_wrap180(step[HKF_AXIS_YAW]);
    hkf_calibration_take(c, z, step, dt);
}

int hkf_calibration_update(hkf_calibration_t *c, hkf_filter_t *f, const hkf_real_t z[3], hkf_real_t dt)
{
    if (c == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!hkf_calibration_wants(c, z)) {
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

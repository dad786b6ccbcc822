/* hkf_position_calibration.c - see hkf/hkf_calibration.h: the noise calibration handed to the
 * position filter (the angles' hand-over is hkf_calibration.c's). A source of its own, so firmware
 * that filters rotation only does not link the position. */
#include "hkf/hkf_calibration.h"
#include "hkf/hkf_position.h"

#include "hkf_calibration_take.h"

int hkf_calibration_init_position(hkf_calibration_t *c, const hkf_calibration_settings_t *s, hkf_position_filter_t *f)
{
    int a, result;
    if (c == 0 || s == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = hkf_calibration_begin(c, s, f->settings.r_min);
    if (result != HKF_OK) {
        return result;
    }
    for (a = 0; a < 3; ++a) { /* n starts at r_const: the followed model's noise */
        c->start[a] = f->settings.r_const[a] > c->floor ? f->settings.r_const[a] : c->floor;
    }
    return hkf_calibration_reset_position(c, f);
}

int hkf_calibration_reset_position(hkf_calibration_t *c, hkf_position_filter_t *f)
{
    if (c == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    hkf_calibration_restart(c);
    return hkf_position_set_noise(f, c->settings.noise_time > 0 ? c->noise : 0);
}

int hkf_calibration_update_position(hkf_calibration_t *c, hkf_position_filter_t *f, const hkf_real_t z[3],
                                    hkf_real_t dt)
{
    hkf_real_t step[HKF_LANES];
    int a;
    if (c == 0 || f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!hkf_calibration_wants(c, z)) {
        return HKF_OK; /* off: f keeps r_const */
    }
    for (a = 0; a < 3; ++a) {
        step[a] = hkf_sub(z[a], c->last_z[a]);
    }
#if HKF_LANES > 3
    step[3] = 0; /* the idle lane */
#endif
    hkf_calibration_take(c, z, step, dt);
    return hkf_position_set_noise(f, c->noise);
}

/* hkf_settings_table.c - see hkf/hkf_settings_table.h. The ranges are hkf.h's and hkf_position.h's limits,
 * the same macros hkf_settings.c and hkf_position.c check against. */
#include "hkf/hkf_settings_table.h"

#include <limits.h>
#include <string.h>

#include "hkf/hkf_rest.h"
#include "hkf_internal.h"
#include "hkf_math.h"

static const char *const noise_modes[] = {"constant", "adaptive", "adaptive_squared"};
static const char *const loop_closures[] = {"off", "norm", "per_axis"};

/* name, field, type, count, unit, min, max, above_min, error, choices, what */
#define ANGLES(name, field, type, count, unit, min, max, above, error, what) \
    {name, offsetof(hkf_settings_t, field), type, count, unit, min, max, above, error, NULL, what}
#define CURVE(name, axis) \
    ANGLES(name, noise[axis], HKF_SETTING_CURVE, 1, "deg", HKF_MIN_SIGMA, HKF_MAX_SIGMA, 0, HKF_ERROR_SETTING_CURVE, \
           "Eq. 8 curve: tau lambda mu sigma")

const hkf_setting_t hkf_settings_table[] = {
    ANGLES("process_noise", process_noise, HKF_SETTING_REAL, 3, "deg^2/s^3", 0, HKF_MAX_PROCESS_NOISE, 0,
           HKF_ERROR_SETTING_PROCESS_NOISE, "q per axis (pitch yaw roll): the moving head's acceleration"),
    {"noise_mode", offsetof(hkf_settings_t, noise_mode), HKF_SETTING_CHOICE, 1, "", 0, 2, 0,
     HKF_ERROR_SETTING_NOISE_MODE, noise_modes, "how R is chosen: constant | adaptive | adaptive_squared"},
    CURVE("noise.pitch", 0),
    CURVE("noise.yaw", 1),
    CURVE("noise.roll", 2),
    ANGLES("r_const", r_const, HKF_SETTING_REAL, 3, "deg^2", 0, HKF_MAX_VARIANCE, 1, HKF_ERROR_SETTING_R_CONST,
           "R per axis in constant mode"),
    ANGLES("r_min", r_min, HKF_SETTING_REAL, 1, "deg^2", HKF_MIN_VARIANCE, HKF_MAX_VARIANCE, 0,
           HKF_ERROR_SETTING_R_RANGE, "lower clamp of R (at most r_max)"),
    ANGLES("r_max", r_max, HKF_SETTING_REAL, 1, "deg^2", HKF_MIN_VARIANCE, HKF_MAX_VARIANCE, 0,
           HKF_ERROR_SETTING_R_RANGE, "upper clamp of R"),
    {"loop_closure", offsetof(hkf_settings_t, loop_closure), HKF_SETTING_CHOICE, 1, "", 0, 2, 0,
     HKF_ERROR_SETTING_LOOP_CLOSURE, loop_closures, "Eq. 9: off | norm | per_axis"},
    ANGLES("lc_xi", lc_xi, HKF_SETTING_REAL, 1, "", 0, 1, 0, HKF_ERROR_SETTING_LC_XI, "loop-closure fusion factor"),
    ANGLES("lc_theta", lc_theta, HKF_SETTING_REAL, 1, "deg", 0, HKF_MAX_LC_THETA, 0, HKF_ERROR_SETTING_LC_THETA,
           "loop-closure threshold"),
    ANGLES("p0_angle", p0_angle, HKF_SETTING_REAL, 1, "deg^2", 0, HKF_MAX_VARIANCE, 1, HKF_ERROR_SETTING_P0,
           "initial angle variance"),
    ANGLES("p0_rate", p0_rate, HKF_SETTING_REAL, 1, "(deg/s)^2", 0, HKF_MAX_VARIANCE, 1, HKF_ERROR_SETTING_P0,
           "initial rate variance, and a move's from rest"),
    ANGLES("gate_sigma", gate_sigma, HKF_SETTING_REAL, 1, "sigmas", 0, HKF_MAX_GATE_SIGMA, 0, HKF_ERROR_SETTING_GATE,
           "innovation gate, 0 = off"),
    ANGLES("max_gate_rejections", max_gate_rejections, HKF_SETTING_UINT, 1, "", 0, UINT_MAX, 0,
           HKF_ERROR_SETTING_GATE, "gated measurements in a row before the track restarts (>= 1 with a gate)"),
    ANGLES("coast_time", coast_time, HKF_SETTING_REAL, 1, "s", 0, HKF_MAX_TIME, 1, HKF_ERROR_SETTING_COAST_TIME,
           "without a face before the track is LOST"),
    ANGLES("max_dt", max_dt, HKF_SETTING_REAL, 1, "s", 0, HKF_MAX_TIME, 1, HKF_ERROR_SETTING_MAX_DT,
           "the longest step; a longer gap restarts the track"),
    ANGLES("still_wander", still_wander, HKF_SETTING_REAL, 1, "deg^2", 0, HKF_MAX_VARIANCE, 0,
           HKF_ERROR_SETTING_MOTION, "motion adaptation: how far a resting head's estimate wanders, beyond R, until a rest is measured"),
    ANGLES("start_rate", start_rate, HKF_SETTING_RATE, 1, "1/s", HKF_MIN_RATE, HKF_MAX_RATE, 0,
           HKF_ERROR_SETTING_MOTION, "motion adaptation: how often a still head starts to move, 0 = off (the paper)"),
    ANGLES("stop_rate", stop_rate, HKF_SETTING_RATE, 1, "1/s", HKF_MIN_RATE, HKF_MAX_RATE, 0,
           HKF_ERROR_SETTING_MOTION, "motion adaptation: how often a moving head stops"),
};
const int hkf_settings_table_count = (int)(sizeof hkf_settings_table / sizeof hkf_settings_table[0]);

const hkf_setting_t hkf_calibration_settings_table[] = {
    {"noise_time", offsetof(hkf_calibration_settings_t, noise_time), HKF_SETTING_REAL, 1, "s", 0, HKF_MAX_TIME, 0,
     HKF_ERROR_SETTING_CALIBRATION, NULL, "noise calibration's time constant, 0 = off (the filter's own R)"},
    {"noise_rise", offsetof(hkf_calibration_settings_t, noise_rise), HKF_SETTING_REAL, 1, "1/s", 0, HKF_MAX_NOISE_RISE,
     0, HKF_ERROR_SETTING_CALIBRATION, NULL, "how fast the noise estimate may rise"},
};
const int hkf_calibration_settings_table_count =
    (int)(sizeof hkf_calibration_settings_table / sizeof hkf_calibration_settings_table[0]);

const hkf_setting_t hkf_rest_settings_table[] = {
    {"rest_time", offsetof(hkf_rest_settings_t, rest_time), HKF_SETTING_REAL, 1, "s", 0, HKF_MAX_TIME, 0,
     HKF_ERROR_SETTING_REST, NULL, "the player's rest: how long it is measured, 0 = off (still_wander stays)"},
    {"rest_reach", offsetof(hkf_rest_settings_t, rest_reach), HKF_SETTING_REAL, 1, "deg", 0, HKF_MAX_LC_THETA, 1,
     HKF_ERROR_SETTING_REST, NULL, "the player's rest: further from its mean than this is a move, which spoils it"},
    {"stillness", offsetof(hkf_rest_settings_t, stillness), HKF_SETTING_REAL, 1, "", 0, HKF_MAX_STILLNESS, 0,
     HKF_ERROR_SETTING_REST, NULL, "how still a resting view is held: a multiple of the wander measured on the rest"},
};
const int hkf_rest_settings_table_count = (int)(sizeof hkf_rest_settings_table / sizeof hkf_rest_settings_table[0]);

#define POSITION(name, type, count, unit, min, max, above, error, what) \
    {#name, offsetof(hkf_position_settings_t, name), type, count, unit, min, max, above, error, NULL, what}

const hkf_setting_t hkf_position_settings_table[] = {
    POSITION(process_noise, HKF_SETTING_REAL, 3, "cm^2/s^3", 0, HKF_MAX_PROCESS_NOISE, 0,
             HKF_ERROR_SETTING_PROCESS_NOISE, "q per axis (x y z): the moving head's white-noise acceleration"),
    POSITION(r_const, HKF_SETTING_REAL, 3, "cm^2", HKF_MIN_VARIANCE, HKF_MAX_VARIANCE, 0, HKF_ERROR_SETTING_R_CONST,
             "R per axis (x y z) of a measurement of scale 1 (the calibration's start)"),
    POSITION(r_min, HKF_SETTING_REAL, 1, "cm^2", HKF_MIN_VARIANCE, HKF_MAX_VARIANCE, 0, HKF_ERROR_SETTING_R_RANGE,
             "R at least this (and the measured noise)"),
    POSITION(r_max, HKF_SETTING_REAL, 1, "cm^2", HKF_MIN_VARIANCE, HKF_MAX_VARIANCE, 0, HKF_ERROR_SETTING_R_RANGE,
             "R at most this"),
    POSITION(p0_rate, HKF_SETTING_REAL, 1, "(cm/s)^2", HKF_MIN_VARIANCE, HKF_MAX_VARIANCE, 0, HKF_ERROR_SETTING_P0,
             "the rate's variance when a track starts, and a move's from rest"),
    POSITION(max_dt, HKF_SETTING_REAL, 1, "s", 0, HKF_MAX_TIME, 1, HKF_ERROR_SETTING_MAX_DT,
             "a longer gap between updates restarts the track"),
    POSITION(still_wander, HKF_SETTING_REAL, 3, "cm^2", 0, HKF_MAX_VARIANCE, 0, HKF_ERROR_SETTING_MOTION,
             "per axis: how far a resting head's measured position wanders, beyond R"),
    POSITION(start_rate, HKF_SETTING_RATE, 1, "1/s", HKF_MIN_RATE, HKF_MAX_RATE, 0, HKF_ERROR_SETTING_MOTION,
             "how often a still head starts to move; 0 = off (MOVE alone)"),
    POSITION(stop_rate, HKF_SETTING_RATE, 1, "1/s", HKF_MIN_RATE, HKF_MAX_RATE, 0, HKF_ERROR_SETTING_MOTION,
             "how often a moving head stops"),
    POSITION(max_speed, HKF_SETTING_REAL, 1, "cm/s", 0, HKF_MAX_SPEED, 0, HKF_ERROR_SETTING_GATE,
             "the outlier gate: farther than this x dt + 3 sigmas is refused, 0 = off"),
    POSITION(max_gate_rejections, HKF_SETTING_UINT, 1, "", 0, UINT_MAX, 0, HKF_ERROR_SETTING_GATE,
             "refused in a row; the next refused one restarts the track (>= 1 with a gate)"),
};
const int hkf_position_settings_table_count =
    (int)(sizeof hkf_position_settings_table / sizeof hkf_position_settings_table[0]);

const hkf_setting_t *hkf_setting_find(const hkf_setting_t *table, int count, const char *name)
{
    int i;
    for (i = 0; table != NULL && name != NULL && i < count; ++i) {
        if (strcmp(table[i].name, name) == 0) {
            return &table[i];
        }
    }
    return NULL;
}

/* One real value against the descriptor's range, compared in the settings' own type as hkf_init compares. */
static int real_in_range(const hkf_setting_t *d, hkf_real_t v)
{
    const hkf_real_t low = HKF_REAL_FROM(d->min), high = HKF_REAL_FROM(d->max);
    if (d->type == HKF_SETTING_RATE && v == 0) {
        return 1;
    }
    return hkf_is_finite(v) && (d->above_min ? v > low : v >= low) && v <= high;
}

int hkf_setting_in_range(const hkf_setting_t *d, const void *value)
{
    const char *at = (const char *)value;
    int i;
    switch (d->type) {
    case HKF_SETTING_UINT: return *(const unsigned *)(const void *)at <= (unsigned)d->max;
    case HKF_SETTING_CHOICE: {
        const int choice = *(const int *)(const void *)at;
        return choice >= 0 && choice <= (int)d->max;
    }
    case HKF_SETTING_CURVE: {
        const hkf_noise_curve_t *c = (const hkf_noise_curve_t *)(const void *)at;
#if defined(HKF_REAL_FIXED)
        return hkf_curve_check(c) == HKF_OK;
#else
        return hkf_is_finite(c->tau) && hkf_is_finite(c->lambda) && hkf_is_finite(c->mu) && hkf_curve_check(c) == HKF_OK;
#endif
    }
    case HKF_SETTING_REAL:
    case HKF_SETTING_RATE:
        for (i = 0; i < d->count; ++i) {
            if (!real_in_range(d, ((const hkf_real_t *)(const void *)at)[i])) {
                return 0;
            }
        }
        return 1;
    }
    return 0;
}

int hkf_setting_is_about(const hkf_setting_t *d, int result)
{
    return result == d->error || (d->type == HKF_SETTING_CURVE && result == HKF_ERROR_SETTING_SIGMA);
}

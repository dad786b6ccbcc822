/*
 * hkf_calibration.h - noise calibration, an optional part beside the angle
 * filter (not in the paper): it measures each axis's frame-to-frame noise n
 * from the raw measurements and hands it to the filter (hkf_set_noise), whose
 * R then follows this camera's noise: R = n e(z) / e(mu), Eq. 8's dependence
 * on the pose at the measured level.
 *
 * The estimate: the second difference d = z_k - 2 z_k-1 + z_k-2 cancels a
 * constant-velocity motion, and E[d^2] = 6 n for white noise; d^2 / 6
 * low-passed with time constant noise_time is the noise power; n follows the
 * power down at once and up by at most the factor (1 + noise_rise dt) a step,
 * so that a head's motion (which raises the power) does not pass for noise.
 * n starts at e(mu), R at the curves' center (the estimator's error on its
 * benchmark), and is at least the filter's r_min.
 *
 * Like Fusion's FusionBias beside its AHRS: a filter without it is the paper's
 * R, and no setting of the filter changes its unit with it. Static memory,
 * float, double or Q16.16 like the rest of libhkf.
 *
 *     hkf_calibration_t c;
 *     hkf_init(&f, &hkf_default_settings);
 *     hkf_calibration_init(&c, &hkf_default_calibration_settings, &f);
 *     each frame with a face:  hkf_update(&f, z, dt, &out);  hkf_calibration_update(&c, &f, z, dt);
 *     each frame without one:  hkf_predict(&f, dt, &out);    hkf_calibration_update(&c, &f, NULL, dt);
 *     after hkf_reset(&f):     hkf_calibration_reset(&c, &f);
 * The position filter takes it the same way (hkf_calibration_init_position and the rest, below).
 */
#ifndef HKF_CALIBRATION_H
#define HKF_CALIBRATION_H

#include "hkf/hkf.h"
#include "hkf/hkf_position.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    hkf_real_t noise_time; /* s: the noise power's low-pass time constant, within [0, HKF_MAX_TIME]; 0 = off (Eq. 8's own R) */
    hkf_real_t noise_rise; /* 1/s: n rises by at most the factor 1 + noise_rise dt a step, within [0, HKF_MAX_NOISE_RISE] */
} hkf_calibration_settings_t;

/* noise_time 0.3 s, noise_rise 0.2 per s: chosen with hkf_default_settings (docs/evaluation.md). */
extern const hkf_calibration_settings_t hkf_default_calibration_settings;

/* Private: members may change between versions. */
typedef struct {
    hkf_calibration_settings_t settings;
    hkf_real_t floor;         /* deg^2: n at least this (the filter's r_min) */
    hkf_real_t start[3];      /* deg^2: n's start, e(mu) of the filter's curves */
    /* per lane: the axes, and the filter's idle fourth lane where it has one (so the step vectorizes) */
    hkf_real_t noise[HKF_LANES];      /* n, deg^2 */
    hkf_real_t power[HKF_LANES];      /* d^2 / 6 low-passed, deg^2 */
    hkf_real_t last_z[HKF_LANES];     /* the last measurement, deg */
    hkf_real_t last_step[HKF_LANES];  /* its step from the one before, deg */
    unsigned history;         /* measurements in a row behind last_z and last_step (0..2) */
} hkf_calibration_t;

/* Checks the settings (HKF_ERROR_SETTING_CALIBRATION, HKF_ERROR_SETTING_NON_FINITE), starts n at e(mu)
 * of f's curves (f: hkf_init'ed, its settings final: call this again after another hkf_init) and hands
 * it to f. */
int hkf_calibration_init(hkf_calibration_t *c, const hkf_calibration_settings_t *s, hkf_filter_t *f);

/* n back to its start, the history forgotten, and handed to f: after hkf_reset(f). */
int hkf_calibration_reset(hkf_calibration_t *c, hkf_filter_t *f);

/* After each successful hkf_update or hkf_predict of f: z the measurement it
 * was given (raw, as given; NULL after hkf_predict: a missing frame breaks the
 * second difference), dt the same step. Updates n and hands it to f, for the
 * next update's R. hkf_update_pair: z, or z2 where z was NULL. */
int hkf_calibration_update(hkf_calibration_t *c, hkf_filter_t *f, const hkf_real_t z[3], hkf_real_t dt);

/* The same for the position filter (hkf_position.h), per axis x, y, z in cm^2: n starts at its
 * r_const (at least r_min, its floor) and is handed over by hkf_position_set_noise, for R = n x a
 * measurement's scale. After each successful hkf_position_update (z, the position given; when the gate
 * refused it, NULL: it broke the track's history) or hkf_position_predict (NULL); the reset after
 * hkf_position_reset or a restart the caller wants to forget the noise over. One calibration object
 * per filter. */
int hkf_calibration_init_position(hkf_calibration_t *c, const hkf_calibration_settings_t *s, hkf_position_filter_t *f);
int hkf_calibration_reset_position(hkf_calibration_t *c, hkf_position_filter_t *f);
int hkf_calibration_update_position(hkf_calibration_t *c, hkf_position_filter_t *f, const hkf_real_t z[3],
                                    hkf_real_t dt);

/* The noise level n per axis, deg^2 (the position's: cm^2). */
int hkf_calibration_get_noise(const hkf_calibration_t *c, hkf_real_t noise[3]);

/* The same with what it follows, for references and diagnostics: n and the low-passed power of
 * the second difference, d^2 / 6 (deg^2), per axis. */
typedef struct {
    hkf_real_t noise[3];
    hkf_real_t power[3];
} hkf_calibration_state_t;
int hkf_calibration_get_state(const hkf_calibration_t *c, hkf_calibration_state_t *state);

#ifdef __cplusplus
}
#endif

#endif /* HKF_CALIBRATION_H */

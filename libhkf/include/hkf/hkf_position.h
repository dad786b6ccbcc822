/*
 * hkf_position.h - the head's position filtered as the angles are: the angles'
 * twin (hkf.h), with the same step, adaptation, calibration and lifecycle.
 *
 * Per axis (x, y, z in cm: camera frame, docs/estimator.md "Head position")
 * the angles' constant-velocity Kalman step (Eq. 1-7) with the motion
 * adaptation (docs/libhkf.md, "The motion adaptation"): HOLD, the head at
 * rest, and MOVE, constant velocity with process noise q, mixed by how well
 * each predicted the measurement. R per axis is r_const, or the noise level n
 * that hkf_position_set_noise gave (hkf_calibration.h measures it), times the
 * measurement's scale (a model that measures position coarsely - from a face
 * box - gives a larger scale), within [r_min, r_max]. No setting changes its
 * unit with the calibration.
 * An outlier gate refuses a measurement farther from the prediction than a
 * head can move in the step (max_speed x dt, plus 3 sigmas of the innovation),
 * after a gap beyond max_dt too (against the track as it was held); after
 * max_gate_rejections in a row that agree with each other the next one
 * restarts the track there.
 * The state stays within +-HKF_MAX_ABS_POSITION on every axis. Between
 * measurements (hkf_position_extrapolate) the position coasts at its rate for
 * up to max_dt, then is stale: held where the coast ended, rate 0, status
 * LOST; its variance grows all the while.
 * Static memory, no allocation; float, double or Q16.16 like the rest of
 * libhkf. Separate from hkf_filter_t: firmware that tracks rotation only
 * does not link it (its size does not change).
 *
 *     hkf_position_filter_t p;
 *     hkf_calibration_t c;                                     // optional (hkf_calibration.h)
 *     if (hkf_position_init(&p, &hkf_position_default_settings) != HKF_OK) ...
 *     hkf_calibration_init_position(&c, &hkf_default_calibration_settings, &p);
 *     each frame with a position:    hkf_position_update(&p, xyz, HKF_REAL(1.0), dt, &out);
 *                                    hkf_calibration_update_position(&c, &p, xyz, dt);
 *     each frame without one:        hkf_position_predict(&p, dt, &out);
 *                                    hkf_calibration_update_position(&c, &p, NULL, dt);
 */
#ifndef HKF_POSITION_H
#define HKF_POSITION_H

#include "hkf/hkf.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { HKF_POSITION_X = 0, HKF_POSITION_Y = 1, HKF_POSITION_Z = 2 };

/* The ranges hkf_position_init and the updates accept (the others are hkf.h's, in cm instead of deg). */
#define HKF_MAX_ABS_POSITION 1000      /* cm: a measurement beyond is refused (HKF_ERROR_POSITION_RANGE) */
#define HKF_MAX_POSITION_SCALE 1000    /* the largest R scale of one measurement */
#define HKF_MAX_SPEED 10000            /* cm/s: the largest max_speed */
#define HKF_POSITION_GATE_SIGMAS 3     /* the gate's allowance for noise, in sigmas of the innovation */

typedef struct {
    hkf_real_t process_noise[3];      /* q per axis, cm^2/s^3: MOVE's white-noise acceleration density */
    hkf_real_t r_const[3];            /* cm^2: R per axis of a measurement of scale 1 (and the calibration's start) */
    hkf_real_t r_min, r_max;          /* cm^2: R within these (r_min: the calibration's floor too) */
    hkf_real_t p0_rate;               /* (cm/s)^2: the rate's variance when a track starts, and a move's from rest */
    hkf_real_t max_dt;                /* s: a longer gap between updates restarts the track; the coast's length */
    /* The motion adaptation, as the angles' (hkf.h): start_rate 0 = off (MOVE alone). */
    hkf_real_t still_wander[3];       /* cm^2 per axis: how far a resting head's measured position wanders, beyond R */
    hkf_real_t start_rate;            /* 1/s: how often a still head starts to move; 0 = off */
    hkf_real_t stop_rate;             /* 1/s: how often a moving head stops */
    /* The outlier gate: a measurement whose innovation on an axis exceeds
     * max_speed x dt + HKF_POSITION_GATE_SIGMAS sqrt(S) is refused; 0: no gate. */
    hkf_real_t max_speed;             /* cm/s */
    unsigned max_gate_rejections;     /* refused in a row; the next refused one restarts the track at it */
} hkf_position_settings_t;

/* Private: members may change between versions (hkf_position_get_state reads them). */
typedef struct {
    hkf_position_settings_t settings;
    hkf_real_t x[3], v[3];            /* cm, cm/s */
    hkf_real_t p00[3], p01[3], p11[3]; /* covariance of (x, v) per axis */
    hkf_real_t moving[3];             /* the motion adaptation's probability of MOVE */
    hkf_real_t noise[3];              /* cm^2: n from hkf_position_set_noise; 0: none (r_const) */
    hkf_real_t center[3];             /* cm: the center position (first measurement, or set) */
    unsigned gate_rejections;         /* measurements the gate refused in a row, each agreeing with the one before */
    hkf_real_t refused_z[3];          /* cm: the last of them */
    int center_source;                /* none, from the first measurement, or set (hkf_position_set_center) */
    hkf_status_t status;              /* what the last call left */
} hkf_position_filter_t;

typedef struct {
    hkf_real_t position[3];  /* cm */
    hkf_real_t rate[3];      /* cm/s */
    hkf_real_t variance[3];  /* cm^2 */
    hkf_status_t status;     /* TRACKING (a measurement), COASTING (up to max_dt after one), LOST (stale) */
    unsigned flags;          /* HKF_FLAG_GATED: the gate refused this measurement */
} hkf_position_output_t;

/* Defaults chosen on truth by construction with the estimator's mesh position
 * (dev/eval/position_truth.py; docs/estimator.md "Head position"). */
extern const hkf_position_settings_t hkf_position_default_settings;

/* Checks the settings (HKF_ERROR_SETTING_*) and clears the track. */
int hkf_position_init(hkf_position_filter_t *f, const hkf_position_settings_t *s);

/* The whole state per axis (x, y, z), for references, logs and diagnostics: the position and its
 * rate, their covariance P = [p00 p01; p01 p11], the center, the noise level R is scaled from (n
 * from hkf_position_set_noise, else r_const) and the motion adaptation's probability of MOVE (1 with
 * start_rate 0). As the last call left it; 0 before the first track. */
typedef struct {
    hkf_real_t position[3], rate[3];      /* cm, cm/s */
    hkf_real_t p00[3], p01[3], p11[3];    /* cm^2, cm^2/s, (cm/s)^2 */
    hkf_real_t center[3];                 /* cm */
    hkf_real_t noise[3];                  /* cm^2 */
    hkf_real_t moving[3];
} hkf_position_state_t;
int hkf_position_get_state(const hkf_position_filter_t *f, hkf_position_state_t *state);

/* Forgets the track (and a center not set by hkf_position_set_center); keeps the settings and the
 * noise level hkf_position_set_noise gave. As hkf_reset. */
void hkf_position_reset(hkf_position_filter_t *f);

/* Forgets the track but keeps the center, however it was set (a new clock, a change of estimator). */
void hkf_position_restart(hkf_position_filter_t *f);

/* Predicts by dt (s) and takes the measurement z (cm) with R = r_scale x the
 * axis's R (r_const or n), within [r_min, r_max]. The first measurement
 * (which ignores dt), or one after a gap beyond max_dt, starts the track there
 * (and sets the center if none is set); dt <= 0 after the first is refused
 * (HKF_ERROR_DT_RANGE), as hkf_update refuses it. A measurement the gate
 * refuses leaves the prediction and sets HKF_FLAG_GATED (HKF_OK). On error the
 * filter is untouched. */
int hkf_position_update(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt,
                        hkf_position_output_t *out);

/* 1 when a measurement has started the track (and no reset or restart has forgotten it since); 0 for NULL. */
int hkf_position_started(const hkf_position_filter_t *f);

/* The track's status as the last call left it: UNINITIALIZED before a track, TRACKING after a
 * measurement taken, COASTING after a prediction or a refused one (HKF_STATUS_UNINITIALIZED for NULL). */
hkf_status_t hkf_position_get_status(const hkf_position_filter_t *f);

/* Predicts by dt (s) without a measurement (MOVE's prediction, Eq. 1-3). */
int hkf_position_predict(hkf_position_filter_t *f, hkf_real_t dt, hkf_position_output_t *out);

/* The position `ahead` s (>= 0) after the last step, without changing the
 * filter: moved on by the rate for up to max_dt (COASTING; TRACKING at 0),
 * beyond that held where the coast ended with rate 0 (LOST); the variance
 * grows with ahead (up to HKF_MAX_TIME, capped at HKF_MAX_VARIANCE). */
int hkf_position_extrapolate(const hkf_position_filter_t *f, hkf_real_t ahead, hkf_position_output_t *out);

/* The measured noise level n per axis (cm^2; hkf_calibration.h measures it): from the next update
 * on, R = n x the measurement's scale, within [r_min, r_max]. NULL: back to r_const. A reset or
 * restart keeps it. HKF_ERROR_NON_FINITE or HKF_ERROR_NOISE_RANGE (n <= 0) change nothing. */
int hkf_position_set_noise(hkf_position_filter_t *f, const hkf_real_t noise[3]);

/* The center := the current position (a recenter; with the angles', hkf_recenter). */
int hkf_position_recenter(hkf_position_filter_t *f);

/* The center := the position hkf_position_extrapolate gives `ahead` s on (what was published then). */
int hkf_position_recenter_at(hkf_position_filter_t *f, hkf_real_t ahead);

/* The center := center (cm, each axis finite and within +-HKF_MAX_ABS_POSITION), as a program
 * published it (e.g. bounded to its own range); kept by a reset and a restart (hkf_set_center's
 * rule). HKF_ERROR_NON_FINITE or HKF_ERROR_POSITION_RANGE leave the center as it was. */
int hkf_position_set_center(hkf_position_filter_t *f, const hkf_real_t center[3]);

/* The center (cm): HKF_ERROR_NOT_INITIALIZED while none is set (no track has started, none was set). */
int hkf_position_get_center(const hkf_position_filter_t *f, hkf_real_t center[3]);

#ifdef __cplusplus
}
#endif

#endif /* HKF_POSITION_H */

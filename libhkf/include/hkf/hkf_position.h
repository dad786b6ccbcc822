/*
 * hkf_position.h - the head's position filtered as the angles are.
 *
 * Per axis (x, y, z in cm: camera frame, docs/estimator.md "Head position") a
 * constant-velocity Kalman filter with the same closed-form 2x2 step as the
 * angles: state (position, rate), white-acceleration process noise q, and an
 * observation noise R of its own per axis, scaled per measurement (a model
 * that measures position coarsely - from a face box - gives a larger scale).
 * With noise calibration on (noise_time > 0, the default) the filter works
 * as the angles' calibrated one (hkf.h): it measures each axis's noise n from
 * the measurements' second differences, R = n x the measurement's scale and
 * q = process_noise n; a motion detector gives the position a random walk
 * while the head moves and damps the rate while it is still - a still head
 * reads still and a lean is followed without the lag one fixed q would need.
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
 *     if (hkf_position_init(&p, &hkf_position_default_settings) != HKF_OK) ...
 *     hkf_position_update(&p, xyz, HKF_REAL(1.0), dt, &out);   // each frame with a position
 *     hkf_position_predict(&p, dt, &out);                      // a frame without one
 */
#ifndef HKF_POSITION_H
#define HKF_POSITION_H

#include "hkf/hkf.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { HKF_POSITION_X = 0, HKF_POSITION_Y = 1, HKF_POSITION_Z = 2 };

/* The ranges hkf_position_init and the updates accept. */
#define HKF_MAX_ABS_POSITION 1000      /* cm: a measurement beyond is refused (HKF_ERROR_POSITION_RANGE) */
#define HKF_MAX_POSITION_SCALE 1000    /* the largest R scale of one measurement */
#define HKF_MAX_SPEED 10000            /* cm/s: the largest max_speed */
#define HKF_POSITION_GATE_SIGMAS 3     /* the gate's allowance for noise, in sigmas of the innovation */
/* The position's motion detector (its settings below; the angles have the motion adaptation of hkf.h). */
#define HKF_MAX_MOTION_THRESHOLD 10000 /* motion_threshold, still_threshold */
#define HKF_MAX_Q_BOOST 16384          /* q_boost, 1/s */
/* The detector's walk and the calibrated q are at most this: the same in every build (fixed point's range). */
#define HKF_MAX_BOOSTED_PROCESS_NOISE 16384 /* cm^2/s^3 */

typedef struct {
    hkf_real_t process_noise[3];      /* q per axis: cm^2/s^3; calibrated: x n, 1/s^3 */
    hkf_real_t measurement_noise[3];  /* cm^2: R per axis for a measurement of scale 1; calibrated: n's start */
    hkf_real_t p0_rate;               /* (cm/s)^2: the rate's variance when a track starts */
    hkf_real_t max_dt;                /* s: a longer gap between updates restarts the track */
    /* Noise calibration and the motion detector, as the angles' (hkf.h,
     * hkf_settings_t: the same names, units per cm instead of per deg);
     * noise_time 0: constant R and q, no detector. */
    hkf_real_t noise_time;            /* s */
    hkf_real_t noise_rise;            /* 1/s */
    hkf_real_t noise_floor;           /* cm^2: n at least this */
    hkf_real_t q_boost;               /* 1/s; 0: no walk while moving */
    hkf_real_t q_boost_time;          /* s */
    hkf_real_t motion_threshold;
    hkf_real_t rate_damping_time;     /* s; 0: the rate never decays */
    hkf_real_t still_threshold;
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
    hkf_real_t center[3];             /* cm: the center position (first measurement, or hkf_position_recenter) */
    hkf_real_t noise[3];              /* cm^2: calibrated, the measured noise n per axis */
    hkf_real_t noise_power[3];        /* cm^2: the low-passed d^2 / 6 n follows */
    hkf_real_t motion[3];             /* cm: the detector's low-passed innovation */
    hkf_real_t last_z[3], last_step[3]; /* cm: the second difference's history */
    hkf_real_t last_dt;               /* s: the step before (equal steps make a second difference) */
    int history;                      /* measurements in the history, 0-2 */
    unsigned gate_rejections;         /* measurements the gate refused in a row, each agreeing with the one before */
    hkf_real_t refused_z[3];          /* cm: the last of them */
    int started;                      /* a measurement has started the track */
    int centered;                     /* the center is set (a restart keeps it; a reset clears it) */
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
 * rate, their covariance P = [p00 p01; p01 p11], the center and the measured noise n (calibrated;
 * else the measurement_noise setting's). As the last call left it; 0 before the first track. */
typedef struct {
    hkf_real_t position[3], rate[3];      /* cm, cm/s */
    hkf_real_t p00[3], p01[3], p11[3];    /* cm^2, cm^2/s, (cm/s)^2 */
    hkf_real_t center[3];                 /* cm */
    hkf_real_t noise[3];                  /* cm^2 */
} hkf_position_state_t;
int hkf_position_get_state(const hkf_position_filter_t *f, hkf_position_state_t *state);

/* Forgets the track, the center and the measured noise; the next measurement starts anew. */
void hkf_position_reset(hkf_position_filter_t *f);

/* Forgets the track but keeps the center and the measured noise (a new clock, a change of estimator). */
void hkf_position_restart(hkf_position_filter_t *f);

/* Predicts by dt (s) and takes the measurement z (cm) with R = r_scale x the
 * setting's R. The first measurement (which ignores dt), or one after a gap
 * beyond max_dt, starts the track there (and sets the center if none is set);
 * dt <= 0 after the first is refused (HKF_ERROR_DT_RANGE), as hkf_update
 * refuses it. A measurement the gate refuses leaves the prediction and sets
 * HKF_FLAG_GATED (HKF_OK). On error the filter is untouched. */
int hkf_position_update(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt,
                        hkf_position_output_t *out);

/* 1 when a measurement has started the track (and no reset has forgotten it since); 0 for NULL. */
int hkf_position_started(const hkf_position_filter_t *f);

/* Predicts by dt (s) without a measurement (the noise's history restarts). */
int hkf_position_predict(hkf_position_filter_t *f, hkf_real_t dt, hkf_position_output_t *out);

/* The position `ahead` s (>= 0) after the last step, without changing the
 * filter: moved on by the rate for up to max_dt (COASTING; TRACKING at 0),
 * beyond that held where the coast ended with rate 0 (LOST); the variance
 * grows with ahead (up to HKF_MAX_TIME, capped at HKF_MAX_VARIANCE). */
int hkf_position_extrapolate(const hkf_position_filter_t *f, hkf_real_t ahead, hkf_position_output_t *out);

/* The center := the current position (a recenter; with the angles', hkf_recenter). */
int hkf_position_recenter(hkf_position_filter_t *f);

/* The center := the position hkf_position_extrapolate gives `ahead` s on (what was published then). */
int hkf_position_recenter_at(hkf_position_filter_t *f, hkf_real_t ahead);

/* The center := center (cm, each axis finite and within +-HKF_MAX_ABS_POSITION), as a program
 * published it (e.g. bounded to its own range); kept by a restart, forgotten by a reset.
 * HKF_ERROR_NON_FINITE or HKF_ERROR_POSITION_RANGE leave the center as it was. */
int hkf_position_set_center(hkf_position_filter_t *f, const hkf_real_t center[3]);

#ifdef __cplusplus
}
#endif

#endif /* HKF_POSITION_H */

/*
 * hkf.h - libhkf, the adaptive Kalman filter of the marker-free head tracker.
 *
 * Implements "A Marker-free Head Tracker Using Vision-based Head Pose
 * Estimation with Adaptive Kalman Filter" (Hu, Lv et al.): a constant-velocity
 * Kalman filter over head (pitch, yaw, roll) whose observation noise R follows
 * an inverted Gaussian of the measured angle (Eq. 8), with a "loop closure"
 * that pulls measurements near the driver's center pose onto it (Eq. 9).
 *
 * Pure C99, no malloc, no stdio, no mutable globals. The caller owns the
 * hkf_filter_t; all its members are private. Units: degrees and seconds.
 * Every array of three is in the paper's axis order: pitch, yaw, roll.
 *
 *     hkf_filter_t f;
 *     if (hkf_init(&f, &hkf_default_settings) != HKF_OK) ...
 *     each frame with a face:  hkf_update(&f, z, dt, &out);
 *     each frame without one:  hkf_predict(&f, dt, &out);
 *     between frames:          hkf_extrapolate(&f, dt_ahead, &out);
 *
 * dt is always the time since the previous hkf_update or hkf_predict call.
 */
#ifndef HKF_H
#define HKF_H

#include "hkf_real.h"

#ifdef __cplusplus
extern "C" {
#endif

enum { HKF_AXIS_PITCH = 0, HKF_AXIS_YAW = 1, HKF_AXIS_ROLL = 2, HKF_AXES = 3 };

/* Every function that can fail returns one of these: 0 = OK, < 0 = error. */
typedef enum {
    HKF_OK = 0,
    HKF_ERROR_NULL_ARGUMENT = -1,      /* a pointer argument is NULL */
    HKF_ERROR_NON_FINITE = -2,         /* a measurement or dt is NaN or infinite */
    HKF_ERROR_DT_RANGE = -3,           /* dt <= 0 or dt > settings.max_dt */
    HKF_ERROR_ANGLE_RANGE = -4,        /* |angle| > HKF_MAX_ABS_ANGLE */
    HKF_ERROR_NOT_INITIALIZED = -5,    /* no measurement has started a track yet */
    HKF_ERROR_POSITION_RANGE = -6,     /* a position beyond +-HKF_MAX_ABS_POSITION cm (hkf_position.h) */
    HKF_ERROR_SCALE_RANGE = -7,        /* a position's R scale outside [1, HKF_MAX_POSITION_SCALE] (hkf_position.h) */
    HKF_ERROR_NOISE_RANGE = -8,        /* hkf_set_noise: a noise level n <= 0 */
    /* hkf_init: settings that make no sense */
    HKF_ERROR_SETTING_NON_FINITE = -20,  /* a setting is NaN or infinite */
    HKF_ERROR_SETTING_NOISE_MODE = -21,  /* noise_mode is not a hkf_noise_mode_t */
    HKF_ERROR_SETTING_SIGMA = -22,       /* a noise curve's sigma outside [HKF_MIN_SIGMA, HKF_MAX_SIGMA] */
    HKF_ERROR_SETTING_R_RANGE = -23,     /* not HKF_MIN_VARIANCE <= r_min <= r_max <= HKF_MAX_VARIANCE */
    HKF_ERROR_SETTING_R_CONST = -24,     /* an r_const outside (0, HKF_MAX_VARIANCE] */
    HKF_ERROR_SETTING_PROCESS_NOISE = -25, /* a process_noise outside [0, HKF_MAX_PROCESS_NOISE] */
    HKF_ERROR_SETTING_LOOP_CLOSURE = -26,  /* loop_closure not a hkf_loop_closure_t */
    HKF_ERROR_SETTING_LC_XI = -27,       /* not 0 <= lc_xi <= 1 */
    HKF_ERROR_SETTING_LC_THETA = -28,    /* lc_theta outside [0, HKF_MAX_LC_THETA] */
    HKF_ERROR_SETTING_P0 = -29,          /* p0_angle or p0_rate outside (0, HKF_MAX_VARIANCE] */
    HKF_ERROR_SETTING_GATE = -30,        /* gate_sigma outside [0, HKF_MAX_GATE_SIGMA], or gate on with max_gate_rejections 0 */
    HKF_ERROR_SETTING_COAST_TIME = -31,  /* coast_time outside (0, HKF_MAX_TIME] */
    HKF_ERROR_SETTING_MAX_DT = -32,      /* max_dt outside (0, HKF_MAX_TIME] */
    HKF_ERROR_SETTING_CURVE = -33,       /* a noise curve's |tau| or |lambda| > HKF_MAX_VARIANCE, or |mu| > HKF_MAX_ABS_ANGLE */
    HKF_ERROR_SETTING_MOTION = -34,      /* still_wander outside [0, HKF_MAX_VARIANCE], start_rate or stop_rate
                                            neither 0 nor in [HKF_MIN_RATE, HKF_MAX_RATE] (the position's too) */
    HKF_ERROR_SETTING_CALIBRATION = -35, /* noise_time outside [0, HKF_MAX_TIME] or noise_rise outside
                                            [0, HKF_MAX_NOISE_RISE] (hkf_calibration.h) */
    HKF_ERROR_SETTING_REST = -36         /* rest_time outside [0, HKF_MAX_TIME], rest_reach outside (0, HKF_MAX_LC_THETA]
                                            or stillness outside [0, HKF_MAX_STILLNESS] (hkf_rest.h) */
} hkf_result_t;

/* A short English description of a hkf_result_t, for logs. Never NULL. */
const char *hkf_result_string(int result);

/* The ranges hkf_init accepts. Beyond them no head tracker has a use for a
 * setting, and within them every intermediate of the filter stays finite and
 * every variance positive and below 1e12 (tests/fuzz/fuzz_libhkf.c checks it).
 * The fixed-point build accepts narrower ranges, inside Q16.16 (+-32768):
 * variances up to 16384 deg^2 (a 128 deg standard deviation), curves at
 * least 1 deg wide, the loop-closure threshold and the gate up to 180. */
#if defined(HKF_REAL_FIXED)
#define HKF_MIN_VARIANCE 1e-4    /* deg^2: r_min (6.5 units of Q16.16) */
#define HKF_MAX_VARIANCE 16384   /* deg^2, (deg/s)^2: r_max, r_const, p0 */
#define HKF_MAX_PROCESS_NOISE 16384 /* deg^2/s^3 */
#define HKF_MIN_SIGMA 1          /* deg */
#define HKF_MAX_SIGMA 16384      /* deg */
#define HKF_MAX_CURVE_FLOOR 1024 /* deg: |floor| of a noise curve */
#define HKF_MAX_CURVATURE 127    /* deg/deg^2: |curvature| of a noise curve (Q8.24) */
#define HKF_MAX_LC_THETA 180     /* deg */
#define HKF_MAX_GATE_SIGMA 180
#else
#define HKF_MIN_VARIANCE 1e-6    /* deg^2: r_min */
#define HKF_MAX_VARIANCE 1e8     /* deg^2, (deg/s)^2: r_max, r_const, p0; deg: |tau|, |lambda| */
#define HKF_MAX_PROCESS_NOISE 1e6 /* deg^2/s^3 */
#define HKF_MIN_SIGMA 1e-3       /* deg */
#define HKF_MAX_SIGMA 1e4        /* deg */
#define HKF_MAX_LC_THETA 360     /* deg */
#define HKF_MAX_GATE_SIGMA 1000
#endif
#define HKF_MAX_TIME 10          /* s: max_dt, coast_time, noise_time */
#define HKF_MAX_NOISE_RISE 100   /* 1/s: noise_rise */
#define HKF_MIN_RATE 1e-3        /* 1/s: start_rate, stop_rate other than 0 (a denormal rate made the prior's 1/rate infinite) */
#define HKF_MAX_RATE 1000        /* 1/s: start_rate, stop_rate */

/* Measurements beyond this magnitude are rejected (HKF_ERROR_ANGLE_RANGE):
 * no head pose is that large, and it keeps every value inside the range of
 * a Q16.16 fixed-point build. */
#define HKF_MAX_ABS_ANGLE 3600

/* Paper Eq. 8, amplitude form: e(x) = tau - lambda * exp(-(x - mu)^2 / (2 sigma^2)).
 * Write curves with HKF_NOISE_CURVE(tau, lambda, mu, sigma), which suits
 * every build. */
#if defined(HKF_REAL_FIXED)
/* Fixed point: Table I's roll curves have tau and lambda ~ 1e5, beyond
 * Q16.16, so a curve is held as its floor and curvature, which fit:
 *   e(x) = floor + curvature 2 sigma^2 (1 - exp(-(x - mu)^2 / (2 sigma^2)))
 * i.e. floor = tau - lambda, curvature = lambda / (2 sigma^2): the same curve.
 * The curvature (FSA-Net yaw: 0.0022) is held in Q8.24 so it keeps 5 digits. */
typedef struct {
    hkf_real_t floor;      /* deg: the error at mu (tau - lambda) */
    int32_t curvature_q24; /* deg/deg^2 in Q8.24: e(mu + u) ~ floor + curvature u^2 near mu */
    hkf_real_t mu;         /* deg: the angle of least error */
    hkf_real_t sigma;      /* deg: the width of the dip, > 0 */
} hkf_noise_curve_t;
#define HKF_NOISE_CURVE(tau, lambda, mu, sigma)                                                         \
    {HKF_REAL_FROM((tau) - (lambda)), (int32_t)((lambda) / (2.0 * (sigma) * (sigma)) * 16777216.0 + 0.5), \
     HKF_REAL(mu), HKF_REAL(sigma)}
#else
typedef struct {
    hkf_real_t tau;     /* deg: the error far from mu */
    hkf_real_t lambda;  /* deg: the depth of the dip; tau - lambda is the error at mu */
    hkf_real_t mu;      /* deg: the angle of least error */
    hkf_real_t sigma;   /* deg: the width of the dip, > 0 */
} hkf_noise_curve_t;
#define HKF_NOISE_CURVE(tau, lambda, mu, sigma) {HKF_REAL(tau), HKF_REAL(lambda), HKF_REAL(mu), HKF_REAL(sigma)}
#endif

typedef enum {
    HKF_NOISE_CONSTANT = 0,        /* R = r_const: the paper's "standard KF" baseline */
    HKF_NOISE_ADAPTIVE = 1,        /* R = e(z): the paper */
    HKF_NOISE_ADAPTIVE_SQUARED = 2 /* R = e(z)^2: e read as a standard deviation */
} hkf_noise_mode_t;

typedef enum {
    HKF_LOOP_CLOSURE_OFF = 0,
    HKF_LOOP_CLOSURE_NORM = 1,    /* the paper: |z - center| over the three axes <= lc_theta */
    HKF_LOOP_CLOSURE_PER_AXIS = 2 /* each axis on its own: |z_a - center_a| <= lc_theta */
} hkf_loop_closure_t;

typedef struct {
    hkf_real_t process_noise[3];   /* q per axis, deg^2/s^3: white-noise acceleration density (the moving head's) */
    hkf_noise_mode_t noise_mode;   /* how R is chosen */
    hkf_noise_curve_t noise[3];    /* e(x) per axis, deg */
    hkf_real_t r_const[3];         /* R per axis in HKF_NOISE_CONSTANT mode, deg^2 */
    hkf_real_t r_min, r_max;       /* clamp of R in every mode, deg^2 */
    int loop_closure;              /* a hkf_loop_closure_t; 0 = off, 1 = on (vector norm) */
    hkf_real_t lc_xi;              /* fusion factor xi of Eq. 9, 0..1 */
    hkf_real_t lc_theta;           /* loop-closure threshold, deg */
    hkf_real_t p0_angle, p0_rate;  /* initial variances: deg^2, (deg/s)^2 (p0_rate also a move's from rest) */
    hkf_real_t gate_sigma;         /* innovation gate, in sigmas; 0 = off */
    unsigned max_gate_rejections;  /* gated measurements in a row; the next gated one restarts the track */
    hkf_real_t coast_time;         /* s without a measurement before the track is LOST */
    hkf_real_t max_dt;             /* s; a larger dt is rejected */
    /* The motion adaptation (not in the paper; start_rate 0 = off, the paper's
     * filter). Two models of each axis's motion over a step, mixed by how well
     * each predicted the measurement (libhkf/src/hkf_two_models.h; docs/libhkf.md):
     * HOLD, the head at rest (the angle holds, the rate is 0; a measurement
     * wanders about the rest by still_wander beyond R, and a move that starts
     * from rest has a rate of variance p0_rate), and MOVE, the paper's
     * constant velocity with process_noise. A still head starts to move at
     * start_rate per s, a moving one stops at stop_rate per s. still_wander is
     * the wander before one is measured (hkf_set_wander; hkf_rest.h). */
    hkf_real_t still_wander;       /* deg^2: how far a resting head's estimate wanders, beyond R */
    hkf_real_t start_rate;         /* 1/s: how often a still head starts to move; 0 = off */
    hkf_real_t stop_rate;          /* 1/s: how often a moving head stops */
} hkf_settings_t;

/* The defaults: the paper's adaptive R (Eq. 8, FSA-Net curves of Table I),
 * the motion adaptation (process_noise 16000 deg^2/s^3 while moving,
 * still_wander 0.03 deg^2 until a rest is measured (hkf_rest.h), start_rate 0.05 per s, stop_rate 16 per s), loop
 * closure off, gate off; chosen on truth by construction and on real clips
 * (docs/evaluation.md) together with the noise calibration
 * (hkf_calibration.h, hkf_default_calibration_settings), which hkf-filter runs
 * beside them. */
extern const hkf_settings_t hkf_default_settings;
/* The paper's filter alone: adaptive R, loop closure (xi 0.618, theta 2 deg),
 * q 500 / 1000 / 500 deg^2/s^3, no calibration or motion adaptation. */
extern const hkf_settings_t hkf_paper_settings;

/* Noise curves of the paper's Table I, per axis (pitch, yaw, roll). Table I
 * prints roll to three significant digits, which loses tau - lambda (the
 * error at the center); these presets set the roll center error to that
 * model's pitch center error (3.36 deg FSA-Net, 3.70 deg Hopenet). */
extern const hkf_noise_curve_t hkf_noise_fsanet[3];
extern const hkf_noise_curve_t hkf_noise_hopenet[3];

/* Noise curves of the estimators hkf ships, fitted on AFLW2000 as Table I was
 * (hkf_estimator_curves.c): hkf-estimator's face mesh (model "mesh_pnp") and
 * WHENet (model "whenet"). */
extern const hkf_noise_curve_t hkf_noise_mesh_pnp[3];
extern const hkf_noise_curve_t hkf_noise_whenet[3];

typedef enum {
    HKF_STATUS_UNINITIALIZED = 0, /* no measurement yet */
    HKF_STATUS_TRACKING = 1,      /* the last call was a measurement update */
    HKF_STATUS_COASTING = 2,      /* no measurement for less than coast_time: predicting */
    HKF_STATUS_LOST = 3           /* no measurement for coast_time: rate zeroed, angle held */
} hkf_status_t;

/* Bits of hkf_output_t.flags: what happened in this call. */
#define HKF_FLAG_LOOP_CLOSURE 0x1u  /* Eq. 9 moved the measurement onto the center */
#define HKF_FLAG_GATED        0x2u  /* the innovation gate rejected the measurement */
#define HKF_FLAG_REACQUIRED   0x4u  /* the track (re)started from this measurement */
#define HKF_FLAG_EXTRAPOLATED 0x8u  /* hkf_extrapolate: a prediction, not a posterior */

typedef struct {
    hkf_real_t angle[3];     /* deg; yaw in [-180, 180) */
    hkf_real_t rate[3];      /* deg/s */
    hkf_real_t variance[3];  /* deg^2: the angle's variance */
    hkf_real_t r[3];         /* deg^2: R of the last measurement update */
    unsigned flags;          /* HKF_FLAG_* */
    hkf_status_t status;
} hkf_output_t;

/* Private: members may change between versions. Sized statically so callers
 * can place it anywhere (stack, static storage, a controller's RAM).
 * Per-axis arrays of the float and double builds have a fourth, idle lane
 * so the axis loops vectorize; the fixed-point build (scalar cores) has none. */
#if defined(HKF_REAL_FIXED)
#define HKF_LANES 3
#else
#define HKF_LANES 4
#endif
typedef struct {
    hkf_settings_t settings;            /* hkf_init's copy */
#if !defined(HKF_REAL_FIXED) /* (the fixed-point build reads its curves from the copy: RAM before time) */
    /* per-lane copies of the settings the axis loops read */
    hkf_real_t q[HKF_LANES], r_const[HKF_LANES];
    hkf_real_t mu[HKF_LANES], lambda[HKF_LANES];
    hkf_real_t noise_floor[HKF_LANES];  /* tau - lambda */
    hkf_real_t gauss_scale[HKF_LANES];  /* 1 / (2 sigma^2) */
#endif
    hkf_real_t angle[HKF_LANES], rate[HKF_LANES];
    hkf_real_t p00[HKF_LANES], p01[HKF_LANES], p11[HKF_LANES];
    hkf_real_t r[HKF_LANES];
    hkf_real_t center[HKF_LANES];
    hkf_real_t moving[HKF_LANES];       /* the motion adaptation's probability of MOVE */
    hkf_real_t noise[HKF_LANES];        /* n from hkf_set_noise, deg^2; 0: none (Eq. 8's own R) */
#if !defined(HKF_REAL_FIXED)
    hkf_real_t r_center[HKF_LANES];     /* e(mu), R at the curves' center, as hkf_math.h's divisor (fixed point: each step's) */
#endif
    hkf_real_t time_since_measurement;
    unsigned gate_rejections;
    int center_source;           /* none, from the first measurement, or explicit */
    hkf_status_t status;
} hkf_filter_t;

/* Validates the settings and starts an empty filter (no track yet). Every
 * build copies *s: it may be a temporary, and changing it later changes
 * nothing (to change the settings, call hkf_init again). */
int hkf_init(hkf_filter_t *f, const hkf_settings_t *s);

/* Forgets the track (and a center not set by hkf_set_center); keeps the
 * settings and the noise level hkf_set_noise gave. */
void hkf_reset(hkf_filter_t *f);

/* One measurement z (deg) taken dt s after the previous call: predict, loop
 * closure, adaptive R, update. The first measurement starts the track and
 * ignores dt. Writes the posterior to out (which may be NULL). On error the
 * filter is untouched. */
int hkf_update(hkf_filter_t *f, const hkf_real_t z[3], hkf_real_t dt, hkf_output_t *out);

/* How one estimator model's R is chosen: its mode, Eq. 8 curves, constant R
 * and clamp (the members of hkf_settings_t of the same names). What
 * hkf_update_pair takes of a second model; hkf_model_noise_of picks it out of
 * a settings set. */
typedef struct {
    hkf_noise_mode_t noise_mode;
    hkf_noise_curve_t noise[3];    /* deg */
    hkf_real_t r_const[3];         /* deg^2 */
    hkf_real_t r_min, r_max;       /* deg^2 */
} hkf_model_noise_t;

hkf_model_noise_t hkf_model_noise_of(const hkf_settings_t *s);

/* Two measurements of the same frame from two estimators whose errors are
 * independent (e.g. a face mesh and an angle-regression network): z with the
 * filter's own R, z2 with the R that `second` gives at z2's angles (Eq. 8).
 * One predict, then z as hkf_update takes it, then z2 as a sequential scalar
 * update (loop closure and gate as for z): for independent noise the same
 * posterior as one update with both stacked (H = [I; I], R = diag(R1, R2)).
 * The motion adaptation weighs its two models by z alone; z2 then corrects
 * the merged state. out->r is the R of both, R1 R2 / (R1 + R2) (or of the
 * one accepted); HKF_FLAG_GATED: one of them was gated. On error (including
 * a bad `second`, checked as hkf_init checks those settings) the filter is
 * untouched. Either z or z2 may be NULL (that model found no face this
 * frame, or has not run on it): then the other alone is taken, as hkf_update
 * takes it but with its own model's R (and the adaptation weighs by it).
 * Both NULL: an error. Prepares `second` on every call, in a filter-sized temporary on the stack
 * (hkf_update_pair_prepared takes it prepared once). */
int hkf_update_pair(hkf_filter_t *f, const hkf_real_t z[3], const hkf_real_t z2[3], const hkf_model_noise_t *second,
                    hkf_real_t dt, hkf_output_t *out);

/* A second model's noise prepared once, for hkf_update_pair_prepared (init once, process many, as
 * CMSIS-DSP's filters do): hkf_update_pair prepares and checks `second` on every call, about half of
 * its cost. Private: members may change between versions. */
typedef struct {
    hkf_filter_t curves; /* its Eq. 8 curves, R's mode, constant and clamp, as hkf_init lays out a filter's */
} hkf_model_prepared_t;

/* Checks `second` as hkf_init checks those settings (HKF_ERROR_SETTING_*; HKF_ERROR_NULL_ARGUMENT) and
 * prepares it in *p. Independent of any filter: one prepared model serves every filter. */
int hkf_model_noise_init(hkf_model_prepared_t *p, const hkf_model_noise_t *second);

/* hkf_update_pair with a prepared second model: the same steps and results, bit for bit. */
int hkf_update_pair_prepared(hkf_filter_t *f, const hkf_real_t z[3], const hkf_real_t z2[3],
                             const hkf_model_prepared_t *second, hkf_real_t dt, hkf_output_t *out);

/* No measurement this frame (face lost): predict dt s ahead. See the coasting
 * rule at the top of libhkf/src/hkf_filter.c. Writes the prediction to out (which may be NULL). */
int hkf_predict(hkf_filter_t *f, hkf_real_t dt, hkf_output_t *out);

/* The pose dt_ahead s after the last call, without changing the filter: for
 * publishing at a display rate between camera frames. 0 <= dt_ahead <= max_dt. */
int hkf_extrapolate(const hkf_filter_t *f, hkf_real_t dt_ahead, hkf_output_t *out);

/* The measured noise level n per axis (deg^2; hkf_calibration.h measures
 * it): from the next update on, R = n e(z) / e(mu), Eq. 8's dependence on the
 * pose at this camera's level (R at the curve's center is n), clamped to
 * [r_min, r_max]. NULL: back to Eq. 8's own R (hkf_init's). hkf_reset keeps
 * it. HKF_ERROR_NON_FINITE or HKF_ERROR_NOISE_RANGE (n <= 0) change nothing. */
int hkf_set_noise(hkf_filter_t *f, const hkf_real_t noise[3]);

/* HOLD's wander w (deg^2; hkf_rest.h measures it on the player's rest): from the next update on, HOLD's
 * measurement variance is R + w, in place of R + the still_wander hkf_init was given (the filter's copy
 * of the settings takes it: hkf_reset keeps it, hkf_init forgets it). HKF_ERROR_NON_FINITE, or
 * HKF_ERROR_SETTING_MOTION (w outside [0, HKF_MAX_VARIANCE]), change nothing. (libhkf 1.2) */
int hkf_set_wander(hkf_filter_t *f, hkf_real_t wander);

/* The wander HOLD takes, deg^2 (still_wander until hkf_set_wander gave another). */
int hkf_get_wander(const hkf_filter_t *f, hkf_real_t *wander);

/* The track's status (HKF_STATUS_UNINITIALIZED for a NULL filter). */
hkf_status_t hkf_get_status(const hkf_filter_t *f);

/* The current state, as the last update or predict left it. */
int hkf_get_output(const hkf_filter_t *f, hkf_output_t *out);

/* The whole state per axis (pitch, yaw, roll), for references, logs and diagnostics: the estimate
 * and its rate, their covariance P = [p00 p01; p01 p11], and the motion adaptation's probability
 * of MOVE (1 with start_rate 0). As the last call left it; 0 before the first track. */
typedef struct {
    hkf_real_t angle[3], rate[3];         /* deg, deg/s */
    hkf_real_t p00[3], p01[3], p11[3];    /* deg^2, deg^2/s, (deg/s)^2 */
    hkf_real_t moving[3];
} hkf_state_t;
int hkf_get_state(const hkf_filter_t *f, hkf_state_t *state);

/* The loop-closure center kappa: set it explicitly (it then survives
 * hkf_reset), or to the current estimate. By default the first measurement
 * sets it. */
int hkf_set_center(hkf_filter_t *f, const hkf_real_t center[3]);
int hkf_recenter(hkf_filter_t *f);
int hkf_get_center(const hkf_filter_t *f, hkf_real_t center[3]);

/* Paper Eq. 8 (amplitude form) and the clamp: R for a measured angle x on one axis. */
hkf_real_t hkf_observation_noise(const hkf_filter_t *f, int axis, hkf_real_t x);

#ifdef __cplusplus
}
#endif

#endif /* HKF_H */

/*
 * hkf_filter.c - the adaptive Kalman filter of Hu, Lv et al., one file with
 * every equation of the paper.
 *
 * The paper's filter has the 6-state x = (pitch, yaw, roll, their rates),
 * F = [[I, dt I], [0, I]], H = [I 0]. With Q, R and P0 block-diagonal per axis
 * it splits exactly into three 2-state filters (angle, rate), each with a
 * closed-form scalar gain: no matrix inverse, no general matrix code.
 *
 * Per axis the covariance is P = [[p00, p01], [p01, p11]]. The per-axis
 * arrays have a fourth, idle lane (zero process noise, zero measurement) so
 * that the compiler turns each axis loop into a few SIMD instructions.
 *
 * Missing measurements (the coasting rule):
 *   hkf_predict advances the constant-velocity model and counts the time
 *   since the last accepted measurement. Once that time reaches coast_time the
 *   track is LOST: the rate and its covariance are zeroed, and later predicts
 *   hold the angle (and its variance) still. The next measurement re-acquires:
 *   the track restarts from it as from the first one, keeping the center.
 *   A measurement the innovation gate rejects counts as a missing one.
 *
 * A noise level from outside (hkf_set_noise, not in the paper; the noise
 * calibration of hkf_calibration.h measures one): R = n e(z) / e(mu)
 * (calibrated_noise_lanes: the paper's Eq. 8 gives the pose-dependent factor,
 * n the scale).
 *
 * The motion adaptation (settings.start_rate > 0, not in the paper): two
 * models per axis, HOLD and the paper's MOVE, mixed by their likelihoods
 * (hkf_two_models.h, which derives it).
 */
#include "hkf/hkf.h"
#include "hkf_internal.h"
#include "hkf_kalman.h"
#include "hkf_math.h"
#include "hkf_two_models.h"

enum { CENTER_NONE = 0, CENTER_FROM_TRACK = 1, CENTER_EXPLICIT = 2 };

static void write_output(const hkf_filter_t *restrict f, unsigned flags, hkf_output_t *restrict out)
{
    int a;
    if (out == 0) {
        return;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        out->angle[a] = f->angle[a];
        out->rate[a] = f->rate[a];
        out->variance[a] = f->p00[a];
        out->r[a] = f->r[a];
    }
    out->flags = flags;
    out->status = f->status;
}

static int check_dt(const hkf_filter_t *f, hkf_real_t dt)
{
    /* NaN fails the range test too; the finite test only names the error */
    if (!(dt > 0 && dt <= HKF_SETTINGS(f)->max_dt)) {
        return hkf_is_finite(dt) ? HKF_ERROR_DT_RANGE : HKF_ERROR_NON_FINITE;
    }
    return HKF_OK;
}

static HKF_ALWAYS_INLINE int check_angles(const hkf_real_t v[3])
{
    const hkf_real_t limit = HKF_REAL_FROM(HKF_MAX_ABS_ANGLE);
    int a;
    /* NaN fails every comparison, so this one test passes only good input */
    if ((int)(hkf_abs(v[0]) <= limit) & (int)(hkf_abs(v[1]) <= limit) & (int)(hkf_abs(v[2]) <= limit)) {
        return HKF_OK;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        if (!hkf_is_finite(v[a])) {
            return HKF_ERROR_NON_FINITE;
        }
        if (hkf_abs(v[a]) > limit) {
            return HKF_ERROR_ANGLE_RANGE;
        }
    }
    return HKF_OK;
}

/* hkf_set_noise has given a noise level (n > 0; 0 = none, Eq. 8's own R). */
static inline int calibrated(const hkf_filter_t *f)
{
    return f->noise[0] > 0;
}

static inline int two_models(const hkf_filter_t *f)
{
    return HKF_SETTINGS(f)->start_rate > 0;
}

/* One axis lane of the filter's state, and back. */
static HKF_ALWAYS_INLINE hkf_axis_t lane_axis(const hkf_filter_t *restrict f, int a)
{
    return hkf_axis_gather(f->angle[a], f->rate[a], f->p00[a], f->p01[a], f->p11[a]);
}

static HKF_ALWAYS_INLINE void set_lane(hkf_filter_t *restrict f, int a, hkf_axis_t x)
{
    hkf_axis_scatter(x, &f->angle[a], &f->rate[a], &f->p00[a], &f->p01[a], &f->p11[a]);
}

/* Paper Eq. 1-3 on every axis (hkf_kalman.h), yaw wrapped after. */
static inline void predict_axes(hkf_filter_t *restrict f, hkf_real_t dt)
{
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        set_lane(f, a, hkf_kalman_predict(lane_axis(f, a), HKF_Q(f, a), dt));
    }
    f->angle[HKF_AXIS_YAW] = hkf_wrap180(f->angle[HKF_AXIS_YAW]);
}

static inline hkf_real_t clamp(hkf_real_t x, hkf_real_t low, hkf_real_t high)
{
    x = x < low ? low : x;
    return x > high ? high : x;
}

/* The measurement into the axis lanes (the idle fourth lane 0), yaw wrapped
 * to [-180, 180): Eq. 8's R is read at the wrapped yaw (359 deg is -1 deg). */
static void load_lanes(hkf_real_t lanes[restrict HKF_LANES], const hkf_real_t z[restrict 3])
{
    lanes[0] = z[0];
    lanes[1] = hkf_wrap180(z[1]);
    lanes[2] = z[2];
#if HKF_LANES > 3 /* (HKF_AXES is an enum, unseen by the preprocessor) */
    lanes[3] = 0;
#endif
}

/* Paper Eq. 9, loop closure: with d = z - kappa, if |d| <= theta_lc then
 * z = kappa + xi d  (= xi z + (1 - xi) kappa). |d| is the Euclidean norm over
 * the three axes (compared squared), or each axis alone in PER_AXIS mode.
 * Returns whether it moved the measurement. */
static HKF_ALWAYS_INLINE int loop_closure(const hkf_filter_t *restrict f, const hkf_real_t z[restrict 3],
                        hkf_real_t zc[restrict HKF_LANES])
{
    const hkf_settings_t *s = HKF_SETTINGS(f);
    const hkf_real_t theta2 = hkf_mul(s->lc_theta, s->lc_theta);
    hkf_real_t d[HKF_LANES];
    int a, closed = 0;
    load_lanes(zc, z);
    if (s->loop_closure == HKF_LOOP_CLOSURE_OFF || f->center_source == CENTER_NONE) {
        return 0;
    }
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        d[a] = hkf_sub(zc[a], f->center[a]);
    }
    d[HKF_AXIS_YAW] = hkf_wrap180(d[HKF_AXIS_YAW]);
    if (s->loop_closure == HKF_LOOP_CLOSURE_NORM) {
        const hkf_real_t norm2 = hkf_add(hkf_add(hkf_mul(d[0], d[0]), hkf_mul(d[1], d[1])), hkf_mul(d[2], d[2]));
        closed = norm2 <= theta2;
        if (closed) {
            for (a = 0; a < HKF_LOOP_LANES; ++a) {
                zc[a] = hkf_add(f->center[a], hkf_mul(s->lc_xi, d[a]));
            }
        }
    } else {
        for (a = 0; a < HKF_AXES; ++a) {
            if (hkf_mul(d[a], d[a]) <= theta2) {
                zc[a] = hkf_add(f->center[a], hkf_mul(s->lc_xi, d[a]));
                closed = 1;
            }
        }
    }
    if (closed) {
        zc[HKF_AXIS_YAW] = hkf_wrap180(zc[HKF_AXIS_YAW]);
    }
    return closed;
}

/* Paper Eq. 8, amplitude form:  e(x) = tau - lambda exp(-(x - mu)^2 / (2 sigma^2)).
 * The paper prints Eq. 8 with the normalising factor 1/(sqrt(2 pi) sigma),
 * but its Table I only makes sense without it (FSA-Net yaw: 7.64 - 4.11 =
 * 3.53 deg at the center, ~7.6 deg at +-90 deg; normalised, pitch R would be a
 * near-constant 315). Written as (tau - lambda) + lambda (1 - exp(.)) so the
 * roll curves (tau, lambda ~ 1e5) do not cancel catastrophically in float;
 * the rise lambda (1 - exp(.)) is the math layer's (hkf_math.h). */
static inline hkf_real_t noise_curve(const hkf_filter_t *restrict f, int lane, hkf_real_t x)
{
    return hkf_add(HKF_NOISE_FLOOR(f, lane), hkf_curve_rise(f, lane, hkf_sub(x, HKF_MU(f, lane))));
}

/* R for every lane at the measured angles x: the mode is tested once, so
 * each lane loop is straight-line code the compiler vectorizes. */
static void observation_noise_lanes(const hkf_filter_t *restrict f, const hkf_real_t x[restrict HKF_LANES],
                                    hkf_real_t r[restrict HKF_LANES])
{
    const hkf_real_t low = HKF_SETTINGS(f)->r_min, high = HKF_SETTINGS(f)->r_max;
    int a;
    if (HKF_SETTINGS(f)->noise_mode == HKF_NOISE_CONSTANT) {
        for (a = 0; a < HKF_LOOP_LANES; ++a) {
            r[a] = clamp(HKF_R_CONST(f, a), low, high);
        }
        return;
    }
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        r[a] = noise_curve(f, a, x[a]);
    }
    if (HKF_SETTINGS(f)->noise_mode == HKF_NOISE_ADAPTIVE_SQUARED) {
        for (a = 0; a < HKF_LOOP_LANES; ++a) {
            r[a] = r[a] > 0 ? hkf_mul(r[a], r[a]) : 0;
        }
    }
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        r[a] = clamp(r[a], low, high);
    }
}

static hkf_real_t observation_noise(const hkf_filter_t *restrict f, int lane, hkf_real_t x)
{
    hkf_real_t lanes[HKF_LANES], r[HKF_LANES];
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        lanes[a] = x;
    }
    observation_noise_lanes(f, lanes, r);
    return r[lane];
}

/* e(mu) per lane, R at the curves' centres, as hkf_math.h's divisor (R = n e(z) / e(mu)). The float and
 * double builds keep it from hkf_init; the fixed-point build forms it each calibrated step, saving its RAM
 * (Eq. 8 at its centre is the floor: no exponential). */
static void center_noise_lanes(const hkf_filter_t *restrict f, hkf_divisor_t center[restrict HKF_LANES])
{
    hkf_real_t mu[HKF_LANES], e[HKF_LANES];
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        mu[a] = HKF_MU(f, a);
    }
    observation_noise_lanes(f, mu, e);
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        center[a] = hkf_divisor(e[a]);
    }
}

/* Noise calibration, R = n e(z) / e(mu): the mode's R at the measured angles
 * (Eq. 8, clamped: the pose-dependent factor) scaled by the measured noise n
 * over the same R at the curve's center, clamped again. */
static HKF_ALWAYS_INLINE void calibrated_noise_lanes(const hkf_filter_t *restrict f, hkf_real_t r[restrict HKF_LANES])
{
    const hkf_real_t low = HKF_SETTINGS(f)->r_min, high = HKF_SETTINGS(f)->r_max;
#if defined(HKF_REAL_FIXED)
    hkf_divisor_t center[HKF_LANES];
    center_noise_lanes(f, center);
#else
    const hkf_divisor_t *center = f->r_center;
#endif
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        r[a] = clamp(hkf_divide(hkf_mul(r[a], f->noise[a]), center[a]), low, high);
    }
}

hkf_real_t hkf_observation_noise(const hkf_filter_t *f, int axis, hkf_real_t x)
{
    if (f == 0 || axis < 0 || axis >= HKF_AXES) {
        return 0;
    }
    return observation_noise(f, axis, x);
}

/* The track's start: the first measurement (or the first after LOST, or after too many
 * gated ones) starts the track: angle = z, rate = 0, P = diag(p0). The
 * caller has put R at z (Eq. 8) in f->r: computed there, not in here, the
 * curve's stack frame does not stack on this one (Cortex-M0's budget). */
static void start_track(hkf_filter_t *f, const hkf_real_t z[3])
{
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        f->angle[a] = a < HKF_AXES ? z[a] : 0; /* (lane 3 exists only where HKF_LOOP_LANES is 4) */
        f->rate[a] = 0;
        f->p00[a] = HKF_SETTINGS(f)->p0_angle;
        f->p01[a] = 0;
        f->p11[a] = HKF_SETTINGS(f)->p0_rate;
        f->moving[a] = 0;
    }
    f->angle[HKF_AXIS_YAW] = hkf_wrap180(z[HKF_AXIS_YAW]);
    if (f->center_source == CENTER_NONE) {
        for (a = 0; a < HKF_AXES; ++a) {
            f->center[a] = f->angle[a];
        }
        f->center_source = CENTER_FROM_TRACK;
    }
    f->time_since_measurement = 0;
    f->gate_rejections = 0;
    f->status = HKF_STATUS_TRACKING;
}

/* A frame without an accepted measurement, dt s long: count it, and lose
 * the track once coast_time has passed without one. */
static void count_missing(hkf_filter_t *f, hkf_real_t dt)
{
    int a;
    f->time_since_measurement = hkf_add(f->time_since_measurement, dt);
    f->status = HKF_STATUS_COASTING;
    if (f->time_since_measurement >= HKF_SETTINGS(f)->coast_time) {
        for (a = 0; a < HKF_LOOP_LANES; ++a) {
            f->rate[a] = 0;
            f->p01[a] = 0;
            f->p11[a] = 0;
            f->moving[a] = 0;
        }
        f->status = HKF_STATUS_LOST;
    }
}

/* hkf_init's first half: the settings checked and kept, their Eq. 8 curves
 * prepared; all hkf_update_pair needs of the second model's (hkf_model_noise_init). */
static int prepare_settings(hkf_filter_t *f, const hkf_settings_t *s)
{
    int a, result = hkf_settings_check(s);
    if (result != HKF_OK) {
        return result;
    }
    HKF_KEEP_SETTINGS(f, s);
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
#if !defined(HKF_REAL_FIXED)
        if (a < HKF_AXES) {
            hkf_curve_prepare(f, a, &s->noise[a]);
            f->q[a] = s->process_noise[a];
            f->r_const[a] = s->r_const[a];
        } else { /* the idle lane: a still, perfectly observed axis */
            f->q[a] = 0;
            f->r_const[a] = s->r_min;
            hkf_curve_flat(f, a, s->r_min);
        }
#endif
    }
    return HKF_OK;
}

int hkf_init(hkf_filter_t *f, const hkf_settings_t *s)
{
    int a, result;
    if (f == 0 || s == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = prepare_settings(f, s);
    if (result != HKF_OK) {
        return result;
    }
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        f->center[a] = 0;
        f->noise[a] = 0; /* no noise level given: Eq. 8's own R */
    }
#if !defined(HKF_REAL_FIXED)
    center_noise_lanes(f, f->r_center); /* e(mu), R = n e(z) / e(mu)'s divisor, kept */
#endif
    f->center_source = CENTER_NONE;
    hkf_reset(f);
    return HKF_OK;
}

void hkf_reset(hkf_filter_t *f)
{
    int a;
    if (f == 0) {
        return;
    }
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        f->angle[a] = 0;
        f->rate[a] = 0;
        f->p00[a] = HKF_SETTINGS(f)->p0_angle;
        f->p01[a] = 0;
        f->p11[a] = HKF_SETTINGS(f)->p0_rate;
        f->r[a] = 0;
        f->moving[a] = 0;
    }
    if (f->center_source != CENTER_EXPLICIT) {
        f->center_source = CENTER_NONE;
    }
    f->time_since_measurement = 0;
    f->gate_rejections = 0;
    f->status = HKF_STATUS_UNINITIALIZED;
}

/* Eq. 4-5 for the loop-closed measurement y (replaced by the innovation) with R r. */
static HKF_ALWAYS_INLINE void innovation(const hkf_filter_t *restrict f, hkf_real_t y[restrict HKF_LANES],
                                         const hkf_real_t r[restrict HKF_LANES], hkf_divisor_t inv_s[restrict HKF_LANES])
{
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        y[a] = hkf_sub(y[a], f->angle[a]);                            /* Eq. 4: y = z - H x */
    }
    y[HKF_AXIS_YAW] = hkf_wrap180(y[HKF_AXIS_YAW]);
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        inv_s[a] = hkf_divisor(hkf_add(f->p00[a], r[a]));             /* Eq. 5: S = H P H' + R */
    }
}

/* The innovation gate's test: the normalised innovation sqrt(y' S^-1 y) beyond gate_sigma. */
static HKF_ALWAYS_INLINE int gated(const hkf_filter_t *restrict f, const hkf_real_t y[restrict HKF_LANES],
                                   const hkf_divisor_t inv_s[restrict HKF_LANES])
{
    const hkf_real_t gate = HKF_SETTINGS(f)->gate_sigma;
    return gate > 0 && hkf_add(hkf_add(hkf_divide(hkf_mul(y[0], y[0]), inv_s[0]), hkf_divide(hkf_mul(y[1], y[1]), inv_s[1])),
                               hkf_divide(hkf_mul(y[2], y[2]), inv_s[2])) > hkf_mul(gate, gate);
}

/* The measurement is accepted: bookkeeping after Eq. 6-7 (the track holds). */
static HKF_ALWAYS_INLINE void accepted(hkf_filter_t *restrict f, const hkf_real_t r[restrict HKF_LANES])
{
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        f->r[a] = r[a];
    }
    f->angle[HKF_AXIS_YAW] = hkf_wrap180(f->angle[HKF_AXIS_YAW]);
    f->time_since_measurement = 0;
    f->gate_rejections = 0;
    f->status = HKF_STATUS_TRACKING;
}

/* Eq. 6-7 with the innovation y, R r and 1/S (hkf_kalman.h). */
static HKF_ALWAYS_INLINE void correct_axes(hkf_filter_t *restrict f, const hkf_real_t y[restrict HKF_LANES],
                                           const hkf_real_t r[restrict HKF_LANES],
                                           const hkf_divisor_t inv_s[restrict HKF_LANES])
{
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        set_lane(f, a, hkf_kalman_correct(lane_axis(f, a), y[a], r[a], inv_s[a]));
    }
    accepted(f, r);
}

/* HOLD and MOVE per axis (hkf_two_models.h): the state holds MOVE's
 * prediction, held_p00 the variances before it, y MOVE's innovations. */
static HKF_ALWAYS_INLINE void two_models_axes(hkf_filter_t *restrict f, const hkf_real_t held_p00[restrict HKF_LANES],
                                              const hkf_real_t y[restrict HKF_LANES],
                                              const hkf_real_t r[restrict HKF_LANES], hkf_real_t dt)
{
    const hkf_settings_t *s = HKF_SETTINGS(f);
    const hkf_two_model_step_t c = hkf_two_models_prepare(dt, s->start_rate, s->stop_rate, s->p0_rate);
    hkf_real_t y_h[HKF_LANES]; /* HOLD's innovations (lanes, so the loops stay vectors) */
    int a;
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        y_h[a] = hkf_add(y[a], hkf_mul(f->rate[a], dt));
    }
    y_h[HKF_AXIS_YAW] = hkf_wrap180(y_h[HKF_AXIS_YAW]);
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        hkf_hold_prior_t hold;
        hold.p00 = held_p00[a];
        hold.y = y_h[a];
        hold.wander = s->still_wander;
        set_lane(f, a, hkf_two_models_update(&c, lane_axis(f, a), hold, y[a], r[a], &f->moving[a]));
    }
    accepted(f, r);
}

/* The track starts (again) from z, with R from `noise`'s curves (lanes: the
 * caller's scratch, so the step's stack does not grow). */
static HKF_ALWAYS_INLINE void restart_from(hkf_filter_t *f, const hkf_filter_t *noise, const hkf_real_t z[restrict 3],
                                           hkf_real_t lanes[restrict HKF_LANES], unsigned flags,
                                           hkf_output_t *restrict out)
{
    load_lanes(lanes, z);
    observation_noise_lanes(noise, lanes, f->r);
    start_track(f, z);
    write_output(f, flags | HKF_FLAG_REACQUIRED, out);
}

/* R for the loop-closed measurement y with `noise`'s Eq. 8 curves (f's own or a second model's), at
 * the noise level hkf_set_noise gave f (R = n e(z) / e(mu)) when it gave one. */
static HKF_ALWAYS_INLINE void measurement_noise(const hkf_filter_t *restrict f, const hkf_filter_t *noise,
                                                const hkf_real_t y[restrict HKF_LANES], hkf_real_t r[restrict HKF_LANES])
{
    observation_noise_lanes(noise, y, r);                                 /* Eq. 8 */
    if (calibrated(f)) {
        calibrated_noise_lanes(f, r);                                     /* R = n e(z) / e(mu) */
    }
}

/* Innovation gate: a measurement whose normalised innovation sqrt(y' S^-1 y) exceeds gate_sigma is
 * missing; after max_gate_rejections in a row, the track restarts from it. */
static HKF_ALWAYS_INLINE void gate_rejects(hkf_filter_t *f, const hkf_filter_t *noise, const hkf_real_t z[restrict 3],
                                           hkf_real_t dt, unsigned flags, hkf_output_t *restrict out)
{
    hkf_real_t lanes[HKF_LANES];
    if (f->gate_rejections >= HKF_SETTINGS(f)->max_gate_rejections) {
        restart_from(f, noise, z, lanes, HKF_FLAG_GATED, out);
    } else {
        count_missing(f, dt);
        f->gate_rejections += 1u;
        write_output(f, HKF_FLAG_GATED | flags, out);
    }
}

/* hkf_update's step for a measurement z whose Eq. 8 curves (and r_const,
 * r_min, r_max) are those of `noise`: f itself, or a second model's prepared
 * curves (hkf_update_pair when only the second model measured). z is checked. */
static HKF_ALWAYS_INLINE int update_with(hkf_filter_t *f, const hkf_filter_t *noise,
                                         const hkf_real_t z[restrict 3], hkf_real_t dt, hkf_output_t *restrict out)
{
    hkf_real_t y[HKF_LANES], r[HKF_LANES]; /* y holds the loop-closed measurement, then the innovation */
    hkf_real_t held_p00[HKF_LANES];        /* the variances before the prediction: HOLD's prior */
    hkf_divisor_t inv_s[HKF_LANES];
    unsigned flags = 0;
    int a, result = f->status == HKF_STATUS_UNINITIALIZED ? HKF_OK : check_dt(f, dt);
    if (result != HKF_OK) {
        return result;
    }
    if (f->status == HKF_STATUS_UNINITIALIZED || f->status == HKF_STATUS_LOST) {
        restart_from(f, noise, z, y, 0, out); /* the first measurement (dt ignored), or the first after LOST */
        return HKF_OK;
    }
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        held_p00[a] = f->p00[a];
    }
    predict_axes(f, dt);
    if (loop_closure(f, z, y)) {
        flags |= HKF_FLAG_LOOP_CLOSURE;
    }
    measurement_noise(f, noise, y, r);
    innovation(f, y, r, inv_s);
    if (gated(f, y, inv_s)) {
        gate_rejects(f, noise, z, dt, flags, out);
        return HKF_OK;
    }
    if (two_models(f)) {
        two_models_axes(f, held_p00, y, r, dt);                           /* Eq. 6-7 by HOLD and MOVE */
    } else {
        correct_axes(f, y, r, inv_s);                                     /* Eq. 6-7 */
    }
    write_output(f, flags, out);
    return HKF_OK;
}

int hkf_update(hkf_filter_t *restrict f, const hkf_real_t z[restrict 3], hkf_real_t dt, hkf_output_t *restrict out)
{
    int result;
    if (f == 0 || z == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = check_angles(z);
    if (result != HKF_OK) {
        return result;
    }
    return update_with(f, f, z, dt, out);
}

/* A second model's noise prepared as hkf_init prepares a filter's (its Eq. 8 curves in the filter's
 * layout) and checked as hkf_init checks it. The steps read nothing else of `curves` (R's mode, curves,
 * constant and clamp: observation_noise_lanes), so the other settings are the defaults', which pass. */
int hkf_model_noise_init(hkf_model_prepared_t *p, const hkf_model_noise_t *second)
{
    hkf_settings_t s;
    int a;
    if (p == 0 || second == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    s = hkf_default_settings;
    s.noise_mode = second->noise_mode;
    for (a = 0; a < HKF_AXES; ++a) {
        s.noise[a] = second->noise[a];
        s.r_const[a] = second->r_const[a];
    }
    s.r_min = second->r_min;
    s.r_max = second->r_max;
    return prepare_settings(&p->curves, &s);
}

/* The second model's measurement z2 after the first's step (whose flags are first_flags): a sequential
 * update, Eq. 9 against the same center and Eq. 8 with its own curves (noise2); out->r the R of both. */
static void update_second(hkf_filter_t *restrict f, const hkf_filter_t *noise2, const hkf_real_t z2[restrict 3],
                          unsigned first_flags, hkf_output_t *restrict out)
{
    hkf_real_t y[HKF_LANES], r[HKF_LANES], r1[HKF_LANES];
    hkf_divisor_t inv_s[HKF_LANES];
    int a;
    if (loop_closure(f, z2, y)) {
        first_flags |= HKF_FLAG_LOOP_CLOSURE;
    }
    measurement_noise(f, noise2, y, r); /* its Eq. 8 at the first model's measured noise level */
    innovation(f, y, r, inv_s);
    if (gated(f, y, inv_s)) { /* the first's outcome stands */
        write_output(f, first_flags | HKF_FLAG_GATED, out);
        return;
    }
    for (a = 0; a < HKF_LOOP_LANES; ++a) {
        r1[a] = f->r[a];
    }
    correct_axes(f, y, r, inv_s);
    if (!(first_flags & HKF_FLAG_GATED)) {
        /* R of both, 1 / (1/R1 + 1/R2), as low (high / (low + high)): the product stays within
         * Q16.16 and the quotient, >= 1/2, keeps its digits */
        for (a = 0; a < HKF_LOOP_LANES; ++a) {
            const hkf_real_t low = r1[a] < r[a] ? r1[a] : r[a], high = r1[a] < r[a] ? r[a] : r1[a];
            f->r[a] = hkf_mul(low, hkf_divide(high, hkf_divisor(hkf_add(low, high))));
        }
    }
    write_output(f, first_flags, out);
}

int hkf_update_pair_prepared(hkf_filter_t *restrict f, const hkf_real_t z[restrict 3], const hkf_real_t z2[restrict 3],
                             const hkf_model_prepared_t *second, hkf_real_t dt, hkf_output_t *restrict out)
{
    hkf_output_t first;
    int result;
    if (f == 0 || (z == 0 && z2 == 0) || second == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (z2 == 0) { /* only the first model measured this frame */
        return hkf_update(f, z, dt, out);
    }
    result = check_angles(z2); /* everything about the second measurement is checked before the state changes */
    if (result != HKF_OK) {
        return result;
    }
    if (z == 0) { /* only the second: its measurement with its own R, as hkf_update takes one */
        return update_with(f, &second->curves, z2, dt, out);
    }
    /* predict (Eq. 1-3) and the first measurement (Eq. 4-9), or the track's start from it; then the second */
    result = hkf_update(f, z, dt, &first);
    if (result == HKF_OK) {
        update_second(f, &second->curves, z2, first.flags, out);
    }
    return result;
}

int hkf_update_pair(hkf_filter_t *restrict f, const hkf_real_t z[restrict 3], const hkf_real_t z2[restrict 3],
                    const hkf_model_noise_t *second, hkf_real_t dt, hkf_output_t *restrict out)
{
    hkf_model_prepared_t prepared;
    int result;
    if (f == 0 || (z == 0 && z2 == 0) || second == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = hkf_model_noise_init(&prepared, second); /* checked before the state changes, z2 or not */
    return result != HKF_OK ? result : hkf_update_pair_prepared(f, z, z2, &prepared, dt, out);
}

int hkf_set_noise(hkf_filter_t *f, const hkf_real_t noise[3])
{
    int a;
    if (f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    for (a = 0; noise != 0 && !hkf_noise_levels_ok(noise) && a < HKF_AXES; ++a) {
        if (!hkf_is_finite(noise[a])) {
            return HKF_ERROR_NON_FINITE;
        }
        if (!(noise[a] > 0)) {
            return HKF_ERROR_NOISE_RANGE;
        }
    }
    for (a = 0; a < HKF_AXES; ++a) {
        f->noise[a] = noise != 0 ? noise[a] : 0;
    }
    return HKF_OK;
}

int hkf_set_wander(hkf_filter_t *f, hkf_real_t wander)
{
    if (f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!hkf_is_finite(wander)) {
        return HKF_ERROR_NON_FINITE;
    }
    if (!(wander >= 0 && wander <= HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
        return HKF_ERROR_SETTING_MOTION;
    }
    f->settings.still_wander = wander; /* HOLD reads it there (two_models_axes) */
    return HKF_OK;
}

int hkf_get_wander(const hkf_filter_t *f, hkf_real_t *wander)
{
    if (f == 0 || wander == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    *wander = f->settings.still_wander;
    return HKF_OK;
}

int hkf_predict(hkf_filter_t *f, hkf_real_t dt, hkf_output_t *out)
{
    int result;
    if (f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (f->status == HKF_STATUS_UNINITIALIZED) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    result = check_dt(f, dt);
    if (result != HKF_OK) {
        return result;
    }
    if (f->status != HKF_STATUS_LOST) {
        predict_axes(f, dt);
        count_missing(f, dt);
    }
    write_output(f, 0u, out);
    return HKF_OK;
}

int hkf_extrapolate(const hkf_filter_t *f, hkf_real_t dt_ahead, hkf_output_t *out)
{
    int a;
    if (f == 0 || out == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (f->status == HKF_STATUS_UNINITIALIZED) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    if (!hkf_is_finite(dt_ahead)) {
        return HKF_ERROR_NON_FINITE;
    }
    if (!(dt_ahead >= 0 && dt_ahead <= HKF_SETTINGS(f)->max_dt)) {
        return HKF_ERROR_DT_RANGE;
    }
    /* Eq. 1-2 for the output alone: the filter is not copied (a small stack) */
    write_output(f, HKF_FLAG_EXTRAPOLATED, out);
    for (a = 0; a < HKF_AXES; ++a) {
        out->angle[a] = hkf_add(out->angle[a], hkf_mul(f->rate[a], dt_ahead));
        out->variance[a] = hkf_add(out->variance[a],
                                   hkf_kalman_growth(f->p01[a], f->p11[a], hkf_mul(HKF_Q(f, a), dt_ahead), dt_ahead));
    }
    out->angle[HKF_AXIS_YAW] = hkf_wrap180(out->angle[HKF_AXIS_YAW]);
    return HKF_OK;
}

hkf_status_t hkf_get_status(const hkf_filter_t *f)
{
    return f == 0 ? HKF_STATUS_UNINITIALIZED : f->status;
}

int hkf_get_output(const hkf_filter_t *f, hkf_output_t *out)
{
    if (f == 0 || out == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    write_output(f, 0u, out);
    return HKF_OK;
}

int hkf_get_state(const hkf_filter_t *f, hkf_state_t *state)
{
    int a;
    if (f == 0 || state == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        state->angle[a] = f->angle[a];
        state->rate[a] = f->rate[a];
        state->p00[a] = f->p00[a];
        state->p01[a] = f->p01[a];
        state->p11[a] = f->p11[a];
        state->moving[a] = f->moving[a];
    }
    return HKF_OK;
}

int hkf_set_center(hkf_filter_t *f, const hkf_real_t center[3])
{
    int a, result;
    if (f == 0 || center == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = check_angles(center);
    if (result != HKF_OK) {
        return result;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        f->center[a] = center[a];
    }
    f->center[HKF_AXIS_YAW] = hkf_wrap180(center[HKF_AXIS_YAW]);
    f->center_source = CENTER_EXPLICIT;
    return HKF_OK;
}

int hkf_recenter(hkf_filter_t *f)
{
    if (f == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (f->status == HKF_STATUS_UNINITIALIZED) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    return hkf_set_center(f, f->angle);
}

int hkf_get_center(const hkf_filter_t *f, hkf_real_t center[3])
{
    int a;
    if (f == 0 || center == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (f->center_source == CENTER_NONE) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        center[a] = f->center[a];
    }
    return HKF_OK;
}

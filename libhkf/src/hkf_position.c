/* hkf_position.c - see hkf/hkf_position.h. The per-axis step is the angles' own
 * (hkf_filter.c): predict with F = [[1, dt], [0, 1]] and white-acceleration q
 * (Eq. 1-3), update with H = [1, 0], the gain in closed form from S = P00 + R
 * (Eq. 4-7); calibrated, the angles' noise estimate and motion detector
 * (hkf_motion.h). */
#include "hkf/hkf_position.h"

#include <stddef.h>

#include "hkf_kalman.h"
#include "hkf_math.h"
#include "hkf_motion.h"

/* Chosen on truth by construction (dev/eval/position_truth.py; the clips and figures: docs/estimator.md
 * "Head position"): the least moving z error whose still z jitter is at most half the goal's. A head leans
 * at well under 1 m/s; a mesh that misreads the face's scale, or a forged message, jumps further in one
 * step (max_speed); 6 refused frames that agree with each other (0.2 s at 30 fps) restart the track. */
const hkf_position_settings_t hkf_position_default_settings = {
    .process_noise = {HKF_REAL(3.0), HKF_REAL(3.0), HKF_REAL(3.0)},          /* x n, 1/s^3 */
    .measurement_noise = {HKF_REAL(0.002), HKF_REAL(0.002), HKF_REAL(0.05)}, /* cm^2: n's start */
    .p0_rate = HKF_REAL(100.0),                                              /* (cm/s)^2 */
    .max_dt = HKF_REAL(0.5),
    .noise_time = HKF_REAL(0.3),
    .noise_rise = HKF_REAL(0.2),
    .noise_floor = HKF_REAL_FROM(HKF_MIN_VARIANCE),
    .q_boost = HKF_REAL(100.0),
    .q_boost_time = HKF_REAL(0.2),
    .motion_threshold = HKF_REAL(128.0),
    .rate_damping_time = HKF_REAL(0.1),
    .still_threshold = HKF_REAL(64.0),
    .max_speed = HKF_REAL(300.0), /* cm/s */
    .max_gate_rejections = 5u,
};

static int in_range(hkf_real_t x, hkf_real_t low, hkf_real_t high) { return hkf_is_finite(x) && x >= low && x <= high; }

/* R, q, the start and the longest step: HKF_OK or the first bad one's error. */
static int check_noise(const hkf_position_settings_t *s)
{
    int a;
    for (a = 0; a < 3; ++a) {
        if (!in_range(s->process_noise[a], HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_PROCESS_NOISE))) {
            return HKF_ERROR_SETTING_PROCESS_NOISE;
        }
        if (!in_range(s->measurement_noise[a], HKF_REAL_FROM(HKF_MIN_VARIANCE), HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
            return HKF_ERROR_SETTING_R_CONST;
        }
    }
    if (!in_range(s->p0_rate, HKF_REAL_FROM(HKF_MIN_VARIANCE), HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
        return HKF_ERROR_SETTING_P0;
    }
    if (!in_range(s->max_dt, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_TIME)) || s->max_dt == 0) {
        return HKF_ERROR_SETTING_MAX_DT;
    }
    if (!in_range(s->noise_floor, HKF_REAL_FROM(HKF_MIN_VARIANCE), HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
        return HKF_ERROR_SETTING_R_RANGE;
    }
    return HKF_OK;
}

/* The calibration, the detector and the gate: HKF_OK or the first bad one's error. */
static int check_adaptation(const hkf_position_settings_t *s)
{
    if (!in_range(s->q_boost, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_Q_BOOST)) ||
        !in_range(s->q_boost_time, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_TIME))) {
        return HKF_ERROR_SETTING_MOTION;
    }
    if (!in_range(s->noise_time, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_TIME)) ||
        !in_range(s->noise_rise, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_NOISE_RISE)) ||
        !in_range(s->motion_threshold, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_MOTION_THRESHOLD)) ||
        !in_range(s->rate_damping_time, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_TIME)) ||
        !in_range(s->still_threshold, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_MOTION_THRESHOLD))) {
        return HKF_ERROR_SETTING_CALIBRATION;
    }
    if (!in_range(s->max_speed, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_SPEED)) ||
        (s->max_speed > 0 && s->max_gate_rejections == 0u)) {
        return HKF_ERROR_SETTING_GATE;
    }
    return HKF_OK;
}

int hkf_position_started(const hkf_position_filter_t *f)
{
    return f != NULL && f->started;
}

int hkf_position_get_state(const hkf_position_filter_t *f, hkf_position_state_t *state)
{
    int a;
    if (f == NULL || state == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    for (a = 0; a < 3; ++a) {
        state->position[a] = f->x[a];
        state->rate[a] = f->v[a];
        state->p00[a] = f->p00[a];
        state->p01[a] = f->p01[a];
        state->p11[a] = f->p11[a];
        state->center[a] = f->center[a];
        state->noise[a] = f->settings.noise_time > 0 ? f->noise[a] : f->settings.measurement_noise[a];
    }
    return HKF_OK;
}

int hkf_position_init(hkf_position_filter_t *f, const hkf_position_settings_t *s)
{
    int result;
    if (f == NULL || s == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = check_noise(s);
    if (result == HKF_OK) {
        result = check_adaptation(s);
    }
    if (result != HKF_OK) {
        return result;
    }
    f->settings = *s;
    hkf_position_reset(f);
    return HKF_OK;
}

void hkf_position_reset(hkf_position_filter_t *f)
{
    int a;
    if (f == NULL) {
        return;
    }
    for (a = 0; a < 3; ++a) {
        f->x[a] = f->v[a] = f->p00[a] = f->p01[a] = f->p11[a] = f->center[a] = 0;
        f->motion[a] = f->last_z[a] = f->last_step[a] = 0;
        f->noise[a] = f->noise_power[a] = f->settings.measurement_noise[a];
    }
    f->last_dt = 0;
    f->history = 0;
    f->gate_rejections = 0u;
    f->started = 0;
    f->centered = 0;
}

void hkf_position_restart(hkf_position_filter_t *f)
{
    if (f != NULL) {
        f->started = 0;
        f->history = 0;
        f->gate_rejections = 0u;
    }
}

/* x within [-limit, limit] */
static hkf_real_t bounded(hkf_real_t x, hkf_real_t limit) { return x > limit ? limit : x < -limit ? -limit : x; }

/* The range: every axis within +-HKF_MAX_ABS_POSITION, its rate within +-HKF_MAX_SPEED. */
static void keep_in_range(hkf_position_filter_t *f)
{
    int a;
    for (a = 0; a < 3; ++a) {
        f->x[a] = bounded(f->x[a], HKF_REAL_FROM(HKF_MAX_ABS_POSITION));
        f->v[a] = bounded(f->v[a], HKF_REAL_FROM(HKF_MAX_SPEED));
    }
}

static void write_output(const hkf_position_filter_t *f, hkf_status_t status, unsigned flags,
                         hkf_position_output_t *out)
{
    int a;
    if (out == NULL) {
        return;
    }
    for (a = 0; a < 3; ++a) {
        out->position[a] = f->x[a];
        out->rate[a] = f->v[a];
        out->variance[a] = f->p00[a];
    }
    out->status = status;
    out->flags = flags;
}

static int calibrated(const hkf_position_filter_t *f) { return f->settings.noise_time > 0; }

/* q of an axis: the setting, or calibrated, process_noise n, capped as the angles' */
static hkf_real_t process_noise(const hkf_position_filter_t *f, int a)
{
    const hkf_real_t q = f->settings.process_noise[a];
    const hkf_real_t most = HKF_REAL_FROM(HKF_MAX_BOOSTED_PROCESS_NOISE);
    const hkf_real_t scaled = hkf_mul(q, f->noise[a]);
    const hkf_real_t cap = q > most ? q : most;
    if (!calibrated(f)) {
        return q;
    }
    return scaled < cap ? scaled : cap;
}

/* The axis's random walk per s for a detector evidence (hkf_motion.h); f: the filter. */
/* R of an axis for a measurement of scale 1: the setting, or calibrated, the measured n */
static hkf_real_t measurement_noise(const hkf_position_filter_t *f, int a)
{
    return calibrated(f) ? f->noise[a] : f->settings.measurement_noise[a];
}

/* P stays positive semi-definite in every build: float and double lose it to rounding when R is
 * far below P (the update's p11 - k1 p01 cancels), and the position's variance is published. */
static void keep_covariance(hkf_real_t *p00, hkf_real_t *p01, hkf_real_t *p11)
{
    hkf_keep_covariance(p00, p01, p11); /* Q16.16's clamp */
    *p00 = *p00 > 0 ? *p00 : 0;
    *p11 = *p11 > 0 ? *p11 : 0;
    if (!(hkf_mul(*p01, *p01) <= hkf_mul(*p00, *p11))) { /* |p01| <= min(p00, p11) <= sqrt(p00 p11) */
        const hkf_real_t most = *p00 < *p11 ? *p00 : *p11;
        *p01 = *p01 < 0 ? -most : most;
    }
}

/* One axis of the state as a lane of the Kalman core (hkf_kalman.h), and back with P kept valid. */
static hkf_axis_t axis_of(const hkf_position_filter_t *f, int a)
{
    return hkf_axis_gather(f->x[a], f->v[a], f->p00[a], f->p01[a], f->p11[a]);
}

static void set_axis(hkf_position_filter_t *f, int a, hkf_axis_t x)
{
    hkf_axis_scatter(x, &f->x[a], &f->v[a], &f->p00[a], &f->p01[a], &f->p11[a]);
    keep_covariance(&f->p00[a], &f->p01[a], &f->p11[a]);
}

/* Eq. 1-3 per axis (hkf_kalman.h). */
static void predict_axes(hkf_position_filter_t *f, hkf_real_t dt)
{
    int a;
    for (a = 0; a < 3; ++a) {
        set_axis(f, a, hkf_kalman_predict(axis_of(f, a), process_noise(f, a), dt));
    }
}

static int check_step(const hkf_position_filter_t *f, hkf_real_t dt)
{
    if (!hkf_is_finite(dt)) {
        return HKF_ERROR_NON_FINITE;
    }
    return dt > 0 && dt <= f->settings.max_dt ? HKF_OK : HKF_ERROR_DT_RANGE;
}

/* Calibrated, the noise n per axis from the raw z (hkf_motion.h: hkf_noise_lane):
 * d = (z - z_k-1) - (z_k-1 - z_k-2) cancels a constant velocity only over
 * equal steps, so a sample counts when dt is within a quarter of the step
 * before (a missed frame does not pass for noise). */
static void noise_estimate_update(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t dt)
{
    const hkf_real_t beta = hkf_step_weight(dt, f->settings.noise_time);
    const hkf_real_t rise = hkf_add(HKF_REAL(1.0), hkf_mul(f->settings.noise_rise, dt));
    const hkf_real_t change = hkf_sub(dt, f->last_dt);
    const int equal = f->history >= 2 && hkf_mul(hkf_abs(change), HKF_REAL(4.0)) <= f->last_dt;
    int a;
    if (f->history == 0) { /* after a frame without one: the history starts here */
        for (a = 0; a < 3; ++a) {
            f->last_z[a] = z[a];
        }
        f->history = 1;
        return;
    }
    for (a = 0; a < 3; ++a) {
        const hkf_real_t step = hkf_sub(z[a], f->last_z[a]);
        if (equal) {
            hkf_noise_lane(hkf_sub(step, f->last_step[a]), beta, rise, &f->settings.noise_floor, &f->noise_power[a],
                           &f->noise[a]);
        }
        f->last_z[a] = z[a];
        f->last_step[a] = step;
    }
    f->last_dt = dt;
    f->history = 2;
}

/* A new track at the measurement z: rate 0, P = diag(R, p0_rate); the center there if none is set. */
static void start_track(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale,
                        hkf_position_output_t *out)
{
    int a;
    for (a = 0; a < 3; ++a) {
        f->x[a] = z[a];
        f->v[a] = 0;
        f->p00[a] = hkf_mul(measurement_noise(f, a), r_scale);
        f->p01[a] = 0;
        f->p11[a] = f->settings.p0_rate;
        if (!f->centered) {
            f->center[a] = z[a];
        }
    }
    for (a = 0; a < 3; ++a) {
        f->last_z[a] = z[a];
        f->motion[a] = 0;
    }
    f->history = 1;
    f->gate_rejections = 0u;
    f->started = 1;
    f->centered = 1;
    write_output(f, HKF_STATUS_TRACKING, HKF_FLAG_REACQUIRED, out);
}

/* A gap beyond max_dt: the track as hkf_position_extrapolate holds it (moved on by its rate for max_dt,
 * then still, Eq. 1-3's variance grown over the gap) becomes the state a new track must agree with
 * (the gate), so a first position after a gap is gated as any other. */
static void hold_track(hkf_position_filter_t *f, hkf_real_t dt)
{
    hkf_position_output_t held;
    int a;
    (void)hkf_position_extrapolate(f, dt, &held); /* started, dt finite and > max_dt > 0 */
    for (a = 0; a < 3; ++a) {
        f->x[a] = held.position[a];
        f->v[a] = 0;
        f->p00[a] = held.variance[a];
        f->p01[a] = 0;
        f->p11[a] = f->settings.p0_rate;
    }
}

/* The outlier gate on the predicted state: an axis's innovation |y| beyond
 * max_speed dt + HKF_POSITION_GATE_SIGMAS sqrt(S), tested without a root as
 * (|y| - max_speed dt)^2 > sigmas^2 S where |y| exceeds the reach. */
static int gated(const hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt)
{
    const hkf_real_t reach = hkf_mul(f->settings.max_speed, dt);
    const hkf_real_t sigmas2 = HKF_REAL_FROM(HKF_POSITION_GATE_SIGMAS * HKF_POSITION_GATE_SIGMAS);
    int a;
    if (!(f->settings.max_speed > 0)) {
        return 0;
    }
    for (a = 0; a < 3; ++a) {
        const hkf_real_t beyond = hkf_sub(hkf_abs(hkf_sub(z[a], f->x[a])), reach);
        const hkf_real_t s = hkf_add(f->p00[a], hkf_mul(measurement_noise(f, a), r_scale));
        if (beyond > 0 && hkf_mul(beyond, beyond) > hkf_mul(sigmas2, s)) {
            return 1;
        }
    }
    return 0;
}

/* After a gap beyond max_dt: the track as it was held (hold_track), and 1 when the gate refuses z there. */
static int gap_gated(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt)
{
    hold_track(f, dt);
    return gated(f, z, r_scale, dt);
}

/* HKF_OK, or why a position (a measurement, a centre) is refused: not finite, or beyond the range. */
static int check_position(const hkf_real_t z[3])
{
    int a;
    for (a = 0; a < 3; ++a) {
        if (!hkf_is_finite(z[a])) {
            return HKF_ERROR_NON_FINITE;
        }
        if (hkf_abs(z[a]) > HKF_REAL_FROM(HKF_MAX_ABS_POSITION)) {
            return HKF_ERROR_POSITION_RANGE;
        }
    }
    return HKF_OK;
}

/* HKF_OK, or why a measurement z with R scale r_scale, dt s after the last, is refused. */
static int check_measurement(const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt)
{
    const int result = check_position(z);
    if (result != HKF_OK) {
        return result;
    }
    if (!hkf_is_finite(r_scale) || !hkf_is_finite(dt)) {
        return HKF_ERROR_NON_FINITE;
    }
    if (!(r_scale >= HKF_REAL(1.0) && r_scale <= HKF_REAL_FROM(HKF_MAX_POSITION_SCALE))) {
        return HKF_ERROR_SCALE_RANGE;
    }
    return HKF_OK;
}

/* A refused measurement z agrees with the one refused dt s before it: on every axis no farther than a
 * head moves in dt (max_speed x dt) plus HKF_POSITION_GATE_SIGMAS sigmas of two measurements' noise. */
static int agrees_with_refused(const hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale,
                               hkf_real_t dt)
{
    const hkf_real_t reach = hkf_mul(f->settings.max_speed, dt);
    const hkf_real_t sigmas2 = HKF_REAL_FROM(HKF_POSITION_GATE_SIGMAS * HKF_POSITION_GATE_SIGMAS);
    int a;
    for (a = 0; a < 3; ++a) {
        const hkf_real_t beyond = hkf_sub(hkf_abs(hkf_sub(z[a], f->refused_z[a])), reach);
        const hkf_real_t r = hkf_mul(measurement_noise(f, a), r_scale);
        if (beyond > 0 && hkf_mul(beyond, beyond) > hkf_mul(sigmas2, hkf_add(r, r))) {
            return 0;
        }
    }
    return 1;
}

/* A measurement the gate refused: the prediction stands, or after max_gate_rejections in a row that
 * agree with each other (the head is there) the track restarts at it. One that disagrees with the
 * one refused before starts the count again. */
static void refused(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt,
                    hkf_position_output_t *out)
{
    int a;
    if (f->gate_rejections > 0u && !agrees_with_refused(f, z, r_scale, dt)) {
        f->gate_rejections = 0u;
    }
    if (f->gate_rejections >= f->settings.max_gate_rejections) {
        start_track(f, z, r_scale, out);
        return;
    }
    ++f->gate_rejections;
    for (a = 0; a < 3; ++a) {
        f->refused_z[a] = z[a];
    }
    f->history = 0; /* a refused measurement breaks the second difference */
    keep_in_range(f);
    write_output(f, HKF_STATUS_COASTING, HKF_FLAG_GATED, out);
}

/* Eq. 4-7 per axis for z with R = r_scale x the axis's R; calibrated, the motion detector first. */
static void correct_axes(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt)
{
    const hkf_position_settings_t *s = &f->settings;
    const hkf_motion_step_t motion = hkf_motion_prepare(dt, s);
    const int detect = calibrated(f) && (s->q_boost > 0 || s->rate_damping_time > 0);
    int a;
    for (a = 0; a < 3; ++a) {
        hkf_motion_innovation_t in;
        in.r = hkf_mul(measurement_noise(f, a), r_scale);
        in.y = hkf_sub(z[a], f->x[a]);                          /* Eq. 4 */
        in.inv_s = hkf_divisor(hkf_add(f->p00[a], in.r));       /* Eq. 5 */
        if (detect) {
            hkf_motion_lane(&motion, f->noise[a], in, &f->motion[a], &f->p00[a], &f->v[a]);
            in.inv_s = hkf_divisor(hkf_add(f->p00[a], in.r));
        }
        set_axis(f, a, hkf_kalman_correct(axis_of(f, a), in.y, in.r, in.inv_s)); /* Eq. 6-7 */
    }
}

int hkf_position_update(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt,
                        hkf_position_output_t *out)
{
    int result;
    if (f == NULL || z == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = check_measurement(z, r_scale, dt);
    if (result == HKF_OK && f->started && dt <= 0) { /* as the angles' rule: a step back in time is refused */
        result = HKF_ERROR_DT_RANGE;
    }
    if (result != HKF_OK) {
        return result;
    }
    if (!f->started || (check_step(f, dt) == HKF_ERROR_DT_RANGE && !gap_gated(f, z, r_scale, dt))) {
        start_track(f, z, r_scale, out); /* a new track at the measurement (after a gap: within reach of the held one) */
        return HKF_OK;
    }
    if (f->settings.max_dt >= dt) { /* no gap: Eq. 1-3 (after a gap the state is the held track) */
        predict_axes(f, dt);
    }
    if (gated(f, z, r_scale, dt)) {
        refused(f, z, r_scale, dt, out);
        return HKF_OK;
    }
    f->gate_rejections = 0u;
    correct_axes(f, z, r_scale, dt);
    if (calibrated(f)) {
        noise_estimate_update(f, z, dt);
    }
    keep_in_range(f);
    write_output(f, HKF_STATUS_TRACKING, 0u, out);
    return HKF_OK;
}

int hkf_position_predict(hkf_position_filter_t *f, hkf_real_t dt, hkf_position_output_t *out)
{
    int result;
    if (f == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!f->started) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    result = check_step(f, dt);
    if (result != HKF_OK) {
        return result;
    }
    predict_axes(f, dt);
    f->history = 0; /* a frame without a measurement breaks the second difference */
    keep_in_range(f);
    write_output(f, HKF_STATUS_COASTING, 0u, out);
    return HKF_OK;
}

int hkf_position_extrapolate(const hkf_position_filter_t *f, hkf_real_t ahead, hkf_position_output_t *out)
{
    hkf_real_t t, coast;
    int a;
    if (f == NULL || out == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!f->started) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    if (!hkf_is_finite(ahead)) {
        return HKF_ERROR_NON_FINITE;
    }
    if (ahead < 0) {
        return HKF_ERROR_DT_RANGE;
    }
    t = ahead < HKF_REAL_FROM(HKF_MAX_TIME) ? ahead : HKF_REAL_FROM(HKF_MAX_TIME);
    coast = t < f->settings.max_dt ? t : f->settings.max_dt;  /* the rate moves it for up to max_dt */
    for (a = 0; a < 3; ++a) {
        /* Eq. 1-3 over t: [1 t] P [1 t]' + q t^3 / 3; beyond HKF_MAX_TIME (where t^3 would overflow
         * Q16.16) in proportion to the time, so it grows while the position is held */
        hkf_real_t variance = hkf_add(f->p00[a], hkf_kalman_growth(f->p01[a], f->p11[a],
                                                                    hkf_mul(process_noise(f, a), t), t));
        if (ahead > t) {
            variance = hkf_mul(variance, hkf_mul(ahead, HKF_REAL_FROM(1.0 / HKF_MAX_TIME)));
        }
        out->position[a] = bounded(hkf_add(f->x[a], hkf_mul(f->v[a], coast)), HKF_REAL_FROM(HKF_MAX_ABS_POSITION));
        out->rate[a] = ahead > f->settings.max_dt ? 0 : f->v[a];
        out->variance[a] = variance < 0 ? 0 : variance < HKF_REAL_FROM(HKF_MAX_VARIANCE) ? variance
                                                                              : HKF_REAL_FROM(HKF_MAX_VARIANCE);
    }
    out->status = ahead > f->settings.max_dt              ? HKF_STATUS_LOST
                  : ahead > 0 || f->gate_rejections > 0u ? HKF_STATUS_COASTING
                                                         : HKF_STATUS_TRACKING;
    out->flags = ahead > 0 ? HKF_FLAG_EXTRAPOLATED : 0u;
    return HKF_OK;
}

int hkf_position_recenter(hkf_position_filter_t *f)
{
    int a;
    if (f == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!f->started) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    for (a = 0; a < 3; ++a) {
        f->center[a] = f->x[a];
    }
    return HKF_OK;
}

int hkf_position_set_center(hkf_position_filter_t *f, const hkf_real_t center[3])
{
    int a, result;
    if (f == NULL || center == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = check_position(center);
    if (result != HKF_OK) {
        return result;
    }
    for (a = 0; a < 3; ++a) {
        f->center[a] = center[a];
    }
    f->centered = 1;
    return HKF_OK;
}

int hkf_position_recenter_at(hkf_position_filter_t *f, hkf_real_t ahead)
{
    hkf_position_output_t out;
    int a;
    const int result = hkf_position_extrapolate(f, ahead, &out);
    if (result != HKF_OK) {
        return result;
    }
    for (a = 0; a < 3; ++a) {
        f->center[a] = out.position[a];
    }
    return HKF_OK;
}

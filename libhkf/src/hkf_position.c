/* hkf_position.c - see hkf/hkf_position.h. The angles' twin (hkf_filter.c): per
 * axis the same closed-form step (hkf_kalman.h: predict with F = [[1, dt],
 * [0, 1]] and white-acceleration q, Eq. 1-3; update with H = [1, 0], the gain
 * from S = P00 + R, Eq. 4-7) and the same motion adaptation (hkf_two_models.h:
 * HOLD and MOVE mixed by their likelihoods). What is the position's own: R as a
 * measurement's scale times r_const or n, the outlier gate by a head's reach,
 * and the coast of max_dt. */
#include "hkf/hkf_position.h"

#include <stddef.h>

#include "hkf_kalman.h"
#include "hkf_math.h"
#include "hkf_two_models.h"

/* Chosen on truth by construction (dev/eval/position_truth.py; the clips and figures: docs/estimator.md
 * "Head position"): on 5 tuning clips, of 280 settings of q, still_wander and the two rates, the least
 * moving z error (to 0.01 cm) whose still z jitter is at most half the goal's on every one, then the
 * least still of those (stiller buys nothing the player sees). still_wander is 0.3 x r_const per axis.
 * p0_rate is not tuned: a lean's starting speed, sd 32 cm/s. R starts at the face mesh's noise (n's
 * start when calibrated). A head leans at well under 1 m/s; a mesh that misreads the face's scale, or a
 * forged message, jumps further in one step (max_speed); 6 refused frames that agree with each other
 * (0.2 s at 30 fps) restart the track. */
const hkf_position_settings_t hkf_position_default_settings = {
    .process_noise = {HKF_REAL(3000.0), HKF_REAL(3000.0), HKF_REAL(3000.0)}, /* cm^2/s^3 */
    .r_const = {HKF_REAL(0.002), HKF_REAL(0.002), HKF_REAL(0.05)},          /* cm^2 */
    .r_min = HKF_REAL(0.002), /* cm^2: R and n at least the mesh's x and y noise (below, Q16.16 parts from double) */
    .r_max = HKF_REAL(100.0),
    .p0_rate = HKF_REAL(1000.0), /* (cm/s)^2 */
    .max_dt = HKF_REAL(0.5),
    .still_wander = {HKF_REAL(0.0006), HKF_REAL(0.0006), HKF_REAL(0.015)}, /* cm^2 */
    .start_rate = HKF_REAL(0.3),
    .stop_rate = HKF_REAL(1.0),
    .max_speed = HKF_REAL(300.0), /* cm/s */
    .max_gate_rejections = 5u,
};

enum { CENTER_NONE = 0, CENTER_FROM_TRACK = 1, CENTER_EXPLICIT = 2 }; /* as the angles' (hkf_filter.c) */

static int in_range(hkf_real_t x, hkf_real_t low, hkf_real_t high) { return hkf_is_finite(x) && x >= low && x <= high; }

/* q, R, the start and the longest step: HKF_OK or the first bad one's error. */
static int check_noise(const hkf_position_settings_t *s)
{
    int a;
    for (a = 0; a < 3; ++a) {
        if (!in_range(s->process_noise[a], HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_PROCESS_NOISE))) {
            return HKF_ERROR_SETTING_PROCESS_NOISE;
        }
        if (!in_range(s->r_const[a], HKF_REAL_FROM(HKF_MIN_VARIANCE), HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
            return HKF_ERROR_SETTING_R_CONST;
        }
    }
    if (!in_range(s->r_min, HKF_REAL_FROM(HKF_MIN_VARIANCE), HKF_REAL_FROM(HKF_MAX_VARIANCE)) ||
        !in_range(s->r_max, s->r_min, HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
        return HKF_ERROR_SETTING_R_RANGE;
    }
    if (!in_range(s->p0_rate, HKF_REAL_FROM(HKF_MIN_VARIANCE), HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
        return HKF_ERROR_SETTING_P0;
    }
    if (!in_range(s->max_dt, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_TIME)) || s->max_dt == 0) {
        return HKF_ERROR_SETTING_MAX_DT;
    }
    return HKF_OK;
}

/* The adaptation and the gate: HKF_OK or the first bad one's error. */
static int check_adaptation(const hkf_position_settings_t *s)
{
    int a, result = HKF_OK;
    for (a = 0; a < 3 && result == HKF_OK; ++a) {
        result = hkf_is_finite(s->still_wander[a]) && hkf_is_finite(s->start_rate) && hkf_is_finite(s->stop_rate)
                     ? hkf_two_models_check(s->still_wander[a], s->start_rate, s->stop_rate)
                     : HKF_ERROR_SETTING_MOTION;
    }
    if (result != HKF_OK) {
        return result;
    }
    if (!in_range(s->max_speed, HKF_REAL(0.0), HKF_REAL_FROM(HKF_MAX_SPEED)) ||
        (s->max_speed > 0 && s->max_gate_rejections == 0u)) {
        return HKF_ERROR_SETTING_GATE;
    }
    return HKF_OK;
}

int hkf_position_started(const hkf_position_filter_t *f)
{
    return f != NULL && f->status != HKF_STATUS_UNINITIALIZED;
}

hkf_status_t hkf_position_get_status(const hkf_position_filter_t *f)
{
    return f != NULL ? f->status : HKF_STATUS_UNINITIALIZED;
}

static int two_models(const hkf_position_filter_t *f) { return f->settings.start_rate > 0; }

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
        state->noise[a] = f->noise[a] > 0 ? f->noise[a] : f->settings.r_const[a];
        state->moving[a] = two_models(f) ? f->moving[a] : HKF_REAL(1.0);
    }
    return HKF_OK;
}

int hkf_position_init(hkf_position_filter_t *f, const hkf_position_settings_t *s)
{
    int a, result;
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
    for (a = 0; a < 3; ++a) {
        f->noise[a] = 0;
        f->center[a] = 0;
    }
    f->center_source = CENTER_NONE;
    hkf_position_reset(f);
    return HKF_OK;
}

void hkf_position_restart(hkf_position_filter_t *f)
{
    int a;
    if (f == NULL) {
        return;
    }
    for (a = 0; a < 3; ++a) {
        f->x[a] = f->v[a] = f->p00[a] = f->p01[a] = f->p11[a] = f->moving[a] = f->refused_z[a] = 0;
    }
    f->gate_rejections = 0u;
    f->status = HKF_STATUS_UNINITIALIZED;
}

void hkf_position_reset(hkf_position_filter_t *f)
{
    if (f == NULL) {
        return;
    }
    hkf_position_restart(f);
    if (f->center_source != CENTER_EXPLICIT) {
        f->center_source = CENTER_NONE;
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

/* The state into out (may be NULL), and the status kept. */
static void write_output(hkf_position_filter_t *f, hkf_status_t status, unsigned flags, hkf_position_output_t *out)
{
    int a;
    f->status = status;
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

/* R per axis for a measurement of scale r_scale: r_scale x (n, or r_const), within [r_min, r_max]. */
static void measurement_noise(const hkf_position_filter_t *f, hkf_real_t r_scale, hkf_real_t r[3])
{
    int a;
    for (a = 0; a < 3; ++a) {
        const hkf_real_t level = f->noise[a] > 0 ? f->noise[a] : f->settings.r_const[a];
        const hkf_real_t scaled = hkf_mul(level, r_scale);
        r[a] = scaled < f->settings.r_min ? f->settings.r_min : scaled > f->settings.r_max ? f->settings.r_max : scaled;
    }
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

/* Eq. 1-3 per axis (hkf_kalman.h): MOVE's prediction. */
static void predict_axes(hkf_position_filter_t *f, hkf_real_t dt)
{
    int a;
    for (a = 0; a < 3; ++a) {
        set_axis(f, a, hkf_kalman_predict(axis_of(f, a), f->settings.process_noise[a], dt));
    }
}

static int check_step(const hkf_position_filter_t *f, hkf_real_t dt)
{
    if (!hkf_is_finite(dt)) {
        return HKF_ERROR_NON_FINITE;
    }
    return dt > 0 && dt <= f->settings.max_dt ? HKF_OK : HKF_ERROR_DT_RANGE;
}

/* A new track at the measurement z: rate 0, P = diag(R, p0_rate), HOLD; the center there if none is set. */
static void start_track(hkf_position_filter_t *f, const hkf_real_t z[3], const hkf_real_t r[3],
                        hkf_position_output_t *out)
{
    int a;
    for (a = 0; a < 3; ++a) {
        f->x[a] = z[a];
        f->v[a] = 0;
        f->p00[a] = r[a];
        f->p01[a] = 0;
        f->p11[a] = f->settings.p0_rate;
        f->moving[a] = 0;
    }
    if (f->center_source == CENTER_NONE) {
        for (a = 0; a < 3; ++a) {
            f->center[a] = z[a];
        }
        f->center_source = CENTER_FROM_TRACK;
    }
    f->gate_rejections = 0u;
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
        f->moving[a] = 0;
    }
}

/* 1 when the innovation y, of variance s, lies beyond reach + HKF_POSITION_GATE_SIGMAS sqrt(s),
 * tested without a root as (|y| - reach)^2 > sigmas^2 s where |y| exceeds the reach. */
static int beyond_reach(hkf_real_t y, hkf_real_t s, hkf_real_t reach)
{
    const hkf_real_t sigmas2 = HKF_REAL_FROM(HKF_POSITION_GATE_SIGMAS * HKF_POSITION_GATE_SIGMAS);
    const hkf_real_t beyond = hkf_sub(hkf_abs(y), reach);
    return beyond > 0 && hkf_mul(beyond, beyond) > hkf_mul(sigmas2, s);
}

/* The outlier gate on the predicted state: z is refused when on some axis it lies beyond what every
 * model of the head's motion reaches in the step, max_speed dt + 3 sigmas of that model's innovation:
 * MOVE's (S = P00 + R, Eq. 5) and, with the adaptation, HOLD's (the value before MOVE's travel, its
 * variance held_p00 + R + still_wander). So a one-frame jump that MOVE took, with the rate it implied,
 * does not make the head's return an outlier: HOLD reaches it. */
static int gated(const hkf_position_filter_t *f, const hkf_real_t z[3], const hkf_real_t held_p00[3],
                 const hkf_real_t r[3], hkf_real_t dt)
{
    const hkf_real_t reach = hkf_mul(f->settings.max_speed, dt);
    int a;
    if (!(f->settings.max_speed > 0)) {
        return 0;
    }
    for (a = 0; a < 3; ++a) {
        const hkf_real_t y = hkf_sub(z[a], f->x[a]);
        int out = beyond_reach(y, hkf_add(f->p00[a], r[a]), reach);
        if (out && two_models(f) && held_p00 != NULL) {
            const hkf_real_t y_h = hkf_add(y, hkf_mul(f->v[a], dt)); /* z against the value before the travel */
            out = beyond_reach(y_h, hkf_add(hkf_add(held_p00[a], r[a]), f->settings.still_wander[a]), reach);
        }
        if (out) {
            return 1;
        }
    }
    return 0;
}

/* After a gap beyond max_dt: the track as it was held (hold_track), and 1 when the gate refuses z there. */
static int gap_gated(hkf_position_filter_t *f, const hkf_real_t z[3], const hkf_real_t r[3], hkf_real_t dt)
{
    hold_track(f, dt);
    return gated(f, z, NULL, r, dt); /* the held track: no travel, no second model */
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
static int agrees_with_refused(const hkf_position_filter_t *f, const hkf_real_t z[3], const hkf_real_t r[3],
                               hkf_real_t dt)
{
    const hkf_real_t reach = hkf_mul(f->settings.max_speed, dt);
    int a;
    for (a = 0; a < 3; ++a) {
        if (beyond_reach(hkf_sub(z[a], f->refused_z[a]), hkf_add(r[a], r[a]), reach)) {
            return 0;
        }
    }
    return 1;
}

/* A measurement the gate refused: the prediction stands, or after max_gate_rejections in a row that
 * agree with each other (the head is there) the track restarts at it. One that disagrees with the
 * one refused before starts the count again. */
static void refused(hkf_position_filter_t *f, const hkf_real_t z[3], const hkf_real_t r[3], hkf_real_t dt,
                    hkf_position_output_t *out)
{
    int a;
    if (f->gate_rejections > 0u && !agrees_with_refused(f, z, r, dt)) {
        f->gate_rejections = 0u;
    }
    if (f->gate_rejections >= f->settings.max_gate_rejections) {
        start_track(f, z, r, out);
        return;
    }
    ++f->gate_rejections;
    for (a = 0; a < 3; ++a) {
        f->refused_z[a] = z[a];
    }
    keep_in_range(f);
    write_output(f, HKF_STATUS_COASTING, HKF_FLAG_GATED, out);
}

/* Eq. 4-7 per axis for z with R r: by HOLD and MOVE (hkf_two_models.h) when the adaptation is on, MOVE
 * alone when not. The state holds MOVE's prediction, held_p00 the variances before it (HOLD's prior). */
static void correct_axes(hkf_position_filter_t *f, const hkf_real_t z[3], const hkf_real_t held_p00[3],
                         const hkf_real_t r[3], hkf_real_t dt)
{
    const hkf_position_settings_t *s = &f->settings;
    int a;
    if (two_models(f)) {
        const hkf_two_model_step_t c = hkf_two_models_prepare(dt, s->start_rate, s->stop_rate, s->p0_rate);
        for (a = 0; a < 3; ++a) {
            hkf_hold_prior_t hold;
            const hkf_real_t y = hkf_sub(z[a], f->x[a]); /* Eq. 4 */
            hold.p00 = held_p00[a];
            hold.y = hkf_add(y, hkf_mul(f->v[a], dt)); /* HOLD's innovation: z against the value before the travel */
            hold.wander = s->still_wander[a];
            set_axis(f, a, hkf_two_models_update(&c, axis_of(f, a), hold, y, r[a], &f->moving[a]));
        }
        return;
    }
    for (a = 0; a < 3; ++a) {
        const hkf_real_t y = hkf_sub(z[a], f->x[a]); /* Eq. 4 */
        set_axis(f, a, hkf_kalman_correct(axis_of(f, a), y, r[a], hkf_divisor(hkf_add(f->p00[a], r[a])))); /* Eq. 5-7 */
    }
}

int hkf_position_update(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt,
                        hkf_position_output_t *out)
{
    hkf_real_t held_p00[3], r[3];
    int a, result;
    if (f == NULL || z == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    result = check_measurement(z, r_scale, dt);
    if (result == HKF_OK && hkf_position_started(f) && dt <= 0) { /* as the angles' rule: a step back in time is refused */
        result = HKF_ERROR_DT_RANGE;
    }
    if (result != HKF_OK) {
        return result;
    }
    measurement_noise(f, r_scale, r);
    if (!hkf_position_started(f) || (check_step(f, dt) == HKF_ERROR_DT_RANGE && !gap_gated(f, z, r, dt))) {
        start_track(f, z, r, out); /* a new track at the measurement (after a gap: within reach of the held one) */
        return HKF_OK;
    }
    for (a = 0; a < 3; ++a) {
        held_p00[a] = f->p00[a];
    }
    if (f->settings.max_dt >= dt) { /* no gap: Eq. 1-3 (after a gap the state is the held track) */
        predict_axes(f, dt);
    }
    if (gated(f, z, held_p00, r, dt)) {
        refused(f, z, r, dt, out);
        return HKF_OK;
    }
    f->gate_rejections = 0u;
    correct_axes(f, z, held_p00, r, dt);
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
    if (!hkf_position_started(f)) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    result = check_step(f, dt);
    if (result != HKF_OK) {
        return result;
    }
    predict_axes(f, dt);
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
    if (!hkf_position_started(f)) {
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
                                                                    hkf_mul(f->settings.process_noise[a], t), t));
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

int hkf_position_set_noise(hkf_position_filter_t *f, const hkf_real_t noise[3])
{
    int a;
    if (f == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    for (a = 0; noise != NULL && !hkf_noise_levels_ok(noise) && a < 3; ++a) {
        if (!hkf_is_finite(noise[a])) {
            return HKF_ERROR_NON_FINITE;
        }
        if (!(noise[a] > 0)) {
            return HKF_ERROR_NOISE_RANGE;
        }
    }
    for (a = 0; a < 3; ++a) {
        f->noise[a] = noise != NULL ? noise[a] : 0;
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
    f->center_source = CENTER_EXPLICIT;
    return HKF_OK;
}

int hkf_position_get_center(const hkf_position_filter_t *f, hkf_real_t center[3])
{
    int a;
    if (f == NULL || center == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (f->center_source == CENTER_NONE) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    for (a = 0; a < 3; ++a) {
        center[a] = f->center[a];
    }
    return HKF_OK;
}

int hkf_position_recenter(hkf_position_filter_t *f)
{
    if (f == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!hkf_position_started(f)) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    return hkf_position_set_center(f, f->x);
}

int hkf_position_recenter_at(hkf_position_filter_t *f, hkf_real_t ahead)
{
    hkf_position_output_t out;
    const int result = hkf_position_extrapolate(f, ahead, &out);
    if (result != HKF_OK) {
        return result;
    }
    return hkf_position_set_center(f, out.position);
}

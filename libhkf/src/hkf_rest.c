/* hkf_rest.c - see hkf/hkf_rest.h: the player's rest, measured (the variogram of a local-level process). */
#include "hkf/hkf_rest.h"

#include "hkf_internal.h"
#include "hkf_math.h"

const hkf_rest_settings_t hkf_default_rest_settings = {
    .rest_time = HKF_REAL(2.0),
    .rest_reach = HKF_REAL(3.0),
    .stillness = HKF_REAL(1.0),
};

/* The least-squares slope of gamma(L) over L = 1..6 is sum_L (L - 3.5) gamma(L) / 17.5: these weights. */
#if HKF_REST_LAGS != 6
#error "hkf_rest.c's least-squares weights are written for HKF_REST_LAGS 6"
#endif
static const hkf_real_t slope_weight[HKF_REST_LAGS] = {
    HKF_REAL_FROM(-2.5 / 17.5), HKF_REAL_FROM(-1.5 / 17.5), HKF_REAL_FROM(-0.5 / 17.5),
    HKF_REAL_FROM(0.5 / 17.5),  HKF_REAL_FROM(1.5 / 17.5),  HKF_REAL_FROM(2.5 / 17.5),
};

/* n as a hkf_real_t, without floating point in the fixed-point build (n <= 32767). */
static hkf_real_t from_count(unsigned n)
{
#if defined(HKF_REAL_FIXED)
    return (hkf_real_t)((int32_t)(n < 32767u ? n : 32767u) * 65536);
#else
    return (hkf_real_t)n;
#endif
}

/* mean += (x - mean) / count: a running mean that cannot overflow Q16.16 as a sum would. */
static hkf_real_t running_mean(hkf_real_t mean, hkf_real_t x, unsigned count)
{
    return hkf_add(mean, hkf_divide(hkf_sub(x, mean), hkf_divisor(from_count(count))));
}

int hkf_rest_init(hkf_rest_t *r, const hkf_rest_settings_t *s)
{
    if (r == 0 || s == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!hkf_is_finite(s->rest_time) || !hkf_is_finite(s->rest_reach) || !hkf_is_finite(s->stillness)) {
        return HKF_ERROR_SETTING_NON_FINITE;
    }
    if (!(s->rest_time >= 0 && s->rest_time <= HKF_REAL_FROM(HKF_MAX_TIME) && s->rest_reach > 0 &&
          s->rest_reach <= HKF_REAL_FROM(HKF_MAX_LC_THETA) && s->stillness >= 0 &&
          s->stillness <= HKF_REAL_FROM(HKF_MAX_STILLNESS))) {
        return HKF_ERROR_SETTING_REST;
    }
    r->settings = *s;
    r->measured = 0;
    r->measuring = 0;
    r->spoiled = 0u;
    r->refused = 0u;
    return HKF_OK;
}

/* The rest starts over: nothing taken yet. */
static void begin(hkf_rest_t *r)
{
    int l, a;
    r->frames = 0u;
    r->history = 0u;
    r->beyond = 0u;
    r->elapsed = 0;
    r->period = 0;
    for (l = 0; l < HKF_REST_LAGS; ++l) {
        r->pairs[l] = 0u;
        for (a = 0; a < HKF_AXES; ++a) {
            r->gamma[l][a] = 0;
            r->recent[l][a] = 0;
        }
    }
    for (a = 0; a < HKF_AXES; ++a) {
        r->origin[a] = 0;
        r->mean[a] = 0;
        r->square[a] = 0;
    }
}

int hkf_rest_start(hkf_rest_t *r)
{
    if (r == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    begin(r);
    r->measuring = r->settings.rest_time > 0;
    r->spoiled = 0u;
    r->refused = 0u;
    return HKF_OK;
}

int hkf_rest_stop(hkf_rest_t *r)
{
    if (r == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    r->measuring = 0;
    return HKF_OK;
}

static int check_frame(const hkf_real_t z[3], hkf_real_t dt)
{
    int a;
    if (!hkf_is_finite(dt)) {
        return HKF_ERROR_NON_FINITE;
    }
    if (!(dt > 0 && dt <= HKF_REAL_FROM(HKF_MAX_TIME))) {
        return HKF_ERROR_DT_RANGE;
    }
    for (a = 0; z != 0 && a < HKF_AXES; ++a) {
        if (!hkf_is_finite(z[a])) {
            return HKF_ERROR_NON_FINITE;
        }
        if (hkf_abs(z[a]) > HKF_REAL_FROM(HKF_MAX_ABS_ANGLE)) {
            return HKF_ERROR_ANGLE_RANGE;
        }
    }
    return HKF_OK;
}

/* z from the rest's origin (yaw the shorter way round). */
static void from_origin(const hkf_rest_t *r, const hkf_real_t z[3], hkf_real_t x[3])
{
    int a;
    for (a = 0; a < HKF_AXES; ++a) {
        x[a] = hkf_sub(z[a], r->origin[a]);
    }
    x[HKF_AXIS_YAW] = hkf_wrap180(x[HKF_AXIS_YAW]);
}

/* A move: x further from the rest's mean so far than rest_reach beyond 3 standard deviations of the
 * frame noise, on any axis: a noisy camera's resting frames are not moves. The noise so far is read where
 * a steady move cannot hide in it: a move at v per frame adds v^2 L^2 to gamma(L), which
 * n = (4 gamma(1) - gamma(2)) / 6 cancels (9 n = 1.5 (4 gamma(1) - gamma(2))). */
static int is_move(const hkf_rest_t *r, const hkf_real_t x[3])
{
    int a, move = 0;
    for (a = 0; a < HKF_AXES; ++a) {
        const hkf_real_t nine_n = hkf_mul(hkf_sub(hkf_mul(r->gamma[0][a], HKF_REAL(4.0)), r->gamma[1][a]), HKF_REAL(1.5));
        const hkf_real_t noise = hkf_sqrt(nine_n > 0 ? nine_n : 0); /* 3 sqrt(n) */
        move |= hkf_abs(hkf_sub(x[a], r->mean[a])) > hkf_add(r->settings.rest_reach, noise);
    }
    return move;
}

/* x (from the origin) into the variogram, the mean and the recent measurements; dt since the last. */
static void take(hkf_rest_t *r, const hkf_real_t x[3], hkf_real_t dt)
{
    int l, a;
    for (l = 0; l < (int)r->history; ++l) {
        r->pairs[l] += 1u;
        for (a = 0; a < HKF_AXES; ++a) {
            const hkf_real_t d = hkf_sub(x[a], r->recent[l][a]);
            r->gamma[l][a] = running_mean(r->gamma[l][a], hkf_mul(d, d), r->pairs[l]);
        }
    }
    if (r->history > 0u) {
        r->period = running_mean(r->period, dt, r->pairs[0]);
    }
    for (l = HKF_REST_LAGS - 1; l > 0; --l) {
        for (a = 0; a < HKF_AXES; ++a) {
            r->recent[l][a] = r->recent[l - 1][a];
        }
    }
    r->frames += 1u;
    for (a = 0; a < HKF_AXES; ++a) {
        r->recent[0][a] = x[a];
        r->mean[a] = running_mean(r->mean[a], x[a], r->frames);
        r->square[a] = running_mean(r->square[a], hkf_mul(x[a], x[a]), r->frames);
    }
    r->history += r->history < HKF_REST_LAGS ? 1u : 0u;
}

/* HOLD's wander of a measured rest: w = stillness max over the axes of (V - n), that largest V - n (into
 * *excess) bounded at HKF_REST_MAX_WANDER. */
static hkf_real_t wander_of(const hkf_rest_result_t *m, hkf_real_t stillness, hkf_real_t *excess)
{
    int a;
    *excess = 0;
    for (a = 0; a < HKF_AXES; ++a) {
        const hkf_real_t beyond = hkf_sub(m->spread[a], m->noise[a]);
        *excess = beyond > *excess ? beyond : *excess;
    }
    return hkf_mul(stillness, *excess < HKF_REAL_FROM(HKF_REST_MAX_WANDER) ? *excess : HKF_REAL_FROM(HKF_REST_MAX_WANDER));
}

/* The line gamma(L) = 2 n + q dt L through the rest's variogram (least squares): n and q per axis; the
 * rest's spread V about its mean; and HOLD's wander (wander_of), into out. Returns the largest V - n. */
static hkf_real_t fit(const hkf_rest_t *r, hkf_rest_result_t *out)
{
    hkf_real_t excess;
    int l, a;
    out->period = r->period;
    for (a = 0; a < HKF_AXES; ++a) {
        hkf_real_t slope = 0, level = 0, n;
        for (l = 0; l < HKF_REST_LAGS; ++l) {
            slope = hkf_add(slope, hkf_mul(slope_weight[l], r->gamma[l][a]));
            level = hkf_add(level, r->gamma[l][a]);
        }
        level = hkf_sub(hkf_mul(level, HKF_REAL_FROM(1.0 / HKF_REST_LAGS)), hkf_mul(slope, HKF_REAL(3.5))); /* gamma(0) */
        n = hkf_mul(level, HKF_REAL(0.5));
        out->noise[a] = n > 0 ? n : 0;
        out->drift[a] = hkf_divide(slope > 0 ? slope : 0, hkf_divisor(r->period)); /* q = (q dt) / dt */
        out->spread[a] = hkf_sub(r->square[a], hkf_mul(r->mean[a], r->mean[a]));
        out->spread[a] = out->spread[a] > 0 ? out->spread[a] : 0;
        out->center[a] = hkf_add(r->origin[a], r->mean[a]);
    }
    out->center[HKF_AXIS_YAW] = hkf_wrap180(out->center[HKF_AXIS_YAW]);
    out->wander = wander_of(out, r->settings.stillness, &excess);
    return excess;
}

int hkf_rest_set_stillness(hkf_rest_t *r, hkf_real_t stillness)
{
    hkf_real_t excess;
    if (r == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!hkf_is_finite(stillness)) {
        return HKF_ERROR_SETTING_NON_FINITE;
    }
    if (!(stillness >= 0 && stillness <= HKF_REAL_FROM(HKF_MAX_STILLNESS))) {
        return HKF_ERROR_SETTING_REST;
    }
    r->settings.stillness = stillness;
    r->result.wander = wander_of(&r->result, stillness, &excess); /* a result not yet held gets its own at its end */
    return HKF_OK;
}

/* 1 when a rest that ended, fitted as `found` with the spread `excess` beyond its noise, was a head that moved:
 * over HKF_REST_MOVED_WANDER of spread, or over HKF_REST_MOVED_DRIFT of wander's rate on any axis. */
static int moved(const hkf_rest_result_t *found, hkf_real_t excess)
{
    int a, drifted = 0;
    for (a = 0; a < HKF_AXES; ++a) {
        drifted |= found->drift[a] > HKF_REAL_FROM(HKF_REST_MOVED_DRIFT);
    }
    return drifted || excess > HKF_REAL_FROM(HKF_REST_MOVED_WANDER);
}

/* A measurement z of a rest: a move spoils the rest so far (HKF_REST_SPOILED), and z starts it again;
 * otherwise it is taken (HKF_REST_MEASURING). */
static int take_measurement(hkf_rest_t *r, const hkf_real_t z[3], hkf_real_t dt)
{
    hkf_real_t x[3];
    int a, result = HKF_REST_MEASURING;
    from_origin(r, z, x);
    if (r->frames > 0u && is_move(r, x)) {
        if (++r->beyond < HKF_REST_MOVE_FRAMES) { /* one frame beyond: an outlier, not taken; it breaks the differences */
            r->history = 0u;
            r->elapsed = hkf_add(r->elapsed, dt);
            return HKF_REST_MEASURING;
        }
        begin(r); /* a move: not taken; the rest is measured again from this frame */
        r->spoiled += 1u;
        result = HKF_REST_SPOILED;
    }
    r->beyond = 0u;
    if (r->frames == 0u) {
        for (a = 0; a < HKF_AXES; ++a) {
            r->origin[a] = z[a];
        }
        from_origin(r, z, x);
    } else {
        r->elapsed = hkf_add(r->elapsed, dt);
    }
    take(r, x, dt);
    return result;
}

/* A rest that reached rest_time, judged: a move across half the reach spoils it, a head that moved through it
 * (moved) refuses it; otherwise it is measured. The hkf_rest_event_t. */
static int end_rest(hkf_rest_t *r)
{
    hkf_rest_result_t found;
    const hkf_real_t half = hkf_mul(r->settings.rest_reach, HKF_REAL(0.5));
    const hkf_real_t excess = fit(r, &found);
    if (excess > hkf_mul(half, half)) { /* spread beyond the noise as a move across half the reach's */
        begin(r);
        r->spoiled += 1u;
        return HKF_REST_SPOILED;
    }
    if (moved(&found, excess)) { /* a head that swayed or settled: refused, asked again */
        r->last_refused = found;
        begin(r);
        r->spoiled += 1u;
        r->refused += 1u;
        return HKF_REST_SPOILED;
    }
    r->result = found;
    r->measuring = 0;
    r->measured = 1;
    return HKF_REST_MEASURED;
}

int hkf_rest_update(hkf_rest_t *r, const hkf_real_t z[3], hkf_real_t dt)
{
    int result;
    if (r == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!r->measuring) {
        return HKF_REST_IDLE;
    }
    result = check_frame(z, r->frames > 0u ? dt : HKF_REAL(1.0) /* a rest's first: dt ignored */);
    if (result != HKF_OK) {
        return result;
    }
    if (z == 0) {
        r->history = 0u; /* a frame without a measurement breaks the differences */
        return HKF_REST_MEASURING;
    }
    result = take_measurement(r, z, dt);
    /* done at rest_time, to the nearest frame (a sum of float periods falls short of it) */
    if (hkf_add(r->elapsed, hkf_mul(r->period, HKF_REAL(0.5))) >= r->settings.rest_time &&
        r->pairs[HKF_REST_LAGS - 1] >= HKF_REST_LAGS) {
        return end_rest(r);
    }
    return result;
}

int hkf_rest_get_progress(const hkf_rest_t *r, int *measuring, hkf_real_t *progress, unsigned *spoiled, int *measured)
{
    if (r == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (measuring != 0) {
        *measuring = r->measuring;
    }
    if (progress != 0) {
        const hkf_real_t share = hkf_divide(r->elapsed, hkf_divisor(r->settings.rest_time));
        *progress = r->measuring ? (share < HKF_REAL(1.0) ? share : HKF_REAL(1.0)) : (r->measured ? HKF_REAL(1.0) : 0);
    }
    if (spoiled != 0) {
        *spoiled = r->spoiled;
    }
    if (measured != 0) {
        *measured = r->measured;
    }
    return HKF_OK;
}

int hkf_rest_get_result(const hkf_rest_t *r, hkf_rest_result_t *result)
{
    if (r == 0 || result == 0) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    if (!r->measured) {
        return HKF_ERROR_NOT_INITIALIZED;
    }
    *result = r->result;
    return HKF_OK;
}

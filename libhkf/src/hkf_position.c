/* hkf_position.c - see hkf/hkf_position.h. The per-axis step is the angles' own
 * (hkf_filter.c): predict with F = [[1, dt], [0, 1]] and white-acceleration q,
 * update with H = [1, 0], the gain in closed form from S = P00 + R. */
#include "hkf/hkf_position.h"

#include <stddef.h>

#include "hkf_math.h"

void hkf_position_default_settings(hkf_position_settings_t *s)
{
    int a;
    if (s == NULL) {
        return;
    }
    /* chosen on truth by construction (tools/eval/position_truth.py, README "Head position"): the
     * least moving z error whose still z jitter is <= 0.05 cm a frame at 60 cm, on d0 d3 d9 d11 d14 */
    for (a = 0; a < 3; ++a) {
        s->process_noise[a] = HKF_REAL(10.0);  /* cm^2/s^3 */
        s->measurement_noise[a] = a == HKF_POSITION_Z ? HKF_REAL(0.05) : HKF_REAL(0.002);  /* cm^2 */
    }
    s->p0_rate = HKF_REAL(100.0);  /* (cm/s)^2 */
    s->max_dt = HKF_REAL(0.5);
}

static int in_range(hkf_real_t x, hkf_real_t low, hkf_real_t high) { return hkf_is_finite(x) && x >= low && x <= high; }

int hkf_position_init(hkf_position_filter_t *f, const hkf_position_settings_t *s)
{
    int a;
    if (f == NULL || s == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
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
    }
    f->started = 0;
    f->centered = 0;
}

void hkf_position_restart(hkf_position_filter_t *f)
{
    if (f != NULL) {
        f->started = 0;
    }
}

static void write_output(const hkf_position_filter_t *f, hkf_position_output_t *out)
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
}

/* x += v dt; P += F P F' - P + Q, Q = q [[dt^3/3, dt^2/2], [dt^2/2, dt]] */
static void predict_axes(hkf_position_filter_t *f, hkf_real_t dt)
{
    int a;
    for (a = 0; a < 3; ++a) {
        const hkf_real_t qdt = hkf_mul(f->settings.process_noise[a], dt);
        const hkf_real_t qdt2 = hkf_mul(qdt, dt);
        const hkf_real_t p11dt = hkf_mul(f->p11[a], dt);
        f->x[a] = hkf_add(f->x[a], hkf_mul(f->v[a], dt));
        f->p00[a] = hkf_add(f->p00[a], hkf_add(hkf_mul(dt, hkf_add(hkf_add(f->p01[a], f->p01[a]), p11dt)),
                                               hkf_mul(qdt2, hkf_mul(dt, HKF_REAL(0.33333333)))));
        f->p01[a] = hkf_add(f->p01[a], hkf_add(p11dt, hkf_mul(qdt2, HKF_REAL(0.5))));
        f->p11[a] = hkf_add(f->p11[a], qdt);
        hkf_keep_covariance(&f->p00[a], &f->p01[a], &f->p11[a]);
    }
}

static int check_step(const hkf_position_filter_t *f, hkf_real_t dt)
{
    if (!hkf_is_finite(dt)) {
        return HKF_ERROR_NON_FINITE;
    }
    return dt > 0 && dt <= f->settings.max_dt ? HKF_OK : HKF_ERROR_DT_RANGE;
}

int hkf_position_update(hkf_position_filter_t *f, const hkf_real_t z[3], hkf_real_t r_scale, hkf_real_t dt,
                        hkf_position_output_t *out)
{
    int a;
    if (f == NULL || z == NULL) {
        return HKF_ERROR_NULL_ARGUMENT;
    }
    for (a = 0; a < 3; ++a) {
        if (!hkf_is_finite(z[a])) {
            return HKF_ERROR_NON_FINITE;
        }
        if (hkf_abs(z[a]) > HKF_REAL_FROM(HKF_MAX_ABS_POSITION)) {
            return HKF_ERROR_ANGLE_RANGE;
        }
    }
    if (!hkf_is_finite(r_scale) || !hkf_is_finite(dt)) {
        return HKF_ERROR_NON_FINITE;
    }
    if (!(r_scale >= HKF_REAL(1.0) && r_scale <= HKF_REAL_FROM(HKF_MAX_POSITION_SCALE))) {
        return HKF_ERROR_SETTING_R_CONST;
    }
    if (!f->started || check_step(f, dt) == HKF_ERROR_DT_RANGE) {  /* a new track: at the measurement */
        for (a = 0; a < 3; ++a) {
            f->x[a] = z[a];
            f->v[a] = 0;
            f->p00[a] = hkf_mul(f->settings.measurement_noise[a], r_scale);
            f->p01[a] = 0;
            f->p11[a] = f->settings.p0_rate;
            if (!f->centered) {
                f->center[a] = z[a];
            }
        }
        f->started = 1;
        f->centered = 1;
        write_output(f, out);
        return HKF_OK;
    }
    predict_axes(f, dt);
    for (a = 0; a < 3; ++a) {
        const hkf_real_t r = hkf_mul(f->settings.measurement_noise[a], r_scale);
        const hkf_divisor_t s = hkf_divisor(hkf_add(f->p00[a], r));
        const hkf_real_t y = hkf_sub(z[a], f->x[a]);
        const hkf_real_t k0 = hkf_divide(f->p00[a], s), k1 = hkf_divide(f->p01[a], s);
        f->x[a] = hkf_add(f->x[a], hkf_mul(k0, y));
        f->v[a] = hkf_add(f->v[a], hkf_mul(k1, y));
        /* P' = (I - K H) P: p00 r / s, p01 r / s, p11 - k1 p01 */
        f->p11[a] = hkf_sub(f->p11[a], hkf_mul(k1, f->p01[a]));
        f->p00[a] = hkf_mul(k0, r);
        f->p01[a] = hkf_mul(k1, r);
        hkf_keep_covariance(&f->p00[a], &f->p01[a], &f->p11[a]);
    }
    write_output(f, out);
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
    write_output(f, out);
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

/*
 * hkf_settings.c - default settings, the paper's noise-curve presets, and the
 * validation hkf_init applies.
 */
#include "hkf/hkf.h"
#include "hkf_internal.h"
#include "hkf_math.h"
#include "hkf_two_models.h"

/* Paper Table I, amplitude form of Eq. 8, as {tau, lambda, mu, sigma}.
 * Roll: Table I gives tau and lambda as 3.29e5 (FSA-Net) and 9.35e4
 * (Hopenet) to three digits, so tau - lambda is lost; lambda is set so that
 * tau - lambda equals the same model's pitch center error. */
#define HKF_FSANET_PITCH HKF_NOISE_CURVE(315.43, 312.07, -5.19, 132.41)
#define HKF_FSANET_YAW   HKF_NOISE_CURVE(7.64, 4.11, -0.35, 30.87)
#define HKF_FSANET_ROLL  HKF_NOISE_CURVE(329000.0, 328996.64, -0.562, 4440.0)

const hkf_noise_curve_t hkf_noise_fsanet[3] = {HKF_FSANET_PITCH, HKF_FSANET_YAW, HKF_FSANET_ROLL};

const hkf_noise_curve_t hkf_noise_hopenet[3] = {
    HKF_NOISE_CURVE(232.88, 229.18, -8.30, 101.37),
    HKF_NOISE_CURVE(10.74, 7.017, -5.57, 48.28),
    HKF_NOISE_CURVE(93500.0, 93496.30, 0.0476, 2219.0),
};

/* The paper's filter (adaptive R with the FSA-Net curves of Table I) as the
 * base of both setting sets:
 * - r_const: the FSA-Net curves' error at the center (Table I), so constant
 *   and adaptive R differ only in their dependence on the angle.
 * - R clamp: 0.01 deg^2 keeps S > 0 (and is the least n); 1e4 deg^2 is a
 *   100 deg standard deviation, i.e. "ignore".
 * - p0: the first measurement's error (~ R); the head may already be turning
 *   at up to ~50 deg/s.
 * - coast_time 0.25 s: a few dropped frames coast through; longer, the head
 *   has probably stopped, so the pose is held rather than extrapolated away. */
#define HKF_PAPER_BASE                                                          \
    .noise_mode = HKF_NOISE_ADAPTIVE,                                           \
    .noise = {HKF_FSANET_PITCH, HKF_FSANET_YAW, HKF_FSANET_ROLL},               \
    .r_const = {HKF_REAL(3.6), HKF_REAL(3.53), HKF_REAL(3.36)},                 \
    .r_max = HKF_REAL(10000.0),                                                 \
    .lc_xi = HKF_REAL(0.618),                                                   \
    .lc_theta = HKF_REAL(2.0),                                                  \
    .p0_angle = HKF_REAL(10.0),                                                 \
    .p0_rate = HKF_REAL(2500.0),                                                \
    .r_min = HKF_REAL(0.01),                                                    \
    .gate_sigma = HKF_REAL(0.0),                                                \
    .max_gate_rejections = 5u,                                                  \
    .coast_time = HKF_REAL(0.25),                                               \
    .max_dt = HKF_REAL(1.0)

/* Defaults (chosen with the noise calibration's defaults beside them,
 * hkf_calibration.c): the motion adaptation: MOVE's q 16000
 * deg^2/s^3 (within fixed point's range), a resting head's estimate wandering
 * by 0.03 deg^2 beyond R until the player's rest measures it (hkf_rest.h,
 * hkf_set_wander; libhkf 1.2, 0.3 before: raw's onset where no rest is
 * measured), a still head starting to move at 0.05 per s, a moving one
 * stopping at 16 per s; loop closure off. q, start_rate and stop_rate chosen
 * on the truth clips of the tuning clips (dev/eval/adaptation_study/);
 * reported on the others (docs/evaluation.md). */
const hkf_settings_t hkf_default_settings = {
    HKF_PAPER_BASE,
    .process_noise = {HKF_REAL(16000.0), HKF_REAL(16000.0), HKF_REAL(16000.0)},
    .loop_closure = HKF_LOOP_CLOSURE_OFF,
    .still_wander = HKF_REAL(0.03),
    .start_rate = HKF_REAL(0.05),
    .stop_rate = HKF_REAL(16.0),
};

/* The paper's filter alone: loop closure on (xi 0.618, theta 2 deg), q by
 * reasoning (a mirror glance turns the head ~60 deg in ~0.5 s, accelerations
 * near 1000 deg/s^2), no calibration or motion adaptation. */
const hkf_settings_t hkf_paper_settings = {
    HKF_PAPER_BASE,
    .process_noise = {HKF_REAL(500.0), HKF_REAL(1000.0), HKF_REAL(500.0)},
    .loop_closure = HKF_LOOP_CLOSURE_NORM,
};

hkf_model_noise_t hkf_model_noise_of(const hkf_settings_t *s)
{
    hkf_model_noise_t m;
    int a;
    m.noise_mode = s->noise_mode;
    for (a = 0; a < HKF_AXES; ++a) {
        m.noise[a] = s->noise[a];
        m.r_const[a] = s->r_const[a];
    }
    m.r_min = s->r_min;
    m.r_max = s->r_max;
    return m;
}

static int all_finite(const hkf_real_t *v, int n)
{
    int i;
    for (i = 0; i < n; ++i) {
        if (!hkf_is_finite(v[i])) {
            return 0;
        }
    }
    return 1;
}

static int settings_finite(const hkf_settings_t *s)
{
    const hkf_real_t scalars[] = {s->r_min, s->r_max, s->lc_xi, s->lc_theta, s->p0_angle, s->p0_rate,
                                  s->gate_sigma, s->coast_time, s->max_dt, s->still_wander, s->start_rate,
                                  s->stop_rate};
    int a;
    for (a = 0; a < HKF_AXES; ++a) {
        const hkf_noise_curve_t *c = &s->noise[a];
#if defined(HKF_REAL_FIXED)
        const hkf_real_t curve[] = {c->floor, c->mu, c->sigma};
#else
        const hkf_real_t curve[] = {c->tau, c->lambda, c->mu, c->sigma};
#endif
        if (!all_finite(curve, (int)(sizeof curve / sizeof curve[0]))) {
            return 0;
        }
    }
    return all_finite(s->process_noise, HKF_AXES) && all_finite(s->r_const, HKF_AXES) &&
           all_finite(scalars, (int)(sizeof scalars / sizeof scalars[0]));
}

/* One Eq. 8 curve: its width, and its floor, depth and centre within the build's range. */
int hkf_curve_check(const hkf_noise_curve_t *c)
{
    if (!(c->sigma >= HKF_REAL_FROM(HKF_MIN_SIGMA) && c->sigma <= HKF_REAL_FROM(HKF_MAX_SIGMA))) {
        return HKF_ERROR_SETTING_SIGMA;
    }
#if defined(HKF_REAL_FIXED)
    if (!(hkf_abs(c->floor) <= HKF_REAL_FROM(HKF_MAX_CURVE_FLOOR) &&
          c->curvature_q24 >= -HKF_MAX_CURVATURE * 16777216 && c->curvature_q24 <= HKF_MAX_CURVATURE * 16777216 &&
          hkf_abs(c->mu) <= HKF_REAL_FROM(HKF_MAX_ABS_ANGLE))) {
        return HKF_ERROR_SETTING_CURVE;
    }
#else
    if (!(hkf_abs(c->tau) <= HKF_REAL_FROM(HKF_MAX_VARIANCE) && hkf_abs(c->lambda) <= HKF_REAL_FROM(HKF_MAX_VARIANCE) &&
          hkf_abs(c->mu) <= HKF_REAL_FROM(HKF_MAX_ABS_ANGLE))) {
        return HKF_ERROR_SETTING_CURVE;
    }
#endif
    return HKF_OK;
}

static int check_curves(const hkf_settings_t *s)
{
    int a, result = HKF_OK;
    for (a = 0; a < HKF_AXES && result == HKF_OK; ++a) {
        result = hkf_curve_check(&s->noise[a]);
    }
    return result;
}

/* How R and q are chosen: the mode, the curves, R's clamp, the constant R and q per axis. */
static int check_noise(const hkf_settings_t *s)
{
    int a, result;
    if (s->noise_mode != HKF_NOISE_CONSTANT && s->noise_mode != HKF_NOISE_ADAPTIVE &&
        s->noise_mode != HKF_NOISE_ADAPTIVE_SQUARED) {
        return HKF_ERROR_SETTING_NOISE_MODE;
    }
    result = check_curves(s);
    if (result != HKF_OK) {
        return result;
    }
    if (!(s->r_min >= HKF_REAL_FROM(HKF_MIN_VARIANCE) && s->r_min <= s->r_max &&
          s->r_max <= HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
        return HKF_ERROR_SETTING_R_RANGE;
    }
    for (a = 0; a < HKF_AXES; ++a) {
        if (!(s->r_const[a] > 0 && s->r_const[a] <= HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
            return HKF_ERROR_SETTING_R_CONST;
        }
        if (!(s->process_noise[a] >= 0 && s->process_noise[a] <= HKF_REAL_FROM(HKF_MAX_PROCESS_NOISE))) {
            return HKF_ERROR_SETTING_PROCESS_NOISE;
        }
    }
    return HKF_OK;
}

/* The track: loop closure (Eq. 9), the first variances, the gate, coasting and the longest step. */
static int check_track(const hkf_settings_t *s)
{
    if (s->loop_closure != HKF_LOOP_CLOSURE_OFF && s->loop_closure != HKF_LOOP_CLOSURE_NORM &&
        s->loop_closure != HKF_LOOP_CLOSURE_PER_AXIS) {
        return HKF_ERROR_SETTING_LOOP_CLOSURE;
    }
    if (!(s->lc_xi >= 0 && s->lc_xi <= HKF_REAL(1.0))) {
        return HKF_ERROR_SETTING_LC_XI;
    }
    if (!(s->lc_theta >= 0 && s->lc_theta <= HKF_REAL_FROM(HKF_MAX_LC_THETA))) {
        return HKF_ERROR_SETTING_LC_THETA;
    }
    if (!(s->p0_angle > 0 && s->p0_rate > 0 && s->p0_angle <= HKF_REAL_FROM(HKF_MAX_VARIANCE) &&
          s->p0_rate <= HKF_REAL_FROM(HKF_MAX_VARIANCE))) {
        return HKF_ERROR_SETTING_P0;
    }
    if (!(s->gate_sigma >= 0 && s->gate_sigma <= HKF_REAL_FROM(HKF_MAX_GATE_SIGMA)) ||
        (s->gate_sigma > 0 && s->max_gate_rejections == 0u)) {
        return HKF_ERROR_SETTING_GATE;
    }
    if (!(s->coast_time > 0 && s->coast_time <= HKF_REAL_FROM(HKF_MAX_TIME))) {
        return HKF_ERROR_SETTING_COAST_TIME;
    }
    if (!(s->max_dt > 0 && s->max_dt <= HKF_REAL_FROM(HKF_MAX_TIME))) {
        return HKF_ERROR_SETTING_MAX_DT;
    }
    return HKF_OK;
}

/* The motion adaptation (not in the paper). */
static int check_adaptation(const hkf_settings_t *s)
{
    return hkf_two_models_check(s->still_wander, s->start_rate, s->stop_rate);
}

/* The first bad setting's error, in the order of hkf_result_t, or HKF_OK. */
int hkf_settings_check(const hkf_settings_t *s)
{
    int result;
    if (!settings_finite(s)) {
        return HKF_ERROR_SETTING_NON_FINITE;
    }
    result = check_noise(s);
    if (result == HKF_OK) {
        result = check_track(s);
    }
    if (result == HKF_OK) {
        result = check_adaptation(s);
    }
    return result;
}

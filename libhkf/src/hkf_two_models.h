/*
 * hkf_two_models.h - the motion adaptation (private; hkf.h states it, docs/libhkf.md
 * derives it): per axis, two models of the head's motion over one step, mixed
 * by how well each predicted the measurement. Not in the paper, whose filter
 * is the MOVE model alone.
 *
 *   HOLD  the head rests: the value stays (x_h = x, P_h00 = p00), the rate is
 *         0; a measurement wanders about the rest by w = still_wander beyond
 *         the frame noise (R_h = R + w: the estimate of a resting face drifts
 *         over a few frames, which n does not see), and a move that starts
 *         from rest has a rate of variance V = p0_rate.
 *   MOVE  the paper's constant-velocity model with process noise q (Eq. 1-3).
 *
 * Which one applies follows a two-state continuous-time Markov chain: a still
 * head starts to move at a = start_rate per s, a moving one stops at
 * b = stop_rate per s. With mu the probability of MOVE after the last step,
 * its prior for this step (the chain's solution over dt) is
 *   pi = m + (mu - m) exp(-(a + b) dt),  m = a / (a + b) (MOVE's long-run share).
 * Each model predicts the measurement z with its own innovation y_j and
 * variance S_j = P_j00 + R_j, a Gaussian likelihood L_j = N(y_j; 0, S_j). Bayes:
 *   mu' = pi L_m / (pi L_m + (1 - pi) L_h),
 *   L_m / L_h = sqrt(S_h / S_m) exp(d),  d = (y_h^2 / S_h - y_m^2 / S_m) / 2.
 * Each model then takes z (Eq. 6-7; HOLD as a 1-state filter with R_h), and
 * the two posteriors are merged into one Gaussian with the same mean and
 * covariance as their mixture (Bar-Shalom's GPB1 with two models), HOLD's
 * posterior being (x_h, 0) with covariance diag(P_h, V):
 *   x = x_h + mu' (x_m - x_h),  v = mu' v_m,
 *   P = mu' P_m + (1 - mu') P_h + mu' (1 - mu') d d',  d = (x_m - x_h, v_m).
 * V keeps MOVE's next prediction wide after a rest (P00 grows by P11 dt^2), so
 * a move is likelier under MOVE than under HOLD's wider R_h however large w.
 * A still head keeps mu' near 0: HOLD's variance, which q does not inflate,
 * sets a small gain, so a still output. A move makes MOVE's prediction the
 * likelier within a frame or two: its gain, set by q, follows the head. When
 * the head stops, the rate's own innovations return mu' to 0, the rate to 0:
 * no overshoot. mu' is continuous in the measurement: no decision flips on a
 * rounding difference.
 */
#ifndef HKF_TWO_MODELS_H
#define HKF_TWO_MODELS_H

#include "hkf_kalman.h"

/* start_rate, stop_rate: 0 (off; a moving head never stops) or within [HKF_MIN_RATE, HKF_MAX_RATE] */
static inline int hkf_two_models_rate_ok(hkf_real_t rate)
{
    return rate == 0 || (rate >= HKF_REAL_FROM(HKF_MIN_RATE) && rate <= HKF_REAL_FROM(HKF_MAX_RATE));
}

/* The adaptation's settings (the angles' and the position's): HKF_OK or HKF_ERROR_SETTING_MOTION. */
static inline int hkf_two_models_check(hkf_real_t still_wander, hkf_real_t start_rate, hkf_real_t stop_rate)
{
    const int ok = still_wander >= 0 && still_wander <= HKF_REAL_FROM(HKF_MAX_VARIANCE) &&
                   hkf_two_models_rate_ok(start_rate) && hkf_two_models_rate_ok(stop_rate);
    return ok ? HKF_OK : HKF_ERROR_SETTING_MOTION;
}

/* What one step of dt takes from the settings, the same for every axis. */
typedef struct {
    hkf_real_t dt;
    hkf_real_t share, decay; /* m = a / (a + b) and exp(-(a + b) dt) */
    hkf_real_t start_var;    /* V: the rate's variance when a move starts from rest */
} hkf_two_model_step_t;

static inline hkf_two_model_step_t hkf_two_models_prepare(hkf_real_t dt, hkf_real_t start_rate, hkf_real_t stop_rate,
                                                          hkf_real_t start_var)
{
    const hkf_real_t rates = hkf_add(start_rate, stop_rate); /* > 0: start_rate > 0 turns the adaptation on */
    hkf_two_model_step_t c;
    c.dt = dt;
    c.share = hkf_divide(start_rate, hkf_divisor(rates));
    c.decay = hkf_exp_neg(hkf_mul(rates, dt));
    c.start_var = start_var;
    return c;
}

/* mu' from the prior pi and d, r = sqrt(S_h / S_m) (above), with exp of -|d|
 * alone, so nothing overflows: for d > 0 the odds' both sides divided by exp(d). */
static HKF_ALWAYS_INLINE hkf_real_t hkf_two_models_posterior(hkf_real_t pi, hkf_real_t d, hkf_real_t r)
{
#if defined(HKF_REAL_FIXED)
    return hkf_two_models_posterior_q16(pi, d, r); /* the same in 64-bit products (hkf_math_fixed.c) */
#else
    const hkf_real_t e = hkf_exp_neg(d > 0 ? d : -d);
    const hkf_real_t move = d > 0 ? hkf_mul(pi, r) : hkf_mul(hkf_mul(pi, r), e);
    const hkf_real_t hold = d > 0 ? hkf_mul(hkf_sub(HKF_REAL(1.0), pi), e) : hkf_sub(HKF_REAL(1.0), pi);
    const hkf_real_t sum = hkf_add(move, hold);
    return sum > 0 ? move / sum : pi; /* a true quotient: 1 / sum overflows when both sides are denormal */
#endif
}

/* HOLD's prior for one axis: the value's variance before MOVE's prediction,
 * HOLD's innovation z - x (MOVE's plus the travel v dt; yaw wrapped), and w,
 * its measurement's variance beyond R (still_wander: the angles' one for all
 * three, the position's per axis). */
typedef struct {
    hkf_real_t p00, y, wander;
} hkf_hold_prior_t;

/* One axis's measurement update by both models: `move` is the state after
 * MOVE's prediction (Eq. 1-3), y its innovation z - x_m (Eq. 4), r = R;
 * *mu the probability of MOVE, updated. The posteriors' difference is formed
 * from the innovations, not from the values, so a yaw the prediction wrapped
 * does not enter it. */
static HKF_ALWAYS_INLINE hkf_axis_t hkf_two_models_update(const hkf_two_model_step_t *c, hkf_axis_t move,
                                                          hkf_hold_prior_t hold, hkf_real_t y, hkf_real_t r,
                                                          hkf_real_t *restrict mu)
{
    const hkf_real_t one = HKF_REAL(1.0);
    const hkf_real_t pi = hkf_add(c->share, hkf_mul(hkf_sub(*mu, c->share), c->decay));
    const hkf_real_t travel = hkf_mul(move.v, c->dt);                     /* x_m - x_h before the update */
    const hkf_real_t y_h = hold.y;
    const hkf_real_t p_h = hold.p00;
    const hkf_real_t r_h = hkf_add(r, hold.wander);
    const hkf_real_t s_h = hkf_add(p_h, r_h);
    const hkf_divisor_t inv_h = hkf_divisor(s_h);                         /* Eq. 5 per model */
    const hkf_divisor_t inv_m = hkf_divisor(hkf_add(move.p00, r));
    const hkf_real_t d = hkf_mul(hkf_sub(hkf_divide(hkf_mul(y_h, y_h), inv_h), hkf_divide(hkf_mul(y, y), inv_m)),
                                 HKF_REAL(0.5));
    const hkf_real_t m = hkf_two_models_posterior(pi, d, hkf_sqrt(hkf_divide(s_h, inv_m)));
    const hkf_axis_t moved = hkf_kalman_correct(move, y, r, inv_m);       /* Eq. 6-7, MOVE */
    const hkf_real_t k_h = hkf_divide(p_h, inv_h);                        /* Eq. 6-7, HOLD */
    const hkf_real_t p_h_post = hkf_mul(p_h, hkf_divide(r_h, inv_h));
    const hkf_real_t dx = hkf_sub(hkf_add(travel, hkf_mul(hkf_divide(move.p00, inv_m), y)), hkf_mul(k_h, y_h));
    const hkf_real_t spread = hkf_mul(m, hkf_sub(one, m));
    hkf_axis_t out;
    *mu = m;
    out.x = hkf_sub(moved.x, hkf_mul(hkf_sub(one, m), dx));              /* x_h + mu' (x_m - x_h) */
    out.v = hkf_mul(m, moved.v);
    out.p00 = hkf_add(hkf_add(p_h_post, hkf_mul(m, hkf_sub(moved.p00, p_h_post))), hkf_mul(hkf_mul(spread, dx), dx));
    out.p01 = hkf_add(hkf_mul(m, moved.p01), hkf_mul(hkf_mul(spread, dx), moved.v));
    out.p11 = hkf_add(hkf_add(hkf_mul(m, moved.p11), hkf_mul(hkf_sub(one, m), c->start_var)),
                      hkf_mul(hkf_mul(spread, moved.v), moved.v));
    hkf_keep_covariance(&out.p00, &out.p01, &out.p11);
    return out;
}

#endif /* HKF_TWO_MODELS_H */

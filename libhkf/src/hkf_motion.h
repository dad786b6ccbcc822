/*
 * hkf_motion.h - the position's motion detector, one lane at a time
 * (hkf_position.c; hkf_position.h documents its settings). Not in the paper.
 */
#ifndef HKF_MOTION_H
#define HKF_MOTION_H

#include "hkf/hkf_position.h"
#include "hkf_internal.h"
#include "hkf_math.h"
#include "hkf_noise_estimate.h"

/* The detector's weights for one step of dt, and the settings its walk reads. */
typedef struct {
    hkf_real_t alpha;          /* the innovation's low-pass weight, dt / (dt + q_boost_time) */
    hkf_real_t spread;         /* (2 - alpha) / alpha = 1 + 2 q_boost_time / dt */
    hkf_real_t damping;        /* the rate's decay weight while still; 0: never */
    hkf_divisor_t still;       /* 1 / still_threshold (1 when that is 0) */
    hkf_real_t q_boost, threshold, dt; /* the settings' q_boost and motion_threshold; the step */
} hkf_motion_step_t;

/* One lane's innovation this step: y, its R and 1 / S. */
typedef struct {
    hkf_real_t y, r;
    hkf_divisor_t inv_s;
} hkf_motion_innovation_t;

static HKF_ALWAYS_INLINE hkf_motion_step_t hkf_motion_prepare(hkf_real_t dt, const hkf_position_settings_t *s)
{
    const hkf_real_t one = HKF_REAL(1.0);
    hkf_motion_step_t c;
    c.alpha = hkf_step_weight(dt, s->q_boost_time);
    c.spread = hkf_add(one, hkf_divide(hkf_add(s->q_boost_time, s->q_boost_time), hkf_divisor(dt)));
    c.damping = s->rate_damping_time > 0 && s->still_threshold > 0 ? hkf_step_weight(dt, s->rate_damping_time) : 0;
    c.still = hkf_divisor(s->still_threshold > 0 ? s->still_threshold : one);
    c.q_boost = s->q_boost;
    c.threshold = s->motion_threshold;
    c.dt = dt;
    return c;
}

/* The random walk per s for a detector evidence: n q_boost times the
 * evidence's excess over the threshold (0 at or below it), at most
 * HKF_MAX_BOOSTED_PROCESS_NOISE; a product that saturates Q16.16 is beyond
 * that cap anyway. */
static inline hkf_real_t hkf_motion_walk(hkf_real_t q_boost, hkf_real_t threshold, hkf_real_t n, hkf_real_t evidence)
{
    const hkf_real_t e = hkf_sub(evidence, threshold);
    const hkf_real_t positive = e > 0 ? e : 0; /* NaN (0 inf) reads as none */
    const hkf_real_t excess = positive < HKF_REAL(10000.0) ? positive : HKF_REAL(10000.0);
    const hkf_real_t walk = hkf_mul(hkf_mul(n, q_boost), excess);
    const hkf_real_t cap = HKF_REAL_FROM(HKF_MAX_BOOSTED_PROCESS_NOISE);
    return walk < cap ? walk : cap;
}

/* One lane of the detector and the boost it drives, for this step (hkf.h):
 * m += alpha (y - m) low-passes the innovation y; while the lane is still y
 * is white with variance S and m has variance S alpha / (2 - alpha), so
 * m^2 (2 - alpha) / (alpha S) is the evidence of a motion beyond chance.
 * Beyond the threshold the lane takes a random walk (hkf_motion_walk for the
 * lane's measured noise n), added to the predicted variance p00 alone (the
 * caller recomputes S):
 * the filter follows the measurement while the head moves, and the rate,
 * whose variance is not raised, is not thrown past a stop (boosting the
 * acceleration's noise instead overshoots fast stops). The walk of the
 * evidence confirmed by the previous frame counts in full; this frame's own
 * adds at most R, so a one-frame blip moves the filter at most about half way
 * (test_position.c: test_blip_capped_step_followed). Below still_threshold the rate decays,
 * with time constant rate_damping_time up to half of it and less and less
 * above, so the filter stops with the head. Both are continuous in the
 * evidence: no decision flips on rounding. */
static HKF_ALWAYS_INLINE void hkf_motion_lane(const hkf_motion_step_t *c, hkf_real_t n, hkf_motion_innovation_t in,
                                              hkf_real_t *restrict m, hkf_real_t *restrict p00, hkf_real_t *restrict rate)
{
    const hkf_real_t one = HKF_REAL(1.0), dt = c->dt;
    const hkf_real_t before = *m;
    const hkf_real_t now = hkf_add(before, hkf_mul(c->alpha, hkf_sub(in.y, before)));
    const hkf_real_t evidence = hkf_divide(hkf_mul(hkf_mul(now, now), c->spread), in.inv_s);
    const hkf_real_t confirmed = hkf_divide(hkf_mul(hkf_mul(before, before), c->spread), in.inv_s);
    const hkf_real_t fresh = hkf_mul(hkf_motion_walk(c->q_boost, c->threshold, n, evidence), dt);
    /* calm: 1 up to half still_threshold, then down to 0 at it */
    const hkf_real_t ramp = hkf_sub(HKF_REAL(2.0), hkf_divide(hkf_add(evidence, evidence), c->still));
    const hkf_real_t below_one = ramp < one ? ramp : one;
    const hkf_real_t calm = below_one > 0 ? below_one : 0;
    *m = now;
    *p00 = hkf_add(hkf_add(*p00, hkf_mul(hkf_motion_walk(c->q_boost, c->threshold, n, confirmed), dt)),
                   fresh < in.r ? fresh : in.r);
    *rate = hkf_sub(*rate, hkf_mul(hkf_mul(c->damping, calm), *rate));
}

#endif /* HKF_MOTION_H */

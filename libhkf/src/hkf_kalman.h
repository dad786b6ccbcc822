/*
 * hkf_kalman.h - the per-axis closed-form Kalman step (private), written once
 * for the angles (hkf_filter.c) and the position (hkf_position.c), in every
 * numeric build.
 *
 * The paper's 6-state filter, x = (pitch, yaw, roll, their rates),
 * F = [[I, dt I], [0, I]], H = [I 0], with Q, R and P0 block-diagonal per
 * axis, splits exactly into three 2-state filters (value, rate) with a scalar
 * gain: no matrix inverse. Per axis P = [[p00, p01], [p01, p11]].
 */
#ifndef HKF_KALMAN_H
#define HKF_KALMAN_H

#include "hkf_internal.h"
#include "hkf_math.h"

/* One axis's state: the value (deg or cm), its rate (per s) and covariance. */
typedef struct {
    hkf_real_t x, v;
    hkf_real_t p00, p01, p11;
} hkf_axis_t;

/* A lane from a filter's per-axis arrays (the angles' and the position's keep their state so), and back. */
static HKF_ALWAYS_INLINE hkf_axis_t hkf_axis_gather(hkf_real_t x, hkf_real_t v, hkf_real_t p00, hkf_real_t p01, hkf_real_t p11)
{
    hkf_axis_t lane;
    lane.x = x;
    lane.v = v;
    lane.p00 = p00;
    lane.p01 = p01;
    lane.p11 = p11;
    return lane;
}

static HKF_ALWAYS_INLINE void hkf_axis_scatter(hkf_axis_t lane, hkf_real_t *x, hkf_real_t *v, hkf_real_t *p00,
                                              hkf_real_t *p01, hkf_real_t *p11)
{
    *x = lane.x;
    *v = lane.v;
    *p00 = lane.p00;
    *p01 = lane.p01;
    *p11 = lane.p11;
}

/* The value's variance growth over dt: (F P F' + Q)_00 - p00, with qdt = q dt. */
static inline hkf_real_t hkf_kalman_growth(hkf_real_t p01, hkf_real_t p11, hkf_real_t qdt, hkf_real_t dt)
{
    const hkf_real_t cross = hkf_mul(dt, hkf_add(hkf_add(p01, p01), hkf_mul(dt, p11)));
    return hkf_add(cross, hkf_mul(hkf_mul(qdt, dt), hkf_mul(dt, HKF_REAL(0.33333333333333333))));
}

/* Paper Eq. 1-3 for one axis:
 *   x = F x                   x += v dt
 *   P = F P F' + Q            Q = q [[dt^3/3, dt^2/2], [dt^2/2, dt]]
 * (Q: continuous white-noise acceleration of density q.) The terms of Q are
 * formed as ((q dt) dt) dt so each product keeps its digits in fixed point. */
static HKF_ALWAYS_INLINE hkf_axis_t hkf_kalman_predict(hkf_axis_t a, hkf_real_t q, hkf_real_t dt)
{
    const hkf_real_t qdt = hkf_mul(q, dt);
    hkf_axis_t b;
    b.x = hkf_add(a.x, hkf_mul(a.v, dt));
    b.v = a.v;
    b.p00 = hkf_add(a.p00, hkf_kalman_growth(a.p01, a.p11, qdt, dt));
    b.p01 = hkf_add(hkf_add(a.p01, hkf_mul(dt, a.p11)), hkf_mul(hkf_mul(qdt, dt), HKF_REAL(0.5)));
    b.p11 = hkf_add(a.p11, qdt);
    hkf_keep_covariance(&b.p00, &b.p01, &b.p11);
    return b;
}

/* Paper Eq. 6-7 for one axis, with the innovation y = z - x (Eq. 4), R r and
 * 1 / S (Eq. 5: S = p00 + r):
 *   K = P H' S^-1 = (p00, p01) / S
 *   x = x + K y,  P = (I - K H) P, with 1 - k0 = R / S (no cancellation). */
static HKF_ALWAYS_INLINE hkf_axis_t hkf_kalman_correct(hkf_axis_t a, hkf_real_t y, hkf_real_t r, hkf_divisor_t inv_s)
{
    const hkf_real_t k0 = hkf_divide(a.p00, inv_s);
    const hkf_real_t k1 = hkf_divide(a.p01, inv_s);
    const hkf_real_t one_minus_k0 = hkf_divide(r, inv_s);
    hkf_axis_t b;
    b.x = hkf_add(a.x, hkf_mul(k0, y));
    b.v = hkf_add(a.v, hkf_mul(k1, y));
    b.p11 = hkf_sub(a.p11, hkf_mul(k1, a.p01));
    b.p01 = hkf_mul(a.p01, one_minus_k0);
    b.p00 = hkf_mul(a.p00, one_minus_k0); /* stays > 0 in float even when P >> R (found by fuzz_libhkf) */
    hkf_keep_covariance(&b.p00, &b.p01, &b.p11);
    return b;
}

#endif /* HKF_KALMAN_H */

/*
 * test_equations.c - each equation of the paper, against numbers worked out
 * by hand (or from Table I) in the comments.
 */
#include "test_support.h"

/* The track's start: the first measurement starts it: angle = z, rate = 0,
 * P = diag(p0), centre = z. dt of the first call is ignored. */
static void test_first_measurement_starts_track(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3], c[3];
    (void)state;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 5, -30, 2);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    assert_near(out.angle[0], 5, TEST_TOL);
    assert_near(out.angle[1], -30, TEST_TOL);
    assert_near(out.angle[2], 2, TEST_TOL);
    assert_near(out.rate[1], 0, TEST_TOL);
    assert_near(out.variance[1], 4, TEST_TOL);
    assert_int_equal(out.status, HKF_STATUS_TRACKING);
    assert_true(out.flags & HKF_FLAG_REACQUIRED);
    assert_int_equal(hkf_get_center(&f, c), HKF_OK);
    assert_near(c[1], -30, TEST_TOL);
}

/* Eq. 1-3 from P = diag(4, 8), q = 12, dt = 0.5:
 *   p00 = 4 + dt^2 8 + q dt^3 / 3 = 4 + 2 + 0.5 = 6.5
 *   p01 = dt 8 + q dt^2 / 2 = 4 + 1.5 = 5.5
 *   p11 = 8 + q dt = 14
 * and with that predicted P, a measurement 3 deg off, R = 2 (Eq. 4-7):
 *   S = 8.5, K = (6.5, 5.5) / 8.5
 *   angle = z0 + 3 * 6.5 / 8.5, rate = 3 * 5.5 / 8.5
 *   p00 = (1 - K0) 6.5 = 13 / 8.5, p01 = (1 - K0) 5.5 = 11 / 8.5,
 *   p11 = 14 - K1 5.5 = 14 - 30.25 / 8.5 */
static void test_predict_eq1_to_3(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3];
    (void)state;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 1, 2, 3);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    assert_int_equal(hkf_predict(&f, R(0.5), &out), HKF_OK);
    assert_near(out.variance[0], 6.5, TEST_TOL);
    assert_near(out.variance[1], 6.5, TEST_TOL);
    assert_near(out.angle[2], 3, TEST_TOL); /* rate 0: the angle stays */
    assert_int_equal(out.status, HKF_STATUS_COASTING);
}

static void test_update_eq4_to_7(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out, ahead;
    hkf_real_t z[3];
    const double k0 = 6.5 / 8.5, k1 = 5.5 / 8.5;
    const double p00 = 13.0 / 8.5, p01 = 11.0 / 8.5, p11 = 14.0 - 30.25 / 8.5;
    int a;
    (void)state;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 1, 2, 3);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    set3(z, 4, 5, 6);
    assert_int_equal(hkf_update(&f, z, R(0.5), &out), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_near(out.angle[a], (a + 1) + 3.0 * k0, TEST_TOL);
        assert_near(out.rate[a], 3.0 * k1, TEST_TOL);
        assert_near(out.variance[a], p00, TEST_TOL);
        assert_near(out.r[a], 2, TEST_TOL);
    }
    assert_int_equal(out.status, HKF_STATUS_TRACKING);
    assert_int_equal(out.flags, 0u);
    /* p01 and p11 show through a prediction 1 s ahead (Eq. 1-3 once more):
     * p00 + 2 p01 + p11 + q / 3 */
    assert_int_equal(hkf_extrapolate(&f, R(1), &ahead), HKF_OK);
    assert_near(ahead.variance[0], p00 + 2.0 * p01 + p11 + 4.0, TEST_TOL);
    assert_near(ahead.angle[0], 1 + 3.0 * k0 + 3.0 * k1, TEST_TOL);
}

/* The shipped estimators' curves (hkf_noise_mesh_pnp, hkf_noise_whenet) in every numeric build: hkf_init
 * takes them (Q16.16 refused them with error -33 when they were written as positional initialisers, tau
 * landing in its floor) and Eq. 8 gives, within the build's rounding, what the fitted values give in
 * double. The values as dev/fit fitted them (hkf_estimator_curves.c). */
static void test_shipped_curves_in_every_build(void **state)
{
    static const double fitted[2][3][4] = {
        {{10002.921, 10000.0, -2.092, 688.07}, {10001.931, 9999.999, -5.515, 1391.36}, {29.637, 27.126, 0.94, 34.82}},
        {{10002.981, 10000.0, -4.72, 748.61}, {4.517, 1.055, 5.016, 20.49}, {10001.315, 10000.0, -1.592, 819.28}},
    };
    const hkf_noise_curve_t *const shipped[2] = {hkf_noise_mesh_pnp, hkf_noise_whenet};
    static const double angles[] = {-90.0, -60.0, -20.0, 0.0, 5.0, 30.0, 75.0, 99.0};
    int model, a, i;
    (void)state;
    for (model = 0; model < 2; ++model) {
        hkf_settings_t s = hkf_default_settings;
        hkf_filter_t f;
        for (a = 0; a < 3; ++a) {
            s.noise[a] = shipped[model][a];
        }
        assert_int_equal(hkf_init(&f, &s), HKF_OK);
        for (a = 0; a < 3; ++a) {
            for (i = 0; i < (int)(sizeof angles / sizeof angles[0]); ++i) {
                const double *c = fitted[model][a], x = angles[i] - c[2];
                const double e = c[0] - c[1] * exp(-x * x / (2.0 * c[3] * c[3]));
                const double expected = e < D(s.r_min) ? D(s.r_min) : e > D(s.r_max) ? D(s.r_max) : e;
                assert_near(hkf_observation_noise(&f, a, R(angles[i])), expected, 2e-3 * expected + 2e-3);
            }
        }
    }
}

/* Eq. 8, amplitude form, with the FSA-Net curves of Table I (values worked
 * out in double: yaw 3.53 at mu, 7.5833 at 90, 6.1960 at -45; pitch 3.5996
 * at 0, 14.1886 at 30; roll 3.36 at mu (the centre error the preset chose;
 * float rounds lambda = 328996.64 by up to 0.016), 6.8880 at 20). */
static void test_observation_noise_eq8(void **state)
{
    hkf_settings_t s = hkf_default_settings;
    hkf_filter_t f;
    (void)state;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_YAW, R(-0.35)), 3.53, 1e-4);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_YAW, R(90)), 7.58328, 1e-4);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_YAW, R(-45)), 6.19602, 1e-4);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_PITCH, R(0)), 3.59963, 1e-3);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_PITCH, R(30)), 14.18861, 2e-3);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_ROLL, R(-0.562)), 3.36, 0.02);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_ROLL, R(20)), 6.88796, 0.02);
    assert_near(hkf_observation_noise(&f, 3, R(0)), 0, 0);

    /* e read as a standard deviation: R = e^2 */
    s.noise_mode = HKF_NOISE_ADAPTIVE_SQUARED;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_YAW, R(90)), 7.58328 * 7.58328, 2e-3);

    /* the clamp applies in every mode */
    s.r_max = R(5);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_YAW, R(90)), 5, 0);
    s.noise_mode = HKF_NOISE_CONSTANT;
    s.r_min = R(4);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_YAW, R(90)), 4, 0); /* r_const 3.53 */

    /* a curve deeper than its plateau (e < 0) is clamped, never negative */
    s = hkf_default_settings;
    s.noise[1] = table_curve(7.64, 20, -0.35, 30.87); /* FSA-Net yaw, lambda 4.11 -> 20 */
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    assert_near(hkf_observation_noise(&f, HKF_AXIS_YAW, R(0)), D(s.r_min), 0);
}

/* The R an update uses is Eq. 8 at the (loop-closed) measured angle. */
static void test_update_uses_adaptive_r(void **state)
{
    hkf_settings_t s = hkf_default_settings;
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3];
    (void)state;
    s.loop_closure = HKF_LOOP_CLOSURE_OFF;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 0, 88, 0);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    set3(z, 0, 90, 20);
    assert_int_equal(hkf_update(&f, z, R(1.0 / 30.0), &out), HKF_OK);
    assert_near(out.r[HKF_AXIS_YAW], 7.58328, 1e-4);
    assert_near(out.r[HKF_AXIS_ROLL], 6.88796, 0.02);
}

/* Runs one filter that starts at `start` and takes `z`; returns the posterior. */
static hkf_output_t two_steps(const hkf_settings_t *s, const hkf_real_t start[3], const hkf_real_t z[3])
{
    hkf_filter_t f;
    hkf_output_t out;
    assert_int_equal(hkf_init(&f, s), HKF_OK);
    assert_int_equal(hkf_update(&f, start, R(0), &out), HKF_OK);
    assert_int_equal(hkf_update(&f, z, R(1.0 / 30.0), &out), HKF_OK);
    return out;
}

/* Eq. 9: a measurement within theta_lc of the centre is replaced by
 * xi z + (1 - xi) kappa, so the filter must give exactly what a filter
 * without loop closure gives for that replaced measurement. */
static void test_loop_closure_eq9(void **state)
{
    hkf_settings_t on = plain_settings(), off;
    hkf_real_t start[3], z[3], fused[3];
    hkf_output_t a, b;
    int k;
    (void)state;
    on.loop_closure = HKF_LOOP_CLOSURE_NORM;
    on.lc_xi = R(0.618);
    on.lc_theta = R(2);
    off = on;
    off.loop_closure = HKF_LOOP_CLOSURE_OFF;

    set3(start, 10, 20, 30); /* the first measurement is the centre */
    set3(z, 10.6, 20.8, 30.0); /* |d| = 1 */
    set3(fused, 10 + 0.618 * 0.6, 20 + 0.618 * 0.8, 30);
    a = two_steps(&on, start, z);
    b = two_steps(&off, start, fused);
    assert_true(a.flags & HKF_FLAG_LOOP_CLOSURE);
    for (k = 0; k < 3; ++k) {
        assert_near(a.angle[k], D(b.angle[k]), TEST_TOL);
        assert_near(a.rate[k], D(b.rate[k]), 10 * TEST_TOL);
    }

    /* further than theta_lc: untouched */
    set3(z, 11.5, 21.5, 30.0); /* |d| = 2.12 */
    a = two_steps(&on, start, z);
    b = two_steps(&off, start, z);
    assert_false(a.flags & HKF_FLAG_LOOP_CLOSURE);
    assert_near(a.angle[1], D(b.angle[1]), 0);
}

/* The boundary: |d| exactly theta_lc closes; just beyond does not.
 * theta = 5 and d = (3, 4, 0) make the norm exactly 5 in any precision. */
static void test_loop_closure_boundary(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_real_t start[3], z[3];
    hkf_output_t out;
    (void)state;
    s.loop_closure = HKF_LOOP_CLOSURE_NORM;
    s.lc_theta = R(5);
    set3(start, 0, 0, 0);
    set3(z, 3, 4, 0);
    out = two_steps(&s, start, z);
    assert_true(out.flags & HKF_FLAG_LOOP_CLOSURE);
    set3(z, 3, 4.001, 0);
    out = two_steps(&s, start, z);
    assert_false(out.flags & HKF_FLAG_LOOP_CLOSURE);

    /* per-axis mode: each axis against theta alone, so (3, 4, 0) with
     * theta 3.5 closes pitch and roll, not yaw */
    s.loop_closure = HKF_LOOP_CLOSURE_PER_AXIS;
    s.lc_theta = R(3.5);
    set3(z, 3, 4, 0);
    out = two_steps(&s, start, z);
    assert_true(out.flags & HKF_FLAG_LOOP_CLOSURE);
    {
        hkf_settings_t off = s;
        hkf_real_t fused[3];
        hkf_output_t ref;
        off.loop_closure = HKF_LOOP_CLOSURE_OFF;
        set3(fused, 3 * 0.618, 4, 0);
        ref = two_steps(&off, start, fused);
        assert_near(out.angle[0], D(ref.angle[0]), TEST_TOL);
        assert_near(out.angle[1], D(ref.angle[1]), TEST_TOL);
    }
}

/* Eq. 9 across the yaw seam: centre 179, z = -179 is 2 deg away, not 358. */
static void test_loop_closure_across_yaw_seam(void **state)
{
    hkf_settings_t s = plain_settings(), off;
    hkf_real_t start[3], z[3], fused[3];
    hkf_output_t a, b;
    (void)state;
    s.loop_closure = HKF_LOOP_CLOSURE_NORM;
    s.lc_theta = R(2.5);
    off = s;
    off.loop_closure = HKF_LOOP_CLOSURE_OFF;
    set3(start, 0, 179, 0);
    set3(z, 0, -179, 0);
    set3(fused, 0, 179 + 0.618 * 2 - 360, 0);
    a = two_steps(&s, start, z);
    b = two_steps(&off, start, fused);
    assert_true(a.flags & HKF_FLAG_LOOP_CLOSURE);
    assert_near(a.angle[1], D(b.angle[1]), TEST_TOL);
}

/* Eq. 9 then Eq. 8 across the seam: the loop-closed measurement is wrapped
 * before R is read off the curve. Centre 179, z = -179: closed to
 * 179 + 0.618 x 2 = 180.236 = -179.764, where a yaw curve dipping at
 * mu = 175 (sigma 10) is at its far value tau = 10 - not at its dip, where
 * the unwrapped 180.236 would put it (R ~ 1.8). */
static void test_loop_closure_then_r_across_the_seam(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_real_t start[3], z[3];
    hkf_output_t out;
    (void)state;
    s.loop_closure = HKF_LOOP_CLOSURE_NORM;
    s.lc_theta = R(2.5);
    s.noise_mode = HKF_NOISE_ADAPTIVE;
    s.noise[1] = table_curve(10, 9, 175, 10);
    set3(start, 0, 179, 0);
    set3(z, 0, -179, 0);
    out = two_steps(&s, start, z);
    assert_true(out.flags & HKF_FLAG_LOOP_CLOSURE);
    assert_near(out.r[1], 10, 0.01);
}

/* Yaw through +-180: a head turning steadily at 40 deg/s from 100 deg, with
 * perfect measurements, is followed across the seam (at 2 s) without a
 * jump, and every published yaw is in [-180, 180); then back again. */
static void test_yaw_crosses_180(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3];
    const double dt = 1.0 / 30.0;
    double truth = 100.0, previous = 100.0;
    int i;
    (void)state;
    s.r_const[1] = R(0.5);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    for (i = 0; i < 240; ++i) {
        const double rate = i < 120 ? 40.0 : -40.0; /* turns back after 4 s */
        truth = yaw_diff(truth + (i > 0 ? rate * dt : 0.0), 0.0);
        set3(z, 0, truth, 0);
        assert_int_equal(hkf_update(&f, z, R(dt), &out), HKF_OK);
        assert_true(D(out.angle[1]) >= -180 && D(out.angle[1]) < 180);
        assert_true(fabs(yaw_diff(D(out.angle[1]), previous)) < 3.0); /* no jump */
        previous = D(out.angle[1]);
        if ((i >= 50 && i < 120) || i >= 200) { /* once the rate has settled */
            assert_near(yaw_diff(D(out.angle[1]), truth), 0, 0.05);
            assert_near(out.rate[1], rate, 0.5);
        }
    }
}

/* Eq. 1-3 from a P with cross terms (test_predict_eq1_to_3 starts from a
 * diagonal one): the P after test_update_eq4_to_7's update,
 *   P00 = 13 / 8.5, P01 = 11 / 8.5, P11 = 14 - 30.25 / 8.5,
 * predicted dt = 0.25 s with q = 12:
 *   p00 = P00 + 2 dt P01 + dt^2 P11 + q dt^3 / 3
 *   p01 = P01 + dt P11 + q dt^2 / 2
 * p00 shows in the predicted variance; p01 in the rate's gain p01 / (p00 + R)
 * of an update 2 deg off the prediction, made from a copy of the same state. */
static void test_predict_with_cross_terms(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f, copy;
    hkf_output_t out, predicted;
    hkf_real_t z[3];
    const double P00 = 13.0 / 8.5, P01 = 11.0 / 8.5, P11 = 14.0 - 30.25 / 8.5, dt = 0.25, q = 12.0;
    const double p00 = P00 + 2 * dt * P01 + dt * dt * P11 + q * dt * dt * dt / 3;
    const double p01 = P01 + dt * P11 + q * dt * dt / 2;
    int a;
    (void)state;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 1, 2, 3);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    set3(z, 4, 5, 6);
    assert_int_equal(hkf_update(&f, z, R(0.5), &out), HKF_OK);
    copy = f;
    assert_int_equal(hkf_predict(&copy, R(dt), &predicted), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_near(predicted.variance[a], p00, 4 * TEST_TOL);
        assert_near(predicted.angle[a], D(out.angle[a]) + D(out.rate[a]) * dt, TEST_TOL);
    }
    set3(z, D(predicted.angle[0]) + 2, D(predicted.angle[1]) + 2, D(predicted.angle[2]) + 2);
    assert_int_equal(hkf_update(&f, z, R(dt), &out), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_near(out.angle[a], D(predicted.angle[a]) + 2 * p00 / (p00 + 2), 4 * TEST_TOL);
        assert_near(out.rate[a], D(predicted.rate[a]) + 2 * p01 / (p00 + 2), 4 * TEST_TOL);
    }
}

/* The yaw seam at exactly +-180 (and beyond, 540): angles are in [-180, 180),
 * so a first measurement of +180 starts the track at -180, and so does its
 * centre; 540 is the same direction. Extrapolation across the seam stays in
 * range: 0.2 s ahead of 178.7 deg turning at +9 deg/s is -179.5, not +180.5. */
static void test_yaw_at_exactly_180(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out, ahead;
    hkf_real_t z[3], c[3];
    int i;
    (void)state;
    for (i = 0; i < 3; ++i) {
        const double yaw[3] = {180.0, 540.0, -180.0};
        assert_int_equal(hkf_init(&f, &s), HKF_OK);
        set3(z, 0, yaw[i], 0);
        assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
        assert_near(out.angle[1], -180, TEST_TOL);
        assert_int_equal(hkf_get_center(&f, c), HKF_OK);
        assert_near(c[1], -180, TEST_TOL);
    }
    for (i = 1; i <= 9; ++i) { /* every whole number of turns from +180 (and -180) is -180 */
        assert_int_equal(hkf_init(&f, &s), HKF_OK);
        set3(z, 0, 180.0 + 360.0 * i, 0);
        assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
        assert_near(out.angle[1], -180, TEST_TOL);
        assert_int_equal(hkf_init(&f, &s), HKF_OK);
        set3(z, 0, -180.0 - 360.0 * i, 0);
        assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
        assert_near(out.angle[1], -180, TEST_TOL);
    }
    set3(c, 0, 180, 0); /* an explicit centre of +180 is -180 too */
    assert_int_equal(hkf_set_center(&f, c), HKF_OK);
    assert_int_equal(hkf_get_center(&f, c), HKF_OK);
    assert_near(c[1], -180, TEST_TOL);
    /* a head turning at 9 deg/s up to 178.7 deg, then extrapolated 0.2 s */
    s.r_const[1] = R(0.01);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    for (i = 0; i < 60; ++i) {
        set3(z, 0, 178.7 - 9.0 * (59 - i) / 30.0, 0);
        assert_int_equal(hkf_update(&f, z, R(i == 0 ? 0 : 1.0 / 30.0), &out), HKF_OK);
    }
    assert_near(out.angle[1], 178.7, 0.05);
    assert_near(out.rate[1], 9, 0.2);
    assert_int_equal(hkf_extrapolate(&f, R(0.2), &ahead), HKF_OK);
    assert_true(D(ahead.angle[1]) >= -180 && D(ahead.angle[1]) < 180);
    assert_near(yaw_diff(D(ahead.angle[1]), 178.7 + 1.8), 0, 0.1);
}

/* Every step keeps yaw in [-180, 180): a correction that pulls a still
 * estimate at 179.5 towards a measurement of -179.5 (1 deg away, across the
 * seam) lands at -179.x, not 180.x; a coasting head turning at 30 deg/s
 * through the seam is predicted across it, in range. And the largest angle
 * accepted, HKF_MAX_ABS_ANGLE (3600 = 10 turns), is accepted and wrapped. */
static void test_every_step_wraps_yaw(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3];
    int i;
    (void)state;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 0, 179.5, 0);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    set3(z, 0, -179.5, 0);
    assert_int_equal(hkf_update(&f, z, R(1.0 / 64.0), &out), HKF_OK);
    assert_true(D(out.angle[1]) >= -180 && D(out.angle[1]) < -179.5 + 1e-3);
    /* coasting through the seam */
    s.r_const[1] = R(0.01);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    for (i = 0; i < 60; ++i) {
        set3(z, 0, 170.0 + 30.0 * i / 30.0 - 59.0, 0);
        assert_int_equal(hkf_update(&f, z, R(i == 0 ? 0 : 1.0 / 30.0), &out), HKF_OK);
    }
    for (i = 0; i < 12; ++i) { /* 0.4 s at 30 deg/s from 170: 182 = -178 */
        assert_int_equal(hkf_predict(&f, R(1.0 / 30.0), &out), HKF_OK);
        assert_true(D(out.angle[1]) >= -180 && D(out.angle[1]) < 180);
    }
    assert_near(yaw_diff(D(out.angle[1]), 182.0), 0, 0.3);
    /* the range's endpoint */
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, -HKF_MAX_ABS_ANGLE, HKF_MAX_ABS_ANGLE, HKF_MAX_ABS_ANGLE);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    assert_near(out.angle[1], 0, TEST_TOL);
}

/* Eq. 9's threshold is inclusive per axis too (the norm's boundary is
 * test_loop_closure_boundary's): an axis exactly lc_theta from the centre is
 * closed (2: exact in every build). */
static void test_loop_closure_per_axis_at_exactly_theta(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_real_t start[3], z[3];
    hkf_output_t out;
    (void)state;
    set3(start, 0, 0, 0);
    s.loop_closure = HKF_LOOP_CLOSURE_PER_AXIS;
    s.lc_theta = R(2);
    set3(z, 0, 2, 9);
    out = two_steps(&s, start, z);
    assert_true(out.flags & HKF_FLAG_LOOP_CLOSURE);
    set3(z, 9, 2.25, -9); /* no axis within 2 */
    out = two_steps(&s, start, z);
    assert_false(out.flags & HKF_FLAG_LOOP_CLOSURE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_first_measurement_starts_track),
        cmocka_unit_test(test_predict_eq1_to_3),
        cmocka_unit_test(test_update_eq4_to_7),
        cmocka_unit_test(test_observation_noise_eq8),
        cmocka_unit_test(test_update_uses_adaptive_r),
        cmocka_unit_test(test_loop_closure_eq9),
        cmocka_unit_test(test_loop_closure_boundary),
        cmocka_unit_test(test_loop_closure_across_yaw_seam),
        cmocka_unit_test(test_yaw_crosses_180),
        cmocka_unit_test(test_predict_with_cross_terms),
        cmocka_unit_test(test_yaw_at_exactly_180),
        cmocka_unit_test(test_shipped_curves_in_every_build),
        cmocka_unit_test(test_every_step_wraps_yaw),
        cmocka_unit_test(test_loop_closure_then_r_across_the_seam),
        cmocka_unit_test(test_loop_closure_per_axis_at_exactly_theta),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

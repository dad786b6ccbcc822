/*
 * test_behaviour.c - what a head tracker needs beyond the paper's equations:
 * coasting and losing the track, re-acquiring, the innovation gate,
 * extrapolation, recentring, and state carried across calls.
 */
#include "test_support.h"

#include "head_motion_sim.h"

static const hkf_real_t frame_dt = HKF_REAL_FROM(1.0 / 30.0);

/* Starts a filter on a head turning at `rate` deg/s in yaw (perfect measurements). */
static void track_turning_head(hkf_filter_t *f, const hkf_settings_t *s, double rate, int frames)
{
    hkf_real_t z[3];
    int i;
    assert_int_equal(hkf_init(f, s), HKF_OK);
    for (i = 0; i < frames; ++i) {
        set3(z, 0, rate * D(frame_dt) * i, 0);
        assert_int_equal(hkf_update(f, z, frame_dt, NULL), HKF_OK);
    }
}

/* The coasting rule: predicts follow the rate until coast_time has passed
 * without a measurement; then the track is LOST, the rate zeroed, the angle held. */
static void test_coast_then_lost(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t before, out;
    double held;
    int i;
    (void)state;
    s.coast_time = R(0.19);
    s.r_const[1] = R(0.1);
    track_turning_head(&f, &s, 30.0, 60);
    assert_int_equal(hkf_get_output(&f, &before), HKF_OK);
    assert_near(before.rate[1], 30, 0.5);

    for (i = 1; i <= 5; ++i) { /* 5 frames = 0.167 s < 0.19 s */
        assert_int_equal(hkf_predict(&f, frame_dt, &out), HKF_OK);
        assert_int_equal(out.status, HKF_STATUS_COASTING);
        assert_near(out.angle[1], D(before.angle[1]) + D(before.rate[1]) * D(frame_dt) * i, 1e-3);
        assert_true(out.variance[1] > before.variance[1]);
    }
    assert_int_equal(hkf_predict(&f, frame_dt, &out), HKF_OK); /* 0.2 s */
    assert_int_equal(out.status, HKF_STATUS_LOST);
    assert_near(out.rate[1], 0, 0);
    held = D(out.angle[1]);
    for (i = 0; i < 100; ++i) {
        assert_int_equal(hkf_predict(&f, frame_dt, &out), HKF_OK);
    }
    assert_int_equal(out.status, HKF_STATUS_LOST);
    assert_near(out.angle[1], held, 0);
}

/* The next measurement after LOST restarts the track from it, keeping the centre. */
static void test_reacquire_after_lost(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3], centre[3];
    int i;
    (void)state;
    s.coast_time = R(0.1);
    track_turning_head(&f, &s, 10.0, 30);
    for (i = 0; i < 10; ++i) {
        assert_int_equal(hkf_predict(&f, frame_dt, &out), HKF_OK);
    }
    assert_int_equal(out.status, HKF_STATUS_LOST);
    set3(z, 3, -40, 1);
    assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_OK);
    assert_int_equal(out.status, HKF_STATUS_TRACKING);
    assert_true(out.flags & HKF_FLAG_REACQUIRED);
    assert_near(out.angle[1], -40, TEST_TOL);
    assert_near(out.rate[1], 0, 0);
    assert_near(out.variance[1], D(s.p0_angle), TEST_TOL);
    assert_int_equal(hkf_get_center(&f, centre), HKF_OK);
    assert_near(centre[1], 0, TEST_TOL); /* still the first measurement's */
}

/* The gate (off by default) rejects an outlier: the state only predicts. */
static void test_gate_rejects_outlier_then_reacquires(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f, predicted;
    hkf_output_t out, expected;
    hkf_real_t z[3];
    int i;
    (void)state;
    assert_true(hkf_default_settings.gate_sigma == 0);
    s.gate_sigma = R(4);
    s.max_gate_rejections = 3u;
    track_turning_head(&f, &s, 0.0, 30);
    set3(z, 0, 45, 0); /* far beyond 4 sigma */
    for (i = 0; i < 3; ++i) {
        predicted = f;
        assert_int_equal(hkf_predict(&predicted, frame_dt, &expected), HKF_OK);
        assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_OK);
        assert_true(out.flags & HKF_FLAG_GATED);
        assert_false(out.flags & HKF_FLAG_REACQUIRED);
        assert_near(out.angle[1], D(expected.angle[1]), 0);
        assert_near(out.variance[1], D(expected.variance[1]), 0);
    }
    /* the fourth in a row is believed: the head really moved */
    assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_OK);
    assert_true(out.flags & HKF_FLAG_REACQUIRED);
    assert_near(out.angle[1], 45, TEST_TOL);
    /* and an ordinary measurement after that is accepted */
    set3(z, 0, 45.5, 0);
    assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_OK);
    assert_int_equal(out.flags & HKF_FLAG_GATED, 0u);
    assert_int_equal(out.status, HKF_STATUS_TRACKING);
}

/* Extrapolation predicts without touching the filter. */
static void test_extrapolate_is_pure(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f, copy;
    hkf_output_t now, ahead;
    (void)state;
    s.r_const[1] = R(0.1);
    track_turning_head(&f, &s, 60.0, 60);
    copy = f;
    assert_int_equal(hkf_get_output(&f, &now), HKF_OK);
    assert_int_equal(hkf_extrapolate(&f, R(0.01), &ahead), HKF_OK);
    assert_memory_equal(&f, &copy, sizeof f);
    assert_near(ahead.angle[1], D(now.angle[1]) + D(now.rate[1]) * 0.01, 1e-3);
    assert_true(ahead.flags & HKF_FLAG_EXTRAPOLATED);
    assert_true(ahead.variance[1] > now.variance[1]);
    assert_int_equal(hkf_extrapolate(&f, R(0), &ahead), HKF_OK);
    assert_near(ahead.angle[1], D(now.angle[1]), 0);
}

/* Recentre: to an explicit pose (kept across reset) or to the current estimate. */
static void test_recenter_and_reset(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3], c[3];
    (void)state;
    s.loop_closure = HKF_LOOP_CLOSURE_NORM;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    assert_int_equal(hkf_get_center(&f, c), HKF_ERROR_NOT_INITIALIZED);
    set3(z, 1, 2, 3);
    assert_int_equal(hkf_update(&f, z, 0, &out), HKF_OK);
    set3(z, 1, 12, 3);
    assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_OK);
    assert_int_equal(hkf_recenter(&f), HKF_OK);
    assert_int_equal(hkf_get_center(&f, c), HKF_OK);
    assert_near(c[1], D(out.angle[1]), 0);

    /* an automatic centre is forgotten by reset; an explicit one is not */
    set3(c, 0, 190, 0); /* wraps to -170 */
    assert_int_equal(hkf_set_center(&f, c), HKF_OK);
    hkf_reset(&f);
    assert_int_equal(hkf_predict(&f, frame_dt, &out), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_get_center(&f, c), HKF_OK);
    assert_near(c[1], -170, TEST_TOL);
    /* a measurement 1 deg from the explicit centre is pulled onto it */
    set3(z, 0, -170, 0);
    assert_int_equal(hkf_update(&f, z, 0, &out), HKF_OK);
    set3(z, 0, -169, 0);
    assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_OK);
    assert_true(out.flags & HKF_FLAG_LOOP_CLOSURE);
    assert_int_equal(hkf_init(&f, &s), HKF_OK); /* init forgets everything */
    assert_int_equal(hkf_get_center(&f, c), HKF_ERROR_NOT_INITIALIZED);
    /* the centre a track set (its first measurement) is forgotten by reset: the next track sets its own */
    set3(z, 1, 12, 3);
    assert_int_equal(hkf_update(&f, z, 0, &out), HKF_OK);
    assert_int_equal(hkf_get_center(&f, c), HKF_OK);
    assert_near(c[1], 12, TEST_TOL);
    hkf_reset(&f);
    assert_int_equal(hkf_get_center(&f, c), HKF_ERROR_NOT_INITIALIZED);
    set3(z, -2, 40, 1);
    assert_int_equal(hkf_update(&f, z, 0, &out), HKF_OK);
    assert_int_equal(hkf_get_center(&f, c), HKF_OK);
    assert_near(c[1], 40, TEST_TOL);
    assert_near(c[0], -2, TEST_TOL);
}

#if defined(HKF_REAL_FIXED)
/* The fixed-point filter's state within the Cortex-M0 budget (libhkf 1.1's goal: hkf_filter_t <= 256 B; the
 * firmware table of ./run mcu prints it per target). */
static void test_state_within_the_m0_budget(void **state)
{
    (void)state;
    assert_true(sizeof(hkf_filter_t) <= 256u);
}
#endif

/* hkf_init copies the settings in every numeric build: a settings struct
 * scribbled over after hkf_init (a temporary gone out of scope) changes
 * nothing; the run matches one from settings left alone. */
static void test_settings_copied(void **state)
{
    enum { FRAMES = 300 };
    sim_config_t config = sim_default_config();
    sim_t sim;
    hkf_settings_t kept = hkf_default_settings, scribbled = hkf_default_settings;
    hkf_filter_t a, b;
    hkf_output_t oa, ob;
    double previous = 0.0;
    int i, k;
    (void)state;
    assert_int_equal(hkf_init(&a, &kept), HKF_OK);
    assert_int_equal(hkf_init(&b, &scribbled), HKF_OK);
    memset(&scribbled, 0xA5, sizeof scribbled);
    sim_init(&sim, &config, 9u);
    for (i = 0; i < FRAMES; ++i) {
        sim_frame_t frame;
        hkf_real_t z[3], dt;
        int ra, rb;
        sim_next(&sim, &frame);
        dt = R(frame.time - previous);
        previous = frame.time;
        set3(z, frame.measured[0], frame.measured[1], frame.measured[2]);
        ra = frame.valid ? hkf_update(&a, z, dt, &oa) : hkf_predict(&a, dt, &oa);
        rb = frame.valid ? hkf_update(&b, z, dt, &ob) : hkf_predict(&b, dt, &ob);
        assert_int_equal(ra, rb);
        if (ra == HKF_OK) {
            for (k = 0; k < 3; ++k) {
                assert_near(oa.angle[k], D(ob.angle[k]), 0);
                assert_near(oa.variance[k], D(ob.variance[k]), 0);
            }
        }
    }
}

/* State carries across calls: a run fed in two chunks, with the filter
 * moved to other storage in between (as a controller might persist it),
 * gives exactly the outputs of an uninterrupted run. */
static void test_state_carried_across_chunks(void **state)
{
    enum { FRAMES = 900 };
    sim_config_t config = sim_default_config();
    sim_t sim;
    sim_frame_t frames[FRAMES];
    hkf_filter_t whole, first, second;
    hkf_output_t a, b;
    double previous = 0.0;
    int i, k;
    (void)state;
    sim_init(&sim, &config, 7u);
    for (i = 0; i < FRAMES; ++i) {
        sim_next(&sim, &frames[i]);
    }
    assert_int_equal(hkf_init(&whole, &hkf_default_settings), HKF_OK);
    assert_int_equal(hkf_init(&first, &hkf_default_settings), HKF_OK);
    for (i = 0; i < FRAMES; ++i) {
        hkf_filter_t *chunked = i < FRAMES / 2 ? &first : &second;
        const hkf_real_t dt = R(frames[i].time - previous);
        hkf_real_t z[3];
        int ra, rb;
        if (i == FRAMES / 2) {
            memcpy(&second, &first, sizeof second);
            memset(&first, 0xA5, sizeof first);
        }
        set3(z, frames[i].measured[0], frames[i].measured[1], frames[i].measured[2]);
        ra = frames[i].valid ? hkf_update(&whole, z, dt, &a) : hkf_predict(&whole, dt, &a);
        rb = frames[i].valid ? hkf_update(chunked, z, dt, &b) : hkf_predict(chunked, dt, &b);
        assert_int_equal(ra, rb);
        if (ra == HKF_OK) {
            for (k = 0; k < 3; ++k) {
                assert_near(a.angle[k], D(b.angle[k]), 0);
                assert_near(a.variance[k], D(b.variance[k]), 0);
            }
        }
        previous = frames[i].time;
    }
}

/* Constant vs adaptive R on a head held at 60 deg yaw: Eq. 8 trusts the
 * estimator less there (R = 7.03 vs 3.53), so the adaptive filter holds a
 * steadier pose; near the centre both R are the same. */
static void test_constant_vs_adaptive_r(void **state)
{
    hkf_settings_t constant = hkf_default_settings, adaptive = hkf_default_settings;
    hkf_filter_t fc, fa;
    hkf_output_t oc, oa;
    sim_rng_t rng;
    double step_c = 0.0, step_a = 0.0, prev_c = 0.0, prev_a = 0.0;
    int i;
    (void)state;
    constant.noise_mode = HKF_NOISE_CONSTANT;
    constant.loop_closure = HKF_LOOP_CLOSURE_OFF;
    adaptive.loop_closure = HKF_LOOP_CLOSURE_OFF;
    assert_int_equal(hkf_init(&fc, &constant), HKF_OK);
    assert_int_equal(hkf_init(&fa, &adaptive), HKF_OK);
    sim_rng_seed(&rng, 3u);
    for (i = 0; i < 600; ++i) {
        hkf_real_t z[3];
        set3(z, 0, 60.0 + 2.6 * sim_rng_gaussian(&rng), 0);
        assert_int_equal(hkf_update(&fc, z, frame_dt, &oc), HKF_OK);
        assert_int_equal(hkf_update(&fa, z, frame_dt, &oa), HKF_OK);
        if (i > 30) {
            step_c += (D(oc.angle[1]) - prev_c) * (D(oc.angle[1]) - prev_c);
            step_a += (D(oa.angle[1]) - prev_a) * (D(oa.angle[1]) - prev_a);
        }
        prev_c = D(oc.angle[1]);
        prev_a = D(oa.angle[1]);
    }
    assert_near(oc.r[1], 3.53, 1e-4);
    assert_near(oa.r[1], 7.03197, 0.05); /* Eq. 8 at the noisy measured yaw */
    assert_true(oa.r[1] > 6.5);
    assert_true(step_a < 0.85 * step_c);
    /* at the centre the curve gives the constant's value */
    assert_near(hkf_observation_noise(&fa, HKF_AXIS_YAW, R(-0.35)),
                D(hkf_observation_noise(&fc, HKF_AXIS_YAW, R(-0.35))), 1e-4);
}

/* The motion adaptation (hkf_two_models.h): on a still, noisy head the
 * output is far stiller than the paper's filter with the same (moving) q, and
 * when the head turns at 90 deg/s it follows far closer than a filter whose q
 * is small enough to be as still. */
static void test_two_models_still_and_moving(void **state)
{
    hkf_settings_t moving = hkf_default_settings, still, adaptive;
    hkf_filter_t fm, fs, fa;
    hkf_output_t om, os, oa;
    sim_rng_t rng;
    double jitter[3] = {0, 0, 0}, prev[3] = {0, 0, 0}, lag[3] = {0, 0, 0};
    int i, k;
    (void)state;
    moving.noise_mode = HKF_NOISE_CONSTANT;
    moving.r_const[0] = moving.r_const[1] = moving.r_const[2] = R(0.25);
    moving.start_rate = 0;
    still = moving;
    still.process_noise[1] = R(10);
    adaptive = moving;
    adaptive.start_rate = hkf_default_settings.start_rate;
    assert_int_equal(hkf_init(&fm, &moving), HKF_OK);
    assert_int_equal(hkf_init(&fs, &still), HKF_OK);
    assert_int_equal(hkf_init(&fa, &adaptive), HKF_OK);
    sim_rng_seed(&rng, 5u);
    for (i = 0; i < 450; ++i) {
        /* still for 10 s, then a turn at 90 deg/s for 0.5 s, then still */
        const double t = i / 30.0;
        const double truth = t < 10.0 ? 0.0 : t < 10.5 ? 90.0 * (t - 10.0) : 45.0;
        hkf_real_t z[3];
        double yaw[3];
        set3(z, 0, truth + 0.5 * sim_rng_gaussian(&rng), 0); /* frame noise well inside R, as on the real clips */
        assert_int_equal(hkf_update(&fm, z, frame_dt, &om), HKF_OK);
        assert_int_equal(hkf_update(&fs, z, frame_dt, &os), HKF_OK);
        assert_int_equal(hkf_update(&fa, z, frame_dt, &oa), HKF_OK);
        yaw[0] = D(om.angle[1]);
        yaw[1] = D(os.angle[1]);
        yaw[2] = D(oa.angle[1]);
        for (k = 0; k < 3; ++k) {
            if (i > 60 && t < 10.0) {
                jitter[k] += (yaw[k] - prev[k]) * (yaw[k] - prev[k]);
            }
            if (t >= 10.0 && t < 11.0) {
                lag[k] += fabs(truth - yaw[k]);
            }
            prev[k] = yaw[k];
        }
    }
    print_message("two models: still jitter %.4f (moving q %.4f, small q %.4f) deg^2 summed, turn error %.1f (%.1f, "
                  "%.1f) deg summed\n", jitter[2], jitter[0], jitter[1], lag[2], lag[0], lag[1]);
    assert_true(jitter[2] < 0.1 * jitter[0]); /* far stiller than the moving q alone */
    assert_true(jitter[2] < jitter[1]);       /* stiller than the small q */
    assert_true(lag[2] < 0.5 * lag[1]);       /* and far closer during the turn than the small q */
    assert_true(lag[2] < 2.0 * lag[0]);       /* about as close as the moving q */
}

/* The two models' step, by hand (hkf_two_models.h), from a still track: the
 * posterior of MOVE from the Markov prior and the two likelihoods (HOLD's with
 * R + still_wander), then the merged angle, rate and variance, and the merged
 * rate variance (HOLD's being p0_rate) through the next prediction - each
 * against the formula in double. */
static void test_two_models_by_hand(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3];
    const double dt = 0.125, q = 12.0, w = 0.5, start = 0.4, stop = 2.0, r = 2.0, p0 = 4.0, v0 = 8.0, y = 3.0;
    double pi, m00, m01, m11, h00, s_m, s_h, lm, lh, mu, xm, vm, pm00, pm01, pm11, xh, ph00, x, v, p00, p01, p11, dx;
    (void)state;
    s.process_noise[0] = s.process_noise[1] = s.process_noise[2] = R(q);
    s.still_wander = R(w);
    s.start_rate = R(start);
    s.stop_rate = R(stop);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 0, 0, 0);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK); /* angle 0, rate 0, P = diag(4, 8), mu 0 */
    set3(z, 0, y, 0);
    assert_int_equal(hkf_update(&f, z, R(dt), &out), HKF_OK);
    pi = start / (start + stop) * (1 - exp(-(start + stop) * dt)); /* the chain from mu = 0 */
    m00 = p0 + dt * dt * v0 + q * dt * dt * dt / 3;           /* MOVE: Eq. 1-3 */
    m01 = dt * v0 + q * dt * dt / 2;
    m11 = v0 + q * dt;
    h00 = p0;                                                 /* HOLD */
    s_m = m00 + r;
    s_h = h00 + r + w;
    lm = exp(-y * y / (2 * s_m)) / sqrt(s_m);
    lh = exp(-y * y / (2 * s_h)) / sqrt(s_h);
    mu = pi * lm / (pi * lm + (1 - pi) * lh);
    xm = m00 / s_m * y;
    vm = m01 / s_m * y;
    pm00 = m00 * r / s_m;
    pm01 = m01 * r / s_m;
    pm11 = m11 - m01 * m01 / s_m;
    xh = h00 / s_h * y;
    ph00 = h00 * (r + w) / s_h;
    x = mu * xm + (1 - mu) * xh;
    v = mu * vm;
    dx = xm - xh;
    p00 = mu * pm00 + (1 - mu) * ph00 + mu * (1 - mu) * dx * dx;
    p01 = mu * pm01 + mu * (1 - mu) * dx * vm;
    p11 = mu * pm11 + (1 - mu) * v0 + mu * (1 - mu) * vm * vm; /* HOLD's rate variance: p0_rate */
    assert_near(out.angle[1], x, 4 * TEST_TOL);
    assert_near(out.rate[1], v, 8 * TEST_TOL);
    assert_near(out.variance[1], p00, 4 * TEST_TOL);
    assert_near(out.angle[0], 0.0, TEST_TOL); /* no innovation: HOLD's angle, no rate */
    assert_near(out.rate[0], 0.0, TEST_TOL);
    assert_true(mu > 0.01 && mu < 0.99); /* a real mixture, not one model */
    assert_int_equal(hkf_predict(&f, R(dt), &out), HKF_OK); /* Eq. 3 from the merged covariance */
    assert_near(out.variance[1], p00 + 2 * dt * p01 + dt * dt * p11 + q * dt * dt * dt / 3, 8 * TEST_TOL);
}

/* Two estimators in one step (hkf_update_pair): the track starts from the first
 * measurement (P = p0), then the second updates it with its own R, by hand:
 * angle = z1 + p0 / (p0 + R2) (z2 - z1), variance p0 R2 / (p0 + R2), and the
 * reported R is that of both, R1 R2 / (R1 + R2). */
static void test_pair_start_weighs_by_each_r(void **state)
{
    hkf_settings_t first = plain_settings(), second = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z1[3], z2[3];
    const double p0 = 4, r1 = 2, r2 = 12, z2v[3] = {10, 20, -10};
    int a;
    (void)state;
    for (a = 0; a < HKF_AXES; ++a) {
        second.r_const[a] = R(r2);
    }
    assert_int_equal(hkf_init(&f, &first), HKF_OK);
    set3(z1, 0, 0, 0);
    set3(z2, z2v[0], z2v[1], z2v[2]);
    assert_int_equal(update_pair(&f, z1, z2, &second, R(0.033), &out), HKF_OK);
    assert_int_equal(out.status, HKF_STATUS_TRACKING);
    assert_true(out.flags & HKF_FLAG_REACQUIRED);
    for (a = 0; a < HKF_AXES; ++a) {
        assert_near(out.angle[a], p0 / (p0 + r2) * z2v[a], TEST_TOL);
        assert_near(out.variance[a], p0 * r2 / (p0 + r2), TEST_TOL);
        assert_near(out.r[a], r1 * r2 / (r1 + r2), TEST_TOL);
    }
}

/* Two measurements of the same value, each with R, are one measurement with
 * R / 2 (independent noise): a pair filter and a single filter with half the R
 * agree over a moving sequence, frame after frame. */
static void test_pair_of_equals_is_half_r(void **state)
{
    hkf_settings_t s = plain_settings(), half = plain_settings();
    hkf_filter_t fp, fh;
    hkf_output_t op, oh;
    int i, a;
    (void)state;
    for (a = 0; a < HKF_AXES; ++a) {
        half.r_const[a] = R(D(s.r_const[a]) / 2);
    }
    assert_int_equal(hkf_init(&fp, &s), HKF_OK);
    assert_int_equal(hkf_init(&fh, &half), HKF_OK);
    for (i = 0; i < 60; ++i) {
        hkf_real_t z[3];
        set3(z, 10.0 * sin(0.1 * i), 3.0 * i - 90.0, (i % 7) - 3.0);
        if (i == 0) { /* both tracks start at z with P = p0 (a pair would then update it with z again) */
            assert_int_equal(hkf_update(&fh, z, R(0.033), &oh), HKF_OK);
            assert_int_equal(hkf_update(&fp, z, R(0.033), &op), HKF_OK);
            continue;
        }
        assert_int_equal(hkf_update(&fh, z, R(0.033), &oh), HKF_OK);
        assert_int_equal(update_pair(&fp, z, z, &s, R(0.033), &op), HKF_OK);
        for (a = 0; a < HKF_AXES; ++a) {
            assert_near(op.angle[a], D(oh.angle[a]), TEST_TOL);
            assert_near(op.rate[a], D(oh.rate[a]), 10 * TEST_TOL);
            assert_near(op.r[a], D(oh.r[a]), TEST_TOL);
        }
    }
}

/* The second model's R is clamped to its own [r_min, r_max]: with both at 1000 its R is 1000 whatever its
 * curves, so the pair is (nearly) the first measurement alone, and the R of both R1 1000 / (R1 + 1000). */
static void test_pair_second_clamp_is_its_own(void **state)
{
    hkf_settings_t s = plain_settings(), second = plain_settings();
    hkf_filter_t fp, fu;
    hkf_output_t op, ou;
    int i, a;
    (void)state;
    second.r_min = R(1000);
    second.r_max = R(1000);
    assert_int_equal(hkf_init(&fp, &s), HKF_OK);
    assert_int_equal(hkf_init(&fu, &s), HKF_OK);
    for (i = 0; i < 30; ++i) {
        hkf_real_t z[3], z2[3];
        set3(z, 2.0 * sin(0.2 * i), 0.5 * i, -1.0);
        set3(z2, 2.0 * sin(0.2 * i) + 5.0, 0.5 * i - 5.0, 4.0); /* 5 deg off: it would pull a pair of equals far */
        assert_int_equal(update_pair(&fp, z, z2, &second, R(0.033), &op), HKF_OK);
        assert_int_equal(hkf_update(&fu, z, R(0.033), &ou), HKF_OK);
        if (i == 0) {
            continue; /* the track's start: then the second updates it */
        }
        for (a = 0; a < HKF_AXES; ++a) {
            assert_near(op.angle[a], D(ou.angle[a]), 0.05);
            assert_near(op.r[a], D(ou.r[a]) * 1000.0 / (D(ou.r[a]) + 1000.0), 1e-2);
        }
    }
}

/* A second model prepared once (hkf_model_noise_init) steps the filter as hkf_update_pair does, bit for
 * bit: the defaults (the adaptation on) with the gate on and WHENet's curves as the second model, over
 * turns with frames where either model is missing and a second measurement the gate refuses; the filters and outputs compared
 * whole after every frame. */
static void test_pair_prepared_is_pair(void **state)
{
    hkf_settings_t s = hkf_default_settings, second = hkf_default_settings;
    hkf_model_noise_t noise;
    hkf_model_prepared_t prepared;
    hkf_filter_t each, once;
    hkf_output_t oe, oo;
    int i, a, gated = 0;
    (void)state;
    for (a = 0; a < HKF_AXES; ++a) {
        second.noise[a] = hkf_noise_whenet[a];
    }
    noise = hkf_model_noise_of(&second);
    assert_int_equal(hkf_model_noise_init(&prepared, &noise), HKF_OK);
    s.gate_sigma = R(5); /* the defaults' gate is off */
    memset(&each, 0, sizeof each); /* the padding alike, so that the filters compare whole */
    memset(&once, 0, sizeof once);
    assert_int_equal(hkf_init(&each, &s), HKF_OK);
    assert_int_equal(hkf_init(&once, &s), HKF_OK);
    for (i = 0; i < 240; ++i) {
        hkf_real_t z[3], z2[3];
        const int first_missing = i % 11 == 5, second_missing = i % 3 != 0 && !first_missing;
        set3(z, 8.0 * sin(0.05 * i), 70.0 * sin(0.03 * i), 2.0 * cos(0.07 * i));
        set3(z2, D(z[0]) + 1.5, D(z[1]) - 2.0 + (i == 120 ? 40.0 : 0.0), D(z[2]) + 0.5);
        memset(&oe, 0, sizeof oe);
        memset(&oo, 0, sizeof oo);
        assert_int_equal(hkf_update_pair(&each, first_missing ? NULL : z, second_missing ? NULL : z2, &noise, R(0.033), &oe),
                         HKF_OK);
        assert_int_equal(hkf_update_pair_prepared(&once, first_missing ? NULL : z, second_missing ? NULL : z2, &prepared,
                                                  R(0.033), &oo),
                         HKF_OK);
        assert_memory_equal(&oe, &oo, sizeof oe);
        assert_memory_equal(&each, &once, sizeof each);
        gated += (oo.flags & HKF_FLAG_GATED) != 0;
    }
    assert_true(gated > 0); /* the jump at frame 120 was refused: the gate's path was compared too */
}

/* hkf_model_noise_init checks the model as hkf_update_pair does, and a bad one prepares nothing usable. */
static void test_model_noise_init_checks(void **state)
{
    hkf_settings_t bad = plain_settings();
    hkf_model_noise_t noise;
    hkf_model_prepared_t prepared;
    hkf_filter_t f, before;
    hkf_real_t z[3];
    (void)state;
    noise = hkf_model_noise_of(&bad);
    assert_int_equal(hkf_model_noise_init(NULL, &noise), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_model_noise_init(&prepared, NULL), HKF_ERROR_NULL_ARGUMENT);
    bad.noise[2].sigma = 0;
    noise = hkf_model_noise_of(&bad);
    assert_int_equal(hkf_model_noise_init(&prepared, &noise), HKF_ERROR_SETTING_SIGMA);
    bad = plain_settings();
    bad.r_min = R(5);
    bad.r_max = R(1);
    noise = hkf_model_noise_of(&bad);
    assert_int_equal(hkf_model_noise_init(&prepared, &noise), HKF_ERROR_SETTING_R_RANGE);
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    set3(z, 1, 2, 3);
    memcpy(&before, &f, sizeof f);
    assert_int_equal(hkf_update_pair(&f, z, z, &noise, R(0.033), NULL), HKF_ERROR_SETTING_R_RANGE);
    assert_int_equal(hkf_update_pair_prepared(&f, z, z, NULL, R(0.033), NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_memory_equal(&before, &f, sizeof f);
}

/* Yaw in [-180, 180): d + 180 wrapped into it. */
static double behind(double yaw)
{
    const double y = yaw + 180.0;
    return y >= 180.0 ? y - 360.0 : y;
}

/* The seam in both models: the same head, once facing the camera (yaw near 0) and once facing away
 * (yaw near +-180, its readings on both sides of the seam), with the defaults (HOLD and MOVE; R constant,
 * as Eq. 8's would differ between the two poses): a rest
 * with noise, a turn across, a rest again. HOLD's innovation and MOVE's are taken the short way round,
 * so the two filters agree frame by frame: pitch, roll, rates and MOVE's probability equal, yaw 180 deg
 * apart. (Unwrapped, HOLD would see a 360 deg jump at every crossing and lose the rest to MOVE.) */
static void test_yaw_seam_in_both_models(void **state)
{
    hkf_settings_t s = hkf_default_settings;
    hkf_filter_t front, seam;
    hkf_output_t of, os;
    hkf_state_t sf, ss;
    int i, a;
    double worst = 0.0;
    (void)state;
    s.noise_mode = HKF_NOISE_CONSTANT; /* Eq. 8's R depends on the pose: facing away is worse measured */
    assert_int_equal(hkf_init(&front, &s), HKF_OK);
    assert_int_equal(hkf_init(&seam, &s), HKF_OK);
    for (i = 0; i < 200; ++i) {
        const double noise = (i % 2 ? 0.4 : -0.4) + 0.1 * sin(1.7 * i);
        const double yaw = (i < 80 ? 0.0 : i < 100 ? 1.5 * (i - 80) : 30.0) - 15.0 + noise; /* -15 .. 15 deg */
        hkf_real_t zf[3], zs[3];
        set3(zf, 2.0 + noise, yaw, -1.0 + noise);
        set3(zs, 2.0 + noise, behind(yaw), -1.0 + noise);
        assert_int_equal(hkf_update(&front, zf, R(0.033), &of), HKF_OK);
        assert_int_equal(hkf_update(&seam, zs, R(0.033), &os), HKF_OK);
        assert_int_equal(hkf_get_state(&front, &sf), HKF_OK);
        assert_int_equal(hkf_get_state(&seam, &ss), HKF_OK);
        for (a = 0; a < HKF_AXES; ++a) {
            const double gap = a == HKF_AXIS_YAW ? behind(D(os.angle[a]) - D(of.angle[a])) : D(os.angle[a]) - D(of.angle[a]);
            worst = fabs(gap) > worst ? fabs(gap) : worst;
            assert_near(gap, 0.0, 0.02);
            assert_near(os.rate[a], D(of.rate[a]), 0.5);
            assert_near(ss.moving[a], D(sf.moving[a]), 0.02);
        }
    }
    print_message("the yaw seam: the filters facing away and facing the camera at most %.4f deg apart\n", worst);
}

/* hkf_get_status follows the track: none, a measurement, a frame without one; and NULL has none. */
static void test_status_accessor(void **state)
{
    const hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_real_t z[3];
    (void)state;
    assert_int_equal(hkf_get_status(NULL), HKF_STATUS_UNINITIALIZED);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    assert_int_equal(hkf_get_status(&f), HKF_STATUS_UNINITIALIZED);
    set3(z, 1, 2, 3);
    assert_int_equal(hkf_update(&f, z, R(0.033), NULL), HKF_OK);
    assert_int_equal(hkf_get_status(&f), HKF_STATUS_TRACKING);
    assert_int_equal(hkf_predict(&f, R(0.033), NULL), HKF_OK);
    assert_int_equal(hkf_get_status(&f), HKF_STATUS_COASTING);
    hkf_reset(&f);
    assert_int_equal(hkf_get_status(&f), HKF_STATUS_UNINITIALIZED);
}

/* A bad second model or measurement is an error that leaves the filter as it was. */
static void test_pair_bad_input_changes_nothing(void **state)
{
    hkf_settings_t s = plain_settings(), bad = plain_settings();
    hkf_filter_t f, before;
    hkf_output_t out;
    hkf_real_t z[3], far[3];
    (void)state;
    bad.noise[1].sigma = 0;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 1, 2, 3);
    assert_int_equal(hkf_update(&f, z, R(0.033), &out), HKF_OK);
    memcpy(&before, &f, sizeof f);
    set3(far, 0, 4000, 0);
    assert_int_equal(update_pair(&f, z, z, &bad, R(0.033), &out), HKF_ERROR_SETTING_SIGMA);
    assert_int_equal(update_pair(&f, z, far, &s, R(0.033), &out), HKF_ERROR_ANGLE_RANGE);
    assert_int_equal(update_pair(&f, far, z, &s, R(0.033), &out), HKF_ERROR_ANGLE_RANGE);
    assert_int_equal(update_pair(&f, z, z, &s, R(-1), &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(update_pair(&f, z, z, NULL, R(0.033), &out), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(update_pair(&f, NULL, NULL, &s, R(0.033), &out), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(update_pair(&f, z, NULL, &bad, R(0.033), &out), HKF_ERROR_SETTING_SIGMA);
    assert_int_equal(update_pair(&f, NULL, far, &s, R(0.033), &out), HKF_ERROR_ANGLE_RANGE);
    assert_memory_equal(&before, &f, sizeof f);
}

/* One model of the pair missing this frame: with z2 NULL the pair is exactly
 * hkf_update; with z NULL it is hkf_update with the second model's R - a
 * filter set up with the second's settings follows the same track, frame by
 * frame, start included, while the first's R would give another. */
static void test_pair_with_one_model_missing(void **state)
{
    hkf_settings_t first = plain_settings(), second = plain_settings();
    hkf_filter_t fp, fu, fs;
    hkf_output_t op, ou, os;
    int i, a;
    (void)state;
    for (a = 0; a < HKF_AXES; ++a) {
        second.r_const[a] = R(6 * D(first.r_const[a]));
    }
    assert_int_equal(hkf_init(&fp, &first), HKF_OK);
    assert_int_equal(hkf_init(&fu, &first), HKF_OK);
    assert_int_equal(hkf_init(&fs, &second), HKF_OK);
    for (i = 0; i < 40; ++i) {
        hkf_real_t z[3];
        set3(z, 8.0 * sin(0.2 * i), 2.0 * i - 40.0, (i % 5) - 2.0);
        assert_int_equal(update_pair(&fp, NULL, z, &second, R(0.033), &op), HKF_OK);
        assert_int_equal(hkf_update(&fs, z, R(0.033), &os), HKF_OK);
        assert_int_equal(hkf_update(&fu, z, R(0.033), &ou), HKF_OK);
        for (a = 0; a < HKF_AXES; ++a) {
            assert_near(op.angle[a], D(os.angle[a]), TEST_TOL);
            assert_near(op.variance[a], D(os.variance[a]), TEST_TOL);
            assert_near(op.r[a], D(second.r_const[a]), TEST_TOL);
        }
        assert_int_equal(op.flags, os.flags);
    }
    assert_true(fabs(D(op.angle[1]) - D(ou.angle[1])) > 0.1); /* the first's R would lag less */
    /* and with only the first, the pair is hkf_update, bit for bit */
    memcpy(&fs, &fu, sizeof fu);
    for (i = 0; i < 10; ++i) {
        hkf_real_t z[3];
        set3(z, 1.0, 40.0 + i, -2.0);
        assert_int_equal(update_pair(&fu, z, NULL, &second, R(0.033), &ou), HKF_OK);
        assert_int_equal(hkf_update(&fs, z, R(0.033), &os), HKF_OK);
        assert_memory_equal(&fu, &fs, sizeof fu);
        assert_memory_equal(&ou, &os, sizeof ou);
    }
}

/* The pair with the gate on: when the first measurement is gated (an
 * outlier) and the second accepted, the output's R is the second's alone -
 * only accepted measurements are combined into 1 / (1/R1 + 1/R2); when the
 * second is gated, the first's outcome stands with the first's R. */
static void test_pair_with_the_gate(void **state)
{
    hkf_settings_t first = plain_settings(), second = plain_settings();
    hkf_filter_t f, only_second, only_first;
    hkf_output_t out, ref;
    hkf_real_t good[3], outlier[3];
    int a;
    (void)state;
    first.gate_sigma = R(4);
    first.max_gate_rejections = 5u;
    for (a = 0; a < HKF_AXES; ++a) {
        second.r_const[a] = R(6);
    }
    track_turning_head(&f, &first, 0.0, 30);
    only_second = f;
    only_first = f;
    set3(good, 0, 0.5, 0);
    set3(outlier, 0, 60, 0);
    assert_int_equal(update_pair(&f, outlier, good, &second, frame_dt, &out), HKF_OK);
    assert_true(out.flags & HKF_FLAG_GATED);
    assert_int_equal(update_pair(&only_second, NULL, good, &second, frame_dt, &ref), HKF_OK);
    for (a = 0; a < HKF_AXES; ++a) {
        assert_near(out.r[a], 6, TEST_TOL);                   /* not 1 / (1/2 + 1/6) = 1.5 */
        assert_near(out.angle[a], D(ref.angle[a]), 10 * TEST_TOL); /* the second's update, after the prediction */
    }
    /* the second gated: the first's outcome, R included */
    f = only_first;
    assert_int_equal(update_pair(&f, good, outlier, &second, frame_dt, &out), HKF_OK);
    assert_true(out.flags & HKF_FLAG_GATED);
    assert_int_equal(hkf_update(&only_first, good, frame_dt, &ref), HKF_OK);
    for (a = 0; a < HKF_AXES; ++a) {
        assert_near(out.r[a], 2, TEST_TOL);
        assert_near(out.angle[a], D(ref.angle[a]), TEST_TOL);
    }
}

/* The coasting rule's boundary, with times exact in every build (0.25 =
 * 2 x 0.125): LOST exactly when the time without a measurement reaches
 * coast_time, COASTING just before. */
static void test_coast_boundary_exact(void **state)
{
    hkf_settings_t s = plain_settings();
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3];
    (void)state;
    s.coast_time = R(0.25);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(z, 1, 2, 3);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    assert_int_equal(hkf_predict(&f, R(0.125), &out), HKF_OK);
    assert_int_equal(out.status, HKF_STATUS_COASTING);
    assert_int_equal(hkf_predict(&f, R(0.125), &out), HKF_OK);
    assert_int_equal(out.status, HKF_STATUS_LOST);
    /* re-acquiring checks dt as any update does: a bad one is an error that changes nothing */
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_update(&f, z, R(D(s.max_dt) * 2), &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_get_output(&f, &out), HKF_OK);
    assert_int_equal(out.status, HKF_STATUS_LOST);
    assert_int_equal(hkf_update(&f, z, R(0.125), &out), HKF_OK);
    assert_true(out.flags & HKF_FLAG_REACQUIRED);
    /* max_dt itself is a valid step, a hair more is not */
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_OK);
    assert_int_equal(hkf_update(&f, z, s.max_dt, &out), HKF_OK);
    assert_int_equal(hkf_update(&f, z, R(D(s.max_dt) + 0.01), &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_update(&f, z, R(0), &out), HKF_ERROR_DT_RANGE);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coast_then_lost),
        cmocka_unit_test(test_reacquire_after_lost),
        cmocka_unit_test(test_gate_rejects_outlier_then_reacquires),
        cmocka_unit_test(test_extrapolate_is_pure),
        cmocka_unit_test(test_recenter_and_reset),
        cmocka_unit_test(test_state_carried_across_chunks),
        cmocka_unit_test(test_constant_vs_adaptive_r),
        cmocka_unit_test(test_two_models_still_and_moving),
        cmocka_unit_test(test_pair_start_weighs_by_each_r),
        cmocka_unit_test(test_pair_of_equals_is_half_r),
        cmocka_unit_test(test_pair_second_clamp_is_its_own),
        cmocka_unit_test(test_status_accessor),
        cmocka_unit_test(test_pair_bad_input_changes_nothing),
        cmocka_unit_test(test_pair_with_one_model_missing),
        cmocka_unit_test(test_pair_prepared_is_pair),
        cmocka_unit_test(test_yaw_seam_in_both_models),
        cmocka_unit_test(test_model_noise_init_checks),
        cmocka_unit_test(test_pair_with_the_gate),
        cmocka_unit_test(test_coast_boundary_exact),
        cmocka_unit_test(test_two_models_by_hand),
        cmocka_unit_test(test_settings_copied),
#if defined(HKF_REAL_FIXED)
        cmocka_unit_test(test_state_within_the_m0_budget),
#endif
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

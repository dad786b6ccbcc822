/*
 * test_position.c - libhkf's position filter (hkf/hkf_position.h), the angles'
 * twin: the closed-form step against the Kalman equations worked in double
 * here, a lean followed without bias, noise smoothed, the noise measured by
 * the calibration beside it (hkf/hkf_calibration.h), the motion adaptation's
 * stiller rest, sooner arrival and settled rate, coarse measurements trusted
 * less, the lifecycle (reset, restart, status, the centre's rules), the gate,
 * and every error path leaving the filter as it was. Built for float, double
 * and Q16.16.
 */
#include "test_support.h"

#include "hkf/hkf_calibration.h"
#include "hkf/hkf_position.h"

static const double frame_s = 1.0 / 60.0;

static hkf_position_filter_t started_filter_with(const hkf_position_settings_t *s, double x, double y, double z)
{
    hkf_position_filter_t f;
    const hkf_real_t at[3] = {R(x), R(y), R(z)};
    assert_int_equal(hkf_position_init(&f, s), HKF_OK);
    assert_int_equal(hkf_position_update(&f, at, R(1.0), R(frame_s), NULL), HKF_OK);
    return f;
}

static hkf_position_filter_t started_filter(double x, double y, double z)
{
    hkf_position_settings_t s;
    s = hkf_position_default_settings;
    return started_filter_with(&s, x, y, z);
}

/* The default filter after a still head at (0, 0, 60) cm for 60 frames. */
static hkf_position_filter_t still_filter(void)
{
    hkf_position_filter_t f = started_filter(0.0, 0.0, 60.0);
    const hkf_real_t still[3] = {R(0.0), R(0.0), R(60.0)};
    int i;
    for (i = 0; i < 60; ++i) {
        assert_int_equal(hkf_position_update(&f, still, R(1.0), R(frame_s), NULL), HKF_OK);
    }
    return f;
}

/* The paper's step alone: MOVE without the adaptation, q 10 cm^2/s^3, R = r_const. */
static hkf_position_settings_t constant_settings(void)
{
    hkf_position_settings_t s;
    int a;
    s = hkf_position_default_settings;
    s.start_rate = 0;
    for (a = 0; a < 3; ++a) {
        s.process_noise[a] = R(10.0);
    }
    return s;
}

static hkf_position_filter_t started_constant_filter(double x, double y, double z)
{
    const hkf_position_settings_t s = constant_settings();
    return started_filter_with(&s, x, y, z);
}

/* Pseudo-random noise, uniform, of standard deviation sd (a fixed sequence per seed). */
static double uniform_noise(unsigned *seed, double sd)
{
    *seed = *seed * 1103515245u + 12345u;
    return ((double)((*seed >> 8) & 0xffff) / 65536.0 - 0.5) * sd * sqrt(12.0);
}

/* A position filter with the noise calibration beside it, as hkf-filter runs it. */
typedef struct {
    hkf_position_filter_t f;
    hkf_calibration_t c;
} calibrated_t;

static calibrated_t calibrated_with(const hkf_position_settings_t *s)
{
    calibrated_t k;
    assert_int_equal(hkf_position_init(&k.f, s), HKF_OK);
    assert_int_equal(hkf_calibration_init_position(&k.c, &hkf_default_calibration_settings, &k.f), HKF_OK);
    return k;
}

static void calibrated_step(calibrated_t *k, const hkf_real_t *z, double r_scale, double dt, hkf_position_output_t *out);

/* 10 s of a still head at (0, 0, z) with noise of standard deviation sd in z: the calibration's n
 * settles on it (it rises by at most noise_rise a second). */
static void settle(calibrated_t *k, double z, double sd, unsigned *seed)
{
    int i;
    for (i = 0; i < 600; ++i) {
        const hkf_real_t at[3] = {R(0.0), R(0.0), R(z + uniform_noise(seed, sd))};
        calibrated_step(k, at, 1.0, frame_s, NULL);
    }
}

/* One measurement (NULL: a frame without one, predicted) into both. */
static void calibrated_step(calibrated_t *k, const hkf_real_t *z, double r_scale, double dt, hkf_position_output_t *out)
{
    if (z != NULL) {
        assert_int_equal(hkf_position_update(&k->f, z, R(r_scale), R(dt), out), HKF_OK);
    } else {
        assert_int_equal(hkf_position_predict(&k->f, R(dt), out), HKF_OK);
    }
    assert_int_equal(hkf_calibration_update_position(&k->c, &k->f, z, R(dt)), HKF_OK);
}

/* The filter's state, as its public accessor gives it. */
static hkf_position_state_t state_of(const hkf_position_filter_t *f)
{
    hkf_position_state_t st;
    assert_int_equal(hkf_position_get_state(f, &st), HKF_OK);
    return st;
}


/* One predict + update against the equations in double: F = [[1, dt], [0, 1]],
 * Q = q [[dt^3/3, dt^2/2], [dt^2/2, dt]], H = [1, 0] (the constant filter). */
static void test_step_matches_equations(void **state)
{
    (void)state;
    hkf_position_filter_t f = started_constant_filter(1.0, -2.0, 60.0);
    const double z[3] = {1.5, -2.2, 61.0};
    const hkf_real_t zr[3] = {R(z[0]), R(z[1]), R(z[2])};
    double x[3], v[3], p00[3], p01[3], p11[3];
    hkf_position_output_t out;
    int a, k;
    for (k = 0; k < 3; ++k) { /* a few steps so the covariance is not the start's */
        const hkf_real_t same[3] = {R(1.0), R(-2.0), R(60.0)};
        assert_int_equal(hkf_position_update(&f, same, R(1.0), R(frame_s), NULL), HKF_OK);
    }
    for (a = 0; a < 3; ++a) {
        const hkf_position_state_t st = state_of(&f);
        x[a] = D(st.position[a]), v[a] = D(st.rate[a]), p00[a] = D(st.p00[a]), p01[a] = D(st.p01[a]), p11[a] = D(st.p11[a]);
    }
    assert_int_equal(hkf_position_update(&f, zr, R(4.0), R(frame_s), &out), HKF_OK);
    for (a = 0; a < 3; ++a) {
        const hkf_position_settings_t set = constant_settings();
        const double q = D(set.process_noise[a]), r = 4.0 * D(set.r_const[a]), dt = frame_s;
        const double xp = x[a] + v[a] * dt;
        const double a00 = p00[a] + 2 * dt * p01[a] + dt * dt * p11[a] + q * dt * dt * dt / 3;
        const double a01 = p01[a] + dt * p11[a] + q * dt * dt / 2, a11 = p11[a] + q * dt;
        const double s = a00 + r, k0 = a00 / s, k1 = a01 / s, y = z[a] - xp;
        assert_true(fabs(D(out.position[a]) - (xp + k0 * y)) < 2 * TEST_TOL);
        assert_true(fabs(D(out.rate[a]) - (v[a] + k1 * y)) < 50 * TEST_TOL);
        assert_true(fabs(D(out.variance[a]) - a00 * r / s) < 2 * TEST_TOL + 1e-3 * a00);
        assert_true(fabs(D(state_of(&f).p11[a]) - (a11 - k1 * a01)) < 50 * TEST_TOL + 1e-3 * a11);
    }
}

/* A lean of 10 cm in z over 0.5 s, measured with 0.5 cm of noise at 60 Hz (10x the mesh's: the
 * calibration measures it, given 10 s at rest first): the output arrives within 1 cm of the end and is
 * far smoother than the input. */
static void test_lean_followed_noise_smoothed(void **state)
{
    (void)state;
    calibrated_t k = calibrated_with(&hkf_position_default_settings);
    hkf_position_output_t out;
    double raw_jitter = 0, out_jitter = 0, last_raw = 60, last_out = 60;
    int i;
    unsigned seed = 7;
    settle(&k, 60.0, 0.5, &seed);
    for (i = 1; i <= 120; ++i) {
        const double t = i * frame_s;
        const double truth = 60.0 - 10.0 * (t < 0.5 ? t / 0.5 : 1.0);
        double noise;
        hkf_real_t z[3];
        noise = uniform_noise(&seed, 0.5);
        z[0] = R(0.0), z[1] = R(0.0), z[2] = R(truth + noise);
        calibrated_step(&k, z, 1.0, frame_s, &out);
        if (i > 90 && i <= 120) { /* still at 50 cm after the lean */
            raw_jitter += (truth + noise - last_raw) * (truth + noise - last_raw);
            out_jitter += (D(out.position[2]) - last_out) * (D(out.position[2]) - last_out);
        }
        last_raw = truth + noise;
        last_out = D(out.position[2]);
        if (i == 90) {
            assert_true(fabs(D(out.position[2]) - 50.0) < 1.0);
        }
    }
    print_message("position: frame-to-frame RMS raw %.3f cm, filtered %.3f cm\n", sqrt(raw_jitter / 30), sqrt(out_jitter / 30));
    assert_true(out_jitter < 0.25 * raw_jitter);
}

/* Calibrated: the measured noise n comes to the measurements' own variance on a still head and on a
 * steady move alike (the second difference cancels a constant velocity) - a little below it on
 * average, as n follows the low-passed power down at once and up slowly - and frames missed in a move
 * (predicted, the calibration told so) do not pass for noise. n reaches the filter: its R. */
static void test_noise_measured(void **state)
{
    const double sd[3] = {0.05, 0.05, 0.3}; /* cm: the mesh's x, y and z noise at ~60 cm */
    const double speed[3] = {4.0, 0.0, -8.0}; /* cm/s */
    calibrated_t k = calibrated_with(&hkf_position_default_settings);
    unsigned seed = 11;
    double t = 0, mean[3] = {0, 0, 0};
    hkf_real_t n[3];
    int i, a;
    (void)state;
    for (i = 1; i <= 600; ++i) {
        hkf_real_t z[3];
        t += frame_s;
        for (a = 0; a < 3; ++a) {
            z[a] = R((a == 2 ? 60.0 : 0.0) + speed[a] * t + uniform_noise(&seed, sd[a]));
        }
        calibrated_step(&k, z, 1.0, frame_s, NULL);
        for (a = 0; a < 3 && i > 300; ++a) {
            mean[a] += D(state_of(&k.f).noise[a]) / 300.0;
        }
    }
    assert_int_equal(hkf_calibration_get_noise(&k.c, n), HKF_OK);
    for (a = 0; a < 3; ++a) {
        const double ratio = mean[a] / (sd[a] * sd[a]);
        print_message("axis %d: measured noise %.5f cm^2 (mean of 5 s), true %.5f (ratio %.2f)\n", a, mean[a],
                      sd[a] * sd[a], ratio);
        assert_true(ratio > 0.4 && ratio < 1.2);
        assert_true(D(n[a]) == D(state_of(&k.f).noise[a])); /* handed to the filter */
    }
    assert_true(mean[2] / mean[0] > 0.5 * 36.0 && mean[2] / mean[0] < 2.0 * 36.0); /* 6x the noise: 36x n */
    { /* a move without noise, every fourth frame missed and predicted: n goes to nothing */
        calibrated_t g = calibrated_with(&hkf_position_default_settings);
        const double start = D(hkf_position_default_settings.r_const[2]);
        t = 0;
        for (i = 1; i <= 300; ++i) {
            const hkf_real_t z[3] = {R(0.0), R(0.0), R(60.0 - 20.0 * t)};
            t += frame_s;
            calibrated_step(&g, i % 4 == 0 ? NULL : z, 1.0, frame_s, NULL);
        }
        print_message("a move with missed frames: measured z noise %.6f cm^2 (started at %.3f)\n",
                      D(state_of(&g.f).noise[2]), start);
        assert_true(D(state_of(&g.f).noise[2]) < 0.05 * start);
    }
}

/* Calibrated, one step of a still head against the equations in double, MOVE alone (start_rate 0):
 * R = the scale x n (the measured noise), q = process_noise in cm^2/s^3 whatever n is (one unit). */
static void test_calibrated_step_matches_equations(void **state)
{
    hkf_position_settings_t s = hkf_position_default_settings;
    calibrated_t k;
    hkf_position_output_t out;
    unsigned seed = 3;
    int i, a;
    (void)state;
    s.start_rate = 0;
    s.r_min = R(1e-4); /* below the defaults' floor (the mesh's x and y noise), so that n comes down */
    k = calibrated_with(&s);
    for (i = 1; i <= 120; ++i) { /* a camera 5x quieter than n's start: n comes down to it */
        const hkf_real_t z[3] = {R(uniform_noise(&seed, 0.02)), R(uniform_noise(&seed, 0.02)),
                                 R(60.0 + uniform_noise(&seed, 0.1))};
        calibrated_step(&k, z, 1.0, frame_s, NULL);
    }
    {
        const hkf_position_state_t st = state_of(&k.f);
        const hkf_real_t z[3] = {st.position[0], st.position[1], st.position[2]};
        double n[3], p00[3], p01[3], p11[3];
        for (a = 0; a < 3; ++a) {
            n[a] = D(st.noise[a]), p00[a] = D(st.p00[a]), p01[a] = D(st.p01[a]), p11[a] = D(st.p11[a]);
            assert_true(n[a] < 0.5 * D(hkf_position_default_settings.r_const[a])); /* measured, not the start */
        }
        assert_int_equal(hkf_position_update(&k.f, z, R(2.0), R(frame_s), &out), HKF_OK);
        for (a = 0; a < 3; ++a) {
            const double q = D(s.process_noise[a]), r = 2.0 * n[a], dt = frame_s;
            const double a00 = p00[a] + 2 * dt * p01[a] + dt * dt * p11[a] + q * dt * dt * dt / 3;
            const double sum = a00 + r;
            assert_true(fabs(D(out.variance[a]) - a00 * r / sum) < 4 * TEST_TOL + 1e-3 * a00);
        }
    }
}

/* The defaults (the motion adaptation) with the calibration (settled for 10 s) against the constant
 * filter (MOVE alone, q 10), a head still at 60 cm, then a fast 10 cm lean (minimum jerk, 0.4 s), still
 * again: the adapting filter is stiller at rest, arrives sooner, and stops without overshooting (the constant
 * one overshoots by 1.4 cm). */
static void test_still_stiller_lean_sooner(void **state)
{
    calibrated_t adapting = calibrated_with(&hkf_position_default_settings);
    hkf_position_filter_t constant = started_constant_filter(0.0, 0.0, 60.0);
    double jitter[2] = {0, 0}, last[2] = {60, 60}, overshoot[2] = {0, 0}, arrived[2] = {-1, -1};
    unsigned seed = 5;
    int i, k;
    (void)state;
    settle(&adapting, 60.0, 0.3, &seed);
    for (i = 1; i <= 240; ++i) {
        const double t = i * frame_s, u = t < 2.0 ? 0.0 : t > 2.4 ? 1.0 : (t - 2.0) / 0.4;
        const double truth = 60.0 - 10.0 * u * u * u * (10.0 - 15.0 * u + 6.0 * u * u);
        const hkf_real_t z[3] = {R(0.0), R(0.0), R(truth + uniform_noise(&seed, 0.3))};
        hkf_position_output_t out[2];
        calibrated_step(&adapting, z, 1.0, frame_s, &out[0]);
        assert_int_equal(hkf_position_update(&constant, z, R(1.0), R(frame_s), &out[1]), HKF_OK);
        for (k = 0; k < 2; ++k) {
            const double p = D(out[k].position[2]);
            if (t >= 1.0 && t < 2.0) {
                jitter[k] += (p - last[k]) * (p - last[k]);
            }
            if (t > 2.4 && 50.0 - p > overshoot[k]) {
                overshoot[k] = 50.0 - p;
            }
            if (arrived[k] < 0 && t >= 2.0 && p < 51.0) {
                arrived[k] = t - 2.0;
            }
            last[k] = p;
        }
    }
    for (k = 0; k < 2; ++k) {
        jitter[k] = sqrt(jitter[k] / 60.0);
        print_message("%s: still jitter %.4f cm/frame, within 1 cm of the lean's end after %.3f s, overshoot %.2f cm\n",
                      k == 0 ? "adapting" : "constant", jitter[k], arrived[k], overshoot[k]);
    }
    assert_true(jitter[0] < jitter[1]);
    assert_true(arrived[0] > 0 && arrived[0] <= arrived[1]);
    assert_true(overshoot[0] < 0.5);
}

/* The motion adaptation's probability of MOVE (hkf_position_get_state: moving), as the angles':
 * near 0 while the head rests; once a lean of 20 cm/s has moved 1.7 cm (5 frames), above 0.7 with the
 * output within 0.4 cm of the head for as long as it moves; back near 0 soon after it stops; a one-frame blip (4.5 cm in z against 0.1 cm of noise, inside the gate) is gone from the
 * output two frames later, while the same 4.5 cm held is followed within a few frames. */
static void test_hold_and_move(void **state)
{
    hkf_position_filter_t f = started_filter(0.0, 0.0, 60.0);
    hkf_position_filter_t blip = started_filter(0.0, 0.0, 60.0), held = started_filter(0.0, 0.0, 60.0);
    hkf_position_output_t ob, oh;
    double most_at_rest = 0, least_in_lean = 1, behind_in_lean = 0, moving_after = 1, blip_after = 0, held_after = 0;
    unsigned seed = 11;
    int i;
    (void)state;
    for (i = 1; i <= 180; ++i) { /* rest 1 s, a lean of 10 cm at 20 cm/s, rest 1.5 s */
        const double t = i * frame_s;
        const double truth = t < 1.0 ? 60.0 : t < 1.5 ? 60.0 - 20.0 * (t - 1.0) : 50.0;
        const hkf_real_t z[3] = {R(0.0), R(0.0), R(truth + uniform_noise(&seed, 0.1))};
        double moving;
        hkf_position_output_t out;
        assert_int_equal(hkf_position_update(&f, z, R(1.0), R(frame_s), &out), HKF_OK);
        moving = D(state_of(&f).moving[2]);
        most_at_rest = t > 0.25 && t < 1.0 ? fmax(most_at_rest, moving) : most_at_rest;
        if (i >= 65 && i <= 90) { /* from 5 frames into the lean to its end */
            least_in_lean = fmin(least_in_lean, moving);
            behind_in_lean = fmax(behind_in_lean, fabs(D(out.position[2]) - truth));
        }
        moving_after = i == 120 ? moving : moving_after; /* 0.5 s after the stop */
    }
    seed = 11;
    for (i = 1; i <= 90; ++i) {
        const double noise = uniform_noise(&seed, 0.1);
        const hkf_real_t zb[3] = {R(0.0), R(0.0), R(60.0 + noise + (i == 75 ? 4.5 : 0.0))};
        const hkf_real_t zh[3] = {R(0.0), R(0.0), R(60.0 + noise + (i >= 75 ? 4.5 : 0.0))};
        assert_int_equal(hkf_position_update(&blip, zb, R(1.0), R(frame_s), &ob), HKF_OK);
        assert_int_equal(hkf_position_update(&held, zh, R(1.0), R(frame_s), &oh), HKF_OK);
        blip_after = i >= 77 ? fmax(blip_after, fabs(D(ob.position[2]) - 60.0)) : blip_after;
        held_after = i == 79 ? D(oh.position[2]) - 60.0 : held_after;
    }
    print_message("position: MOVE's probability at rest at most %.3f, in a lean at least %.3f (output within %.2f cm), "
                  "0.5 s after it %.3f; a 4.5 cm blip %.2f cm two frames on; 4.5 cm held: %.2f cm after 4 frames\n",
                  most_at_rest, least_in_lean, behind_in_lean, moving_after, blip_after, held_after);
    assert_true(most_at_rest < 0.1);
    assert_true(least_in_lean > 0.7 && behind_in_lean < 0.4);
    assert_true(moving_after < 0.1);
    assert_true(blip_after < 0.5);
    assert_true(held_after > 4.0);
}

/* hkf_position_started and hkf_position_get_status: started after the first measurement, until a
 * reset or restart; TRACKING after a measurement taken, COASTING after a prediction or a refused one,
 * UNINITIALIZED before a track and for NULL. */
static void test_started_and_status(void **state)
{
    hkf_position_filter_t f;
    const hkf_real_t z[3] = {R(1.0), R(2.0), R(60.0)};
    const hkf_real_t forged[3] = {R(900.0), R(2.0), R(60.0)};
    (void)state;
    assert_int_equal(hkf_position_started(NULL), 0);
    assert_int_equal(hkf_position_get_status(NULL), HKF_STATUS_UNINITIALIZED);
    assert_int_equal(hkf_position_init(&f, &hkf_position_default_settings), HKF_OK);
    assert_int_equal(hkf_position_started(&f), 0);
    assert_int_equal(hkf_position_get_status(&f), HKF_STATUS_UNINITIALIZED);
    assert_int_equal(hkf_position_update(&f, z, R(1.0), R(frame_s), NULL), HKF_OK);
    assert_int_equal(hkf_position_started(&f), 1);
    assert_int_equal(hkf_position_get_status(&f), HKF_STATUS_TRACKING);
    assert_int_equal(hkf_position_predict(&f, R(frame_s), NULL), HKF_OK);
    assert_int_equal(hkf_position_get_status(&f), HKF_STATUS_COASTING);
    assert_int_equal(hkf_position_update(&f, z, R(1.0), R(frame_s), NULL), HKF_OK);
    assert_int_equal(hkf_position_get_status(&f), HKF_STATUS_TRACKING);
    assert_int_equal(hkf_position_update(&f, forged, R(1.0), R(frame_s), NULL), HKF_OK); /* the gate refuses it */
    assert_int_equal(hkf_position_get_status(&f), HKF_STATUS_COASTING);
    hkf_position_restart(&f);
    assert_int_equal(hkf_position_started(&f), 0);
    assert_int_equal(hkf_position_get_status(&f), HKF_STATUS_UNINITIALIZED);
    assert_int_equal(hkf_position_update(&f, z, R(1.0), R(frame_s), NULL), HKF_OK);
    hkf_position_reset(&f);
    assert_int_equal(hkf_position_started(&f), 0);
    assert_int_equal(hkf_position_get_status(&f), HKF_STATUS_UNINITIALIZED);
}

/* A measurement with a larger R scale moves the output less. */
static void test_coarse_measurement_trusted_less(void **state)
{
    (void)state;
    hkf_position_filter_t fine = started_filter(0.0, 0.0, 60.0), coarse = fine;
    const hkf_real_t z[3] = {R(2.0), R(0.0), R(60.0)};
    hkf_position_output_t a, b;
    assert_int_equal(hkf_position_update(&fine, z, R(1.0), R(frame_s), &a), HKF_OK);
    assert_int_equal(hkf_position_update(&coarse, z, R(25.0), R(frame_s), &b), HKF_OK);
    assert_true(D(a.position[0]) > D(b.position[0]) + 0.1);
    assert_true(D(b.position[0]) > 0.0);
}

/* The centre (hkf_reset's rule): the first measurement sets it, and a reset forgets that one (the
 * next track sets its own); a recentre sets it on the position, and a restart and a reset keep it. */
static void test_center_recenter_reset(void **state)
{
    (void)state;
    hkf_position_filter_t f = started_filter(3.0, 4.0, 55.0);
    const hkf_real_t moved[3] = {R(8.0), R(4.0), R(50.0)};
    const hkf_real_t other[3] = {R(-6.0), R(1.0), R(70.0)};
    hkf_real_t c[3];
    int i;
    assert_true(fabs(D(state_of(&f).center[0]) - 3.0) < TEST_TOL && fabs(D(state_of(&f).center[2]) - 55.0) < TEST_TOL);
    assert_int_equal(hkf_position_get_center(&f, c), HKF_OK);
    assert_true(fabs(D(c[0]) - 3.0) < TEST_TOL && fabs(D(c[2]) - 55.0) < TEST_TOL);
    hkf_position_reset(&f); /* the track's centre is forgotten with the track */
    assert_int_equal(hkf_position_get_center(&f, c), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_position_update(&f, other, R(1.0), R(frame_s), NULL), HKF_OK);
    assert_int_equal(hkf_position_get_center(&f, c), HKF_OK);
    assert_true(fabs(D(c[0]) + 6.0) < TEST_TOL && fabs(D(c[2]) - 70.0) < TEST_TOL); /* the new track's own */
    for (i = 0; i < 120; ++i) {
        assert_int_equal(hkf_position_update(&f, moved, R(1.0), R(frame_s), NULL), HKF_OK);
    }
    assert_int_equal(hkf_position_recenter(&f), HKF_OK);
    assert_true(fabs(D(state_of(&f).center[0]) - 8.0) < 0.05 && fabs(D(state_of(&f).center[2]) - 50.0) < 0.05);
    hkf_position_restart(&f); /* a new track, elsewhere, keeps the centre */
    {
        const hkf_real_t elsewhere[3] = {R(12.0), R(4.0), R(45.0)};
        assert_int_equal(hkf_position_update(&f, elsewhere, R(1.0), R(frame_s), NULL), HKF_OK);
        assert_true(fabs(D(state_of(&f).position[0]) - 12.0) < TEST_TOL);
    }
    assert_true(fabs(D(state_of(&f).center[0]) - 8.0) < 0.05 && fabs(D(state_of(&f).center[2]) - 50.0) < 0.05);
    hkf_position_reset(&f); /* a centre set (by a recentre) outlives a reset */
    assert_int_equal(hkf_position_recenter(&f), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_position_predict(&f, R(frame_s), NULL), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_position_get_center(&f, c), HKF_OK);
    assert_true(fabs(D(c[0]) - 8.0) < 0.05 && fabs(D(c[2]) - 50.0) < 0.05);
    assert_int_equal(hkf_position_update(&f, other, R(1.0), R(frame_s), NULL), HKF_OK);
    assert_true(fabs(D(state_of(&f).center[0]) - 8.0) < 0.05); /* the next track does not move it */
    assert_int_equal(hkf_position_get_center(NULL, c), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_position_get_center(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
}

/* A gap beyond max_dt restarts the track at the measurement. */
static void test_gap_restarts(void **state)
{
    (void)state;
    hkf_position_filter_t f = started_filter(0.0, 0.0, 60.0);
    const hkf_real_t far[3] = {R(20.0), R(-5.0), R(80.0)};
    hkf_position_output_t out;
    assert_int_equal(hkf_position_update(&f, far, R(1.0), R(2.0), &out), HKF_OK);
    assert_true(fabs(D(out.position[0]) - 20.0) < TEST_TOL && fabs(D(out.position[2]) - 80.0) < TEST_TOL);
    assert_true(fabs(D(out.rate[2])) < TEST_TOL);
}

/* The outlier gate: a measurement farther than max_speed dt + 3 sigmas is refused (the prediction
 * stands, HKF_FLAG_GATED, COASTING); max_gate_rejections such in a row, then the next restarts
 * the track there. A real lean at 100 cm/s is never refused; max_speed 0 turns the gate off. */
static void test_gate(void **state)
{
    (void)state;
    hkf_position_settings_t s;
    hkf_position_filter_t f = started_filter(0.0, 0.0, 60.0);
    const hkf_real_t still[3] = {R(0.0), R(0.0), R(60.0)};
    const hkf_real_t forged[3] = {R(1000.0), R(-1000.0), R(1000.0)};
    const hkf_real_t moved[3] = {R(20.0), R(0.0), R(60.0)};
    hkf_position_output_t out;
    unsigned i;
    for (i = 0; i < 60; ++i) {
        assert_int_equal(hkf_position_update(&f, still, R(1.0), R(frame_s), &out), HKF_OK);
        assert_int_equal(out.flags, 0u);
    }
    assert_int_equal(hkf_position_update(&f, forged, R(1.0), R(frame_s), &out), HKF_OK);
    assert_true(out.flags == HKF_FLAG_GATED && out.status == HKF_STATUS_COASTING);
    assert_true(fabs(D(out.position[0])) < 0.01 && fabs(D(out.position[2]) - 60.0) < 0.01);
    assert_int_equal(hkf_position_update(&f, still, R(1.0), R(frame_s), &out), HKF_OK); /* the count starts again */
    assert_int_equal(out.flags, 0u);
    for (i = 0; i < hkf_position_default_settings.max_gate_rejections; ++i) {
        assert_int_equal(hkf_position_update(&f, moved, R(1.0), R(frame_s), &out), HKF_OK);
        assert_int_equal(out.flags, HKF_FLAG_GATED);
    }
    assert_int_equal(hkf_position_update(&f, moved, R(1.0), R(frame_s), &out), HKF_OK);
    assert_int_equal(out.flags, HKF_FLAG_REACQUIRED); /* they agree: the head is there */
    assert_true(fabs(D(out.position[0]) - 20.0) < TEST_TOL && out.status == HKF_STATUS_TRACKING);
    f = started_filter(0.0, 0.0, 60.0);
    for (i = 0; i < 30; ++i) { /* still, then a lean at 100 cm/s for 0.5 s */
        assert_int_equal(hkf_position_update(&f, still, R(1.0), R(frame_s), &out), HKF_OK);
    }
    for (i = 1; i <= 30; ++i) {
        const hkf_real_t lean[3] = {R(0.0), R(0.0), R(60.0 - 100.0 * frame_s * i)};
        assert_int_equal(hkf_position_update(&f, lean, R(1.0), R(frame_s), &out), HKF_OK);
        assert_int_equal(out.flags, 0u);
    }
    s = hkf_position_default_settings; /* a noisy still head (R 1 cm^2), a gate of 6 cm/s: the noise passes, 3 sigmas */
    s.r_const[0] = s.r_const[1] = s.r_const[2] = R(1.0);
    s.max_speed = R(6.0);
    f = started_filter_with(&s, 0.0, 0.0, 60.0);
    for (i = 0; i < 120; ++i) {
        const double noise = ((int)(i * 7919u % 11u) - 5) * 0.1; /* +-0.5 cm, spread, about 0.32 cm rms */
        const hkf_real_t z[3] = {R(noise), R(0.0), R(60.0 - noise)};
        assert_int_equal(hkf_position_update(&f, z, R(1.0), R(frame_s), &out), HKF_OK);
        assert_int_equal(out.flags & HKF_FLAG_GATED, 0u);
    }
    s = hkf_position_default_settings;
    s.max_speed = 0;
    f = started_filter_with(&s, 0.0, 0.0, 60.0);
    assert_int_equal(hkf_position_update(&f, forged, R(1.0), R(frame_s), &out), HKF_OK);
    assert_true(out.flags == 0u && D(out.position[0]) > 1.0); /* no gate: taken */
}

/* After a gap beyond max_dt the first position is gated as any other, against the track as it
 * was held (moved on by its rate for max_dt, its variance grown): a forged one 0.7 s later (past
 * max_dt 0.5 s) is refused and the held position stands; the real ones that follow are taken; a
 * position within reach of the held one after a gap starts the new track there. */
static void test_gate_after_gap(void **state)
{
    (void)state;
    hkf_position_filter_t f = still_filter();
    const hkf_real_t still[3] = {R(0.0), R(0.0), R(60.0)};
    const hkf_real_t forged[3] = {R(1000.0), R(-1000.0), R(1000.0)};
    const hkf_real_t near[3] = {R(30.0), R(0.0), R(60.0)};
    hkf_position_output_t out;
    unsigned i;
    assert_true(hkf_position_default_settings.max_dt < R(0.7));
    assert_int_equal(hkf_position_update(&f, forged, R(1.0), R(0.7), &out), HKF_OK);
    assert_true(out.flags == HKF_FLAG_GATED && out.status == HKF_STATUS_COASTING);
    assert_true(fabs(D(out.position[0])) < 0.01 && fabs(D(out.position[2]) - 60.0) < 0.01);
    for (i = 0; i < 10; ++i) { /* the real head, still where it was */
        assert_int_equal(hkf_position_update(&f, still, R(1.0), R(frame_s), &out), HKF_OK);
        assert_int_equal(out.flags, 0u);
    }
    assert_true(fabs(D(out.position[0])) < 0.01 && fabs(D(out.position[2]) - 60.0) < 0.01);
    assert_int_equal(hkf_position_update(&f, near, R(1.0), R(0.7), &out), HKF_OK); /* 30 cm in 0.7 s: within reach */
    assert_int_equal(out.flags, HKF_FLAG_REACQUIRED);
    assert_true(fabs(D(out.position[0]) - 30.0) < TEST_TOL && out.status == HKF_STATUS_TRACKING);
}

/* The gate restarts the track only at refused positions that agree with each other (the head is
 * there): max_gate_rejections + 1 far positions that each disagree with the one before do not
 * restart it, and the real ones after them are taken; as many that agree do. */
static void test_gate_restart_needs_agreement(void **state)
{
    (void)state;
    hkf_position_filter_t f = still_filter();
    const hkf_real_t still[3] = {R(0.0), R(0.0), R(60.0)};
    const unsigned most = hkf_position_default_settings.max_gate_rejections;
    hkf_position_output_t out;
    unsigned i;
    for (i = 0; i <= most + 1; ++i) { /* x 900, -900, 900, ...: each far off, none agreeing with the last */
        const hkf_real_t forged[3] = {R(i % 2 ? -900.0 : 900.0), R(0.0), R(900.0)};
        assert_int_equal(hkf_position_update(&f, forged, R(1.0), R(frame_s), &out), HKF_OK);
        assert_int_equal(out.flags, HKF_FLAG_GATED);
    }
    assert_true(fabs(D(out.position[0])) < 0.01 && fabs(D(out.position[2]) - 60.0) < 0.01);
    assert_int_equal(hkf_position_update(&f, still, R(1.0), R(frame_s), &out), HKF_OK);
    assert_int_equal(out.flags, 0u); /* the real head is still taken */
    for (i = 0; i < most; ++i) { /* x 900 in a row: they agree */
        const hkf_real_t moved[3] = {R(900.0), R(0.0), R(900.0)};
        assert_int_equal(hkf_position_update(&f, moved, R(1.0), R(frame_s), &out), HKF_OK);
        assert_int_equal(out.flags, HKF_FLAG_GATED);
    }
    {
        const hkf_real_t moved[3] = {R(900.0), R(0.0), R(900.0)};
        assert_int_equal(hkf_position_update(&f, moved, R(1.0), R(frame_s), &out), HKF_OK);
        assert_int_equal(out.flags, HKF_FLAG_REACQUIRED);
    }
}

/* The gate at its edge (constant R and q, so the edge is known): on an axis, max_speed dt + 3 sqrt(S) from the
 * prediction, S = the predicted variance (Eq. 1-3) + R. A measurement 1 % inside it is taken, 1 % beyond it
 * refused, in every numeric build. */
static void test_gate_edge(void **state)
{
    (void)state;
    hkf_position_settings_t s = constant_settings();
    hkf_position_filter_t f;
    const hkf_real_t still[3] = {R(0.0), R(0.0), R(60.0)};
    const double dt = frame_s, q = D(s.process_noise[0]), r = D(s.r_const[0]);
    hkf_position_output_t out;
    int i, side;
    s.max_speed = R(6.0);
    for (side = 0; side < 2; ++side) {
        f = started_filter_with(&s, 0.0, 0.0, 60.0);
        for (i = 0; i < 120; ++i) {
            assert_int_equal(hkf_position_update(&f, still, R(1.0), R(dt), &out), HKF_OK);
        }
        {
            const hkf_position_state_t st = state_of(&f);
            const double p00 = D(st.p00[0]) + dt * (2.0 * D(st.p01[0]) + dt * D(st.p11[0])) + q * dt * dt * dt / 3.0;
            const double edge = 6.0 * dt + 3.0 * sqrt(p00 + r), x = D(st.position[0]) + D(st.rate[0]) * dt;
            const hkf_real_t z[3] = {R(x + edge * (side == 0 ? 0.99 : 1.01)), R(0.0), R(60.0)};
            assert_int_equal(hkf_position_update(&f, z, R(1.0), R(dt), &out), HKF_OK);
            print_message("edge %.4f cm: %s side -> flags %u\n", edge, side == 0 ? "inner" : "outer", out.flags);
            assert_int_equal(out.flags, side == 0 ? 0u : (unsigned)HKF_FLAG_GATED);
        }
    }
}

/* The centre set as a program published it; out of range or non-finite leaves it as it was. */
static void test_set_center(void **state)
{
    (void)state;
    hkf_position_filter_t f = started_filter(1.0, 2.0, 60.0);
    const hkf_real_t center[3] = {R(1.5), R(-2.0), R(1.0)};
    const hkf_real_t beyond[3] = {R(0.0), R(0.0), R(1001.0)};
    hkf_position_state_t st;
    assert_int_equal(hkf_position_set_center(&f, center), HKF_OK);
    st = state_of(&f);
    assert_true(fabs(D(st.center[0]) - 1.5) < TEST_TOL && fabs(D(st.center[2]) - 1.0) < TEST_TOL);
    assert_int_equal(hkf_position_set_center(&f, beyond), HKF_ERROR_POSITION_RANGE);
    st = state_of(&f);
    assert_true(fabs(D(st.center[2]) - 1.0) < TEST_TOL);
    hkf_position_restart(&f); /* a restart keeps it */
    assert_true(fabs(D(state_of(&f).center[2]) - 1.0) < TEST_TOL);
    hkf_position_reset(&f); /* and a reset (hkf_set_center's rule): only hkf_position_init forgets it */
    assert_true(fabs(D(state_of(&f).center[2]) - 1.0) < TEST_TOL);
    assert_int_equal(hkf_position_init(&f, &hkf_position_default_settings), HKF_OK);
    assert_int_equal(hkf_position_get_center(&f, st.center), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_position_set_center(NULL, center), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_position_set_center(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
}

/* The range: whatever comes in, the state, the output and every extrapolation stay within
 * +-HKF_MAX_ABS_POSITION, and the rate within +-HKF_MAX_SPEED. */
static void test_range(void **state)
{
    (void)state;
    hkf_position_settings_t s;
    hkf_position_filter_t f;
    hkf_position_output_t out;
    int i, a;
    s = hkf_position_default_settings;
    s.max_speed = 0; /* no gate: the worst case */
    f = started_filter_with(&s, -1000.0, 0.0, 1.0);
    for (i = 0; i < 40; ++i) {
        const double x = i < 20 ? -1000.0 : 1000.0;
        const hkf_real_t z[3] = {R(x), R(-x), R(i % 2 ? 1000.0 : 1.0)};
        assert_int_equal(hkf_position_update(&f, z, R(1.0), R(frame_s), &out), HKF_OK);
        for (a = 0; a < 3; ++a) {
            assert_true(fabs(D(out.position[a])) <= HKF_MAX_ABS_POSITION);
            assert_true(fabs(D(out.rate[a])) <= HKF_MAX_SPEED);
        }
        assert_int_equal(hkf_position_extrapolate(&f, R(0.4), &out), HKF_OK);
        for (a = 0; a < 3; ++a) {
            assert_true(fabs(D(out.position[a])) <= HKF_MAX_ABS_POSITION);
        }
    }
}

/* Between measurements: moved on by the rate for up to max_dt (COASTING), beyond held there with
 * rate 0 (LOST), the variance growing all the while; the filter untouched; the centre on it. */
static void test_extrapolate_coast_then_stale(void **state)
{
    (void)state;
    hkf_position_filter_t f = started_constant_filter(0.0, 0.0, 60.0), before;
    hkf_position_output_t out, previous;
    hkf_position_state_t st;
    const double max_dt = D(constant_settings().max_dt);
    int i;
    for (i = 1; i <= 60; ++i) { /* a lean at 10 cm/s in x */
        const hkf_real_t z[3] = {R(10.0 * frame_s * i), R(0.0), R(60.0)};
        assert_int_equal(hkf_position_update(&f, z, R(1.0), R(frame_s), &out), HKF_OK);
    }
    before = f;
    assert_int_equal(hkf_position_extrapolate(&f, R(0.0), &previous), HKF_OK);
    assert_true(previous.status == HKF_STATUS_TRACKING && D(previous.position[0]) == D(out.position[0]));
    for (i = 1; i <= 40; ++i) {
        const double ahead = 0.05 * i;
        assert_int_equal(hkf_position_extrapolate(&f, R(ahead), &out), HKF_OK);
        assert_true(D(out.variance[0]) > D(previous.variance[0]));
        if (ahead <= max_dt - 0.01) {
            assert_int_equal(out.status, HKF_STATUS_COASTING);
            assert_true(fabs(D(out.position[0]) - (D(state_of(&f).position[0]) + D(state_of(&f).rate[0]) * ahead)) < 10 * TEST_TOL);
        } else if (ahead > max_dt + 0.01) {
            assert_int_equal(out.status, HKF_STATUS_LOST);
            assert_true(D(out.rate[0]) == 0.0);
            assert_true(fabs(D(out.position[0]) - (D(state_of(&f).position[0]) + D(state_of(&f).rate[0]) * max_dt)) < 10 * TEST_TOL);
        }
        previous = out;
    }
    for (i = 1; i <= 6; ++i) { /* held for 5 s to 30 s: the variance grows all the while (it stopped at 10 s) */
        assert_int_equal(hkf_position_extrapolate(&f, R(5.0 * i), &out), HKF_OK);
        assert_true(D(out.variance[0]) > D(previous.variance[0]) && out.status == HKF_STATUS_LOST);
        previous = out;
    }
    assert_int_equal(hkf_position_extrapolate(&f, R(2.0), &previous), HKF_OK);
    assert_int_equal(hkf_position_extrapolate(&f, R(-0.1), &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_position_extrapolate(&f, R(0.1), NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_position_get_state(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_position_get_state(NULL, &st), HKF_ERROR_NULL_ARGUMENT);
    assert_memory_equal(&f, &before, sizeof f);
    st = state_of(&f); /* the state the output shows */
    assert_int_equal(hkf_position_extrapolate(&f, R(0.0), &out), HKF_OK);
    assert_true(st.position[0] == out.position[0] && st.rate[0] == out.rate[0] && st.p00[0] == out.variance[0]);
    assert_true(D(st.rate[0]) > 9.0 && D(st.p11[0]) > 0.0);
    assert_int_equal(hkf_position_recenter_at(&f, R(2.0)), HKF_OK);
    assert_true(fabs(D(state_of(&f).center[0]) - D(previous.position[0])) < TEST_TOL);
    hkf_position_reset(&f);
    assert_int_equal(hkf_position_extrapolate(&f, R(0.1), &out), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_position_recenter_at(&f, R(0.1)), HKF_ERROR_NOT_INITIALIZED);
}

/* Bad settings get their code. */
static void test_setting_errors(void **state)
{
    (void)state;
    hkf_position_settings_t s;
    hkf_position_filter_t f = started_filter(0.0, 0.0, 60.0);
    s = hkf_position_default_settings;
    s.process_noise[1] = R(-1.0);
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_PROCESS_NOISE);
    s = hkf_position_default_settings;
    s.r_const[2] = 0;
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_R_CONST);
    s = hkf_position_default_settings;
    s.max_dt = 0;
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_MAX_DT);
    s = hkf_position_default_settings;
    s.r_min = 0;
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_R_RANGE);
    s = hkf_position_default_settings;
    s.r_max = R(0.5 * D(s.r_min)); /* below r_min */
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_R_RANGE);
    s = hkf_position_default_settings;
    s.p0_rate = 0;
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_P0);
    s = hkf_position_default_settings;
    s.still_wander[1] = R(-1.0);
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_MOTION);
    s = hkf_position_default_settings;
    s.stop_rate = R(2.0 * HKF_MAX_RATE);
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_MOTION);
    s = hkf_position_default_settings;
    s.max_speed = R(-1.0);
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_GATE);
    s = hkf_position_default_settings;
    s.max_gate_rejections = 0u;
    assert_int_equal(hkf_position_init(&f, &s), HKF_ERROR_SETTING_GATE);
    s.max_speed = 0; /* no gate: no count needed */
    assert_int_equal(hkf_position_init(&f, &s), HKF_OK);
    s.max_speed = R(HKF_MAX_SPEED);
    s.max_gate_rejections = 1u;
    assert_int_equal(hkf_position_init(&f, &s), HKF_OK);
    assert_int_equal(hkf_position_init(NULL, &s), HKF_ERROR_NULL_ARGUMENT);
}

/* Bad input gets its code, the filter untouched. */
static void test_input_errors(void **state)
{
    (void)state;
    hkf_position_filter_t f = started_filter(0.0, 0.0, 60.0), before;
    const hkf_real_t beyond[3] = {R(0.0), R(0.0), R(2000.0)};
    const hkf_real_t fine[3] = {R(0.0), R(0.0), R(60.0)};
    before = f;
    assert_int_equal(hkf_position_update(&f, beyond, R(1.0), R(frame_s), NULL), HKF_ERROR_POSITION_RANGE);
    assert_int_equal(hkf_position_update(&f, fine, R(0.5), R(frame_s), NULL), HKF_ERROR_SCALE_RANGE);
    assert_int_equal(hkf_position_update(&f, fine, R(1.0), R(0.0), NULL), HKF_ERROR_DT_RANGE); /* as hkf_update */
    assert_int_equal(hkf_position_update(&f, fine, R(1.0), R(-frame_s), NULL), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_position_update(&f, NULL, R(1.0), R(frame_s), NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_position_predict(&f, R(0.0), NULL), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_position_predict(&f, R(-1.0), NULL), HKF_ERROR_DT_RANGE);
#if TEST_HAS_NON_FINITE
    {
        const hkf_real_t nan_z[3] = {R(0.0), R(NAN), R(60.0)};
        assert_int_equal(hkf_position_update(&f, nan_z, R(1.0), R(frame_s), NULL), HKF_ERROR_NON_FINITE);
        assert_int_equal(hkf_position_predict(&f, R(NAN), NULL), HKF_ERROR_NON_FINITE);
    }
#endif
    assert_memory_equal(&f, &before, sizeof f);
}

/* The rate after a lean: once the head is still again, HOLD (rate 0) takes the rate down with MOVE's
 * probability, faster than the Kalman update alone (MOVE without the adaptation, start_rate 0), and
 * the position settles where the head stopped. */
static void test_rate_settles_at_rest(void **state)
{
    hkf_position_settings_t adapting = hkf_position_default_settings, move_alone = hkf_position_default_settings;
    hkf_position_filter_t f[2];
    hkf_position_output_t out[2];
    double rate_after[2] = {0, 0};
    unsigned seed = 11;
    int i, k;
    (void)state;
    move_alone.start_rate = R(0.0);
    f[0] = started_filter_with(&adapting, 0.0, 0.0, 60.0);
    f[1] = started_filter_with(&move_alone, 0.0, 0.0, 60.0);
    for (i = 1; i <= 150; ++i) { /* still 1 s, a lean of 10 cm in 0.5 s, still again */
        const double t = i * frame_s;
        const double z_true = t < 1.0 ? 60.0 : t < 1.5 ? 60.0 - 20.0 * (t - 1.0) : 50.0;
        const hkf_real_t z[3] = {R(uniform_noise(&seed, 0.02)), R(uniform_noise(&seed, 0.02)),
                                 R(z_true + uniform_noise(&seed, 0.05))};
        for (k = 0; k < 2; ++k) {
            assert_int_equal(hkf_position_update(&f[k], z, R(1.0), R(frame_s), &out[k]), HKF_OK);
            if (i >= 110 && i <= 130) { /* 1/3 to 2/3 s after the stop */
                rate_after[k] += fabs(D(out[k].rate[2])) / 21.0;
            }
        }
    }
    print_message("mean |rate| 1/3 to 2/3 s after the stop: %.3f cm/s adapting, %.3f cm/s MOVE alone\n",
                  rate_after[0], rate_after[1]);
    assert_true(rate_after[0] < 0.5 * rate_after[1]);
    assert_true(fabs(D(out[0].position[2]) - 50.0) < 0.1);
}

/* The noise level handed over (hkf_position_set_noise): R = the scale x n, within [r_min, r_max]
 * (the step's variance shows it, MOVE alone); NULL back to r_const; kept by a reset and a restart;
 * a bad level refused, nothing changed. */
static void test_set_noise(void **state)
{
    hkf_position_settings_t s = constant_settings();
    hkf_position_filter_t f, before;
    const hkf_real_t level[3] = {R(0.01), R(0.02), R(0.5)};
    const hkf_real_t zero[3] = {R(0.01), R(0.0), R(0.5)};
    const hkf_real_t z[3] = {R(0.0), R(0.0), R(60.0)};
    hkf_position_output_t out;
    int a;
    (void)state;
    s.r_max = R(0.9);
    assert_int_equal(hkf_position_init(&f, &s), HKF_OK);
    assert_int_equal(hkf_position_set_noise(&f, level), HKF_OK);
    assert_int_equal(hkf_position_update(&f, z, R(2.0), R(frame_s), &out), HKF_OK); /* a track starts: P00 = R */
    for (a = 0; a < 3; ++a) {
        const double r = fmin(2.0 * D(level[a]), 0.9);
        assert_true(fabs(D(out.variance[a]) - r) < TEST_TOL + 1e-3 * r);
        assert_true(fabs(D(state_of(&f).noise[a]) - D(level[a])) < TEST_TOL);
    }
    hkf_position_reset(&f);
    assert_true(fabs(D(state_of(&f).noise[2]) - 0.5) < TEST_TOL); /* kept */
    hkf_position_restart(&f);
    assert_true(fabs(D(state_of(&f).noise[2]) - 0.5) < TEST_TOL);
    before = f;
    assert_int_equal(hkf_position_set_noise(&f, zero), HKF_ERROR_NOISE_RANGE);
    for (a = 0; a < 3; ++a) { /* each axis alone bad, the others good */
        hkf_real_t bad[3] = {R(0.01), R(0.02), R(0.5)};
        bad[a] = 0;
        assert_int_equal(hkf_position_set_noise(&f, bad), HKF_ERROR_NOISE_RANGE);
        bad[a] = R(-0.5);
        assert_int_equal(hkf_position_set_noise(&f, bad), HKF_ERROR_NOISE_RANGE);
#if TEST_HAS_NON_FINITE
        bad[a] = NAN;
        assert_int_equal(hkf_position_set_noise(&f, bad), HKF_ERROR_NON_FINITE);
        bad[a] = INFINITY;
        assert_int_equal(hkf_position_set_noise(&f, bad), HKF_ERROR_NON_FINITE);
#endif
    }
    assert_int_equal(hkf_position_set_noise(NULL, level), HKF_ERROR_NULL_ARGUMENT);
    assert_memory_equal(&f, &before, sizeof f);
    assert_int_equal(hkf_position_set_noise(&f, NULL), HKF_OK); /* back to r_const */
    assert_int_equal(hkf_position_update(&f, z, R(1.0), R(frame_s), &out), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_true(fabs(D(out.variance[a]) - D(s.r_const[a])) < TEST_TOL + 1e-3 * D(s.r_const[a]));
    }
}

/* The calibration handed to the position (hkf_calibration_init_position): n starts at r_const, a
 * reset takes it back there, and its noise_time 0 leaves the filter on r_const; its settings are
 * checked as the angles' are. */
static void test_calibration_lifecycle(void **state)
{
    calibrated_t k = calibrated_with(&hkf_position_default_settings);
    hkf_calibration_settings_t off = hkf_default_calibration_settings;
    hkf_real_t n[3];
    unsigned seed = 5;
    int i, a;
    (void)state;
    for (a = 0; a < 3; ++a) {
        assert_true(D(state_of(&k.f).noise[a]) == D(hkf_position_default_settings.r_const[a]));
    }
    for (i = 0; i < 120; ++i) {
        const hkf_real_t z[3] = {R(uniform_noise(&seed, 0.01)), R(uniform_noise(&seed, 0.01)),
                                 R(60.0 + uniform_noise(&seed, 0.02))};
        calibrated_step(&k, z, 1.0, frame_s, NULL);
    }
    assert_true(D(state_of(&k.f).noise[2]) < 0.1 * D(hkf_position_default_settings.r_const[2]));
    assert_int_equal(hkf_calibration_reset_position(&k.c, &k.f), HKF_OK);
    assert_int_equal(hkf_calibration_get_noise(&k.c, n), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_true(D(n[a]) == D(hkf_position_default_settings.r_const[a]));
        assert_true(D(state_of(&k.f).noise[a]) == D(n[a]));
    }
    off.noise_time = 0;
    assert_int_equal(hkf_calibration_init_position(&k.c, &off, &k.f), HKF_OK);
    for (i = 0; i < 30; ++i) {
        const hkf_real_t z[3] = {R(0.0), R(0.0), R(60.0 + (i % 2 ? 1.0 : -1.0))};
        calibrated_step(&k, z, 1.0, frame_s, NULL);
    }
    assert_true(D(state_of(&k.f).noise[2]) == D(hkf_position_default_settings.r_const[2])); /* off: r_const */
    off.noise_rise = R(-1.0);
    assert_int_equal(hkf_calibration_init_position(&k.c, &off, &k.f), HKF_ERROR_SETTING_CALIBRATION);
    assert_int_equal(hkf_calibration_init_position(NULL, &off, &k.f), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_calibration_update_position(&k.c, NULL, NULL, R(frame_s)), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_calibration_reset_position(NULL, &k.f), HKF_ERROR_NULL_ARGUMENT);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_step_matches_equations),
        cmocka_unit_test(test_lean_followed_noise_smoothed),
        cmocka_unit_test(test_noise_measured),
        cmocka_unit_test(test_calibrated_step_matches_equations),
        cmocka_unit_test(test_still_stiller_lean_sooner),
        cmocka_unit_test(test_hold_and_move),
        cmocka_unit_test(test_started_and_status),
        cmocka_unit_test(test_coarse_measurement_trusted_less),
        cmocka_unit_test(test_center_recenter_reset),
        cmocka_unit_test(test_gap_restarts),
        cmocka_unit_test(test_gate),
        cmocka_unit_test(test_gate_after_gap),
        cmocka_unit_test(test_gate_restart_needs_agreement),
        cmocka_unit_test(test_set_center),
        cmocka_unit_test(test_gate_edge),
        cmocka_unit_test(test_range),
        cmocka_unit_test(test_extrapolate_coast_then_stale),
        cmocka_unit_test(test_setting_errors),
        cmocka_unit_test(test_input_errors),
        cmocka_unit_test(test_rate_settles_at_rest),
        cmocka_unit_test(test_set_noise),
        cmocka_unit_test(test_calibration_lifecycle),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

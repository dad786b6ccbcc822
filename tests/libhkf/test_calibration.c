/*
 * test_calibration.c - noise calibration (hkf_calibration.h) beside the
 * filter: the frame-noise estimate n and what it does to R (hkf_set_noise);
 * the defaults' motion adaptation on a glance and a blip; and Eq. 8 read at
 * the wrapped yaw.
 */
#include "test_support.h"

#include "head_motion_sim.h"
#include "hkf/hkf_calibration.h"

static const double frame_s = 1.0 / 30.0;

/* A filter with the noise calibration beside it, stepped as hkf_calibration.h says. */
typedef struct {
    hkf_filter_t f;
    hkf_calibration_t c;
} calibrated_t;

static void calibrated_init(calibrated_t *t, const hkf_settings_t *s)
{
    assert_int_equal(hkf_init(&t->f, s), HKF_OK);
    assert_int_equal(hkf_calibration_init(&t->c, &hkf_default_calibration_settings, &t->f), HKF_OK);
}

static void calibrated_update(calibrated_t *t, const hkf_real_t z[3], hkf_real_t dt, hkf_output_t *out)
{
    assert_int_equal(hkf_update(&t->f, z, dt, out), HKF_OK);
    assert_int_equal(hkf_calibration_update(&t->c, &t->f, z, dt), HKF_OK);
}

/* The defaults (the calibration beside them) with R = n (constant mode: no pose factor). */
static hkf_settings_t calibrated_settings(void)
{
    hkf_settings_t s = hkf_default_settings;
    s.noise_mode = HKF_NOISE_CONSTANT;
    s.loop_closure = HKF_LOOP_CLOSURE_OFF;
    s.r_min = R(0.001);
    return s;
}

/* Runs `frames` frames of yaw = truth(t) + sigma N(0, 1) (pitch and roll likewise, at 0)
 * and returns the last R of yaw, which is n in constant mode. With `jitter`, also the
 * RMS frame-to-frame change of the output's yaw over the last half. */
static double run_still(const hkf_settings_t *s, double sigma, double rate, int frames, unsigned seed,
                        double *jitter)
{
    calibrated_t t;
    hkf_output_t out;
    sim_rng_t rng;
    double sum = 0.0, prev = 0.0;
    int i, counted = 0;
    calibrated_init(&t, s);
    sim_rng_seed(&rng, seed);
    for (i = 0; i < frames; ++i) {
        hkf_real_t z[3];
        const double truth = rate * frame_s * i;
        set3(z, sigma * sim_rng_gaussian(&rng), truth + sigma * sim_rng_gaussian(&rng), sigma * sim_rng_gaussian(&rng));
        calibrated_update(&t, z, R(frame_s), &out);
        if (i > frames / 2) {
            const double step = D(out.angle[1]) - prev - rate * frame_s;
            sum += step * step;
            ++counted;
        }
        prev = D(out.angle[1]);
    }
    if (jitter != NULL) {
        *jitter = sqrt(sum / counted);
    }
    return D(out.r[1]);
}

/* White frame noise of sigma: n settles below sigma^2 (the floor tracker reads the
 * low-passed power's lower envelope: 0.47 sigma^2 here, within 0.35-0.65),
 * the same on a head turning at constant speed (the second difference cancels it),
 * and scales with sigma^2. */
static void test_noise_estimate_follows_the_noise(void **state)
{
    const hkf_settings_t s = calibrated_settings();
    const double still = run_still(&s, 0.3, 0.0, 600, 1u, NULL);
    const double turning = run_still(&s, 0.3, 20.0, 600, 1u, NULL);
    const double noisier = run_still(&s, 0.6, 0.0, 600, 1u, NULL);
    (void)state;
    print_message("n: %.4f still, %.4f turning at 20 deg/s (sigma^2 0.09); %.4f at sigma 0.6 (0.36)\n", still,
                  turning, noisier);
    assert_true(still > 0.35 * 0.09 && still < 0.65 * 0.09);
    assert_true(turning > 0.35 * 0.09 && turning < 0.65 * 0.09);
    assert_true(noisier / still > 0.7 * 4.0 && noisier / still < 1.3 * 4.0);
}

/* With calibration the still output filters the noise whatever its level (R
 * follows it). The share is not the same at both levels: MOVE's q is a fixed
 * number of deg^2/s^3 (its unit does not depend on calibration), so a noisier
 * camera is smoothed more; and n reads the noise's lower envelope (about half
 * its power), which makes HOLD's likelihood the stricter judge. */
static void test_jitter_share_holds_with_more_noise(void **state)
{
    const hkf_settings_t s = calibrated_settings();
    double j1, j2;
    (void)state;
    run_still(&s, 0.3, 0.0, 900, 2u, &j1);
    run_still(&s, 0.6, 0.0, 900, 2u, &j2);
    print_message("still jitter %.4f at sigma 0.3, %.4f at sigma 0.6: share %.3f vs %.3f\n", j1, j2, j1 / 0.3,
                  j2 / 0.6);
    assert_true(j1 / 0.3 < 0.5); /* it filters at either level */
    assert_true(j2 / 0.6 < 0.5);
}

/* A glance: the head turns 30 deg in 0.15 s (200 deg/s) and stops. The
 * defaults follow (less error during the turn than the paper's filter with a
 * q small enough to be as still, 1 deg^2/s^3), overshoot the stop by under
 * 5 % of the move, and after it their rate returns to 0 (HOLD's), nearer 0 than
 * the paper's filter with the defaults' moving q. */
static void test_glance_followed_without_overshoot(void **state)
{
    hkf_settings_t with = calibrated_settings(), small_q, moving_q;
    calibrated_t fw, fs, fm;
    hkf_output_t ow, os, om;
    sim_rng_t rng;
    double turn_w = 0.0, turn_s = 0.0, over_w = 0.0, rate_w = 0.0, rate_m = 0.0;
    int i, a;
    (void)state;
    moving_q = with;
    moving_q.start_rate = 0;
    small_q = moving_q;
    for (a = 0; a < HKF_AXES; ++a) {
        small_q.process_noise[a] = R(1);
    }
    calibrated_init(&fw, &with);
    calibrated_init(&fs, &small_q);
    calibrated_init(&fm, &moving_q);
    sim_rng_seed(&rng, 3u);
    for (i = 0; i < 300; ++i) {
        const double t = i * frame_s;
        const double truth = t < 5.0 ? 0.0 : t < 5.15 ? 200.0 * (t - 5.0) : 30.0;
        hkf_real_t z[3];
        set3(z, 0, truth + 0.3 * sim_rng_gaussian(&rng), 0);
        calibrated_update(&fw, z, R(frame_s), &ow);
        calibrated_update(&fs, z, R(frame_s), &os);
        calibrated_update(&fm, z, R(frame_s), &om);
        if (t >= 5.0 && t < 5.3) {
            turn_w += fabs(truth - D(ow.angle[1]));
            turn_s += fabs(truth - D(os.angle[1]));
        }
        if (t >= 5.15 && t < 6.5) {
            over_w = fmax(over_w, D(ow.angle[1]) - 30.0);
        }
        if (t >= 5.5 && t < 6.5) {
            rate_w += fabs(D(ow.rate[1]));
            rate_m += fabs(D(om.rate[1]));
        }
    }
    print_message("turn error %.1f vs %.1f deg summed with a small q alone; overshoot %.2f deg; |rate| after "
                  "the stop %.1f vs %.1f deg/s summed with the moving q alone\n", turn_w, turn_s, over_w, rate_w, rate_m);
    assert_true(turn_w < 0.5 * turn_s);
    assert_true(over_w < 0.05 * 30.0);
    assert_true(rate_w < rate_m);
}

/* A one-frame blip (2 deg in roll against 0.1 deg of noise, as d14 has) is
 * followed (MOVE explains it better than HOLD; an outlier is the gate's to
 * refuse), but it is gone two frames later: the next measurements make HOLD
 * the likelier again. The same 2 deg held is followed within a few frames. */
static void test_blip_gone_motion_followed(void **state)
{
    const hkf_settings_t s = calibrated_settings();
    calibrated_t blip, held;
    hkf_output_t ob, oh;
    sim_rng_t rng;
    double blip_after = 0.0, held_after = 0.0;
    int i;
    (void)state;
    calibrated_init(&blip, &s);
    calibrated_init(&held, &s);
    sim_rng_seed(&rng, 4u);
    for (i = 0; i < 200; ++i) {
        const double noise = 0.1 * sim_rng_gaussian(&rng);
        hkf_real_t zb[3], zh[3];
        set3(zb, 0, 0, (i == 150 ? 2.0 : 0.0) + noise);
        set3(zh, 0, 0, (i >= 150 ? 2.0 : 0.0) + noise);
        calibrated_update(&blip, zb, R(frame_s), &ob);
        calibrated_update(&held, zh, R(frame_s), &oh);
        if (i >= 152) {
            blip_after = fmax(blip_after, fabs(D(ob.angle[2])));
        }
        if (i == 155) {
            held_after = D(oh.angle[2]);
        }
    }
    print_message("two frames after a 2 deg blip the output is within %.2f deg of 0; a 2 deg step: %.2f deg after "
                  "5 frames\n", blip_after, held_after);
    assert_true(blip_after < 0.3);
    assert_true(held_after > 1.7);
}

/* Eq. 8 is read at the wrapped yaw: a yaw of 359 deg is -1 deg, near the curve's
 * centre, not on its tail (FSA-Net yaw: ~3.5 deg at the centre, ~7.6 far out). */
static void test_yaw_r_read_wrapped(void **state)
{
    hkf_settings_t s = hkf_paper_settings;
    hkf_filter_t f359, fm1;
    hkf_output_t o359, om1;
    hkf_real_t z[3];
    int i;
    (void)state;
    s.loop_closure = HKF_LOOP_CLOSURE_OFF;
    assert_int_equal(hkf_init(&f359, &s), HKF_OK);
    assert_int_equal(hkf_init(&fm1, &s), HKF_OK);
    for (i = 0; i < 3; ++i) { /* the track's start, then two updates */
        set3(z, 0, 359, 0);
        assert_int_equal(hkf_update(&f359, z, R(frame_s), &o359), HKF_OK);
        set3(z, 0, -1, 0);
        assert_int_equal(hkf_update(&fm1, z, R(frame_s), &om1), HKF_OK);
        assert_near_at(D(o359.r[1]), D(om1.r[1]), 1e-3, "R of yaw 359 vs -1", __FILE__, __LINE__);
    }
    assert_true(D(o359.r[1]) < 4.0);
}

/* Off (start_rate 0), the motion adaptation's other settings change nothing, and a calibration with
 * noise_time 0 beside the filter leaves it alone: the paper's filter bit for bit. */
static void test_off_is_the_paper(void **state)
{
    hkf_settings_t a = hkf_paper_settings, b = hkf_paper_settings;
    hkf_calibration_settings_t off = hkf_default_calibration_settings;
    hkf_calibration_t c;
    hkf_filter_t fa, fb;
    hkf_output_t oa, ob;
    int i;
    (void)state;
    b.still_wander = R(3);
    b.stop_rate = R(0.1);
    off.noise_time = 0;
    off.noise_rise = R(5);
    assert_int_equal(hkf_init(&fa, &a), HKF_OK);
    assert_int_equal(hkf_init(&fb, &b), HKF_OK);
    assert_int_equal(hkf_calibration_init(&c, &off, &fb), HKF_OK);
    for (i = 0; i < 60; ++i) {
        hkf_real_t z[3];
        set3(z, 0.5 * i, 2.0 * i, -0.3 * i);
        assert_int_equal(hkf_update(&fa, z, R(frame_s), &oa), HKF_OK);
        assert_int_equal(hkf_update(&fb, z, R(frame_s), &ob), HKF_OK);
        assert_int_equal(hkf_calibration_update(&c, &fb, z, R(frame_s)), HKF_OK);
        assert_memory_equal(oa.angle, ob.angle, sizeof oa.angle);
        assert_memory_equal(oa.variance, ob.variance, sizeof oa.variance);
    }
}

/* hkf_set_noise: R at the curve's center is n, Eq. 8's shape around it; NULL is Eq. 8's own R again; a
 * bad n is refused and changes nothing; hkf_reset keeps n. */
static void test_set_noise(void **state)
{
    hkf_settings_t s = hkf_paper_settings;
    hkf_filter_t f, before;
    hkf_output_t out;
    hkf_real_t z[3], n[3], bad[3];
    int a;
    (void)state;
    s.loop_closure = HKF_LOOP_CLOSURE_OFF;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    set3(n, 0.5, 0.25, 2.0);
    assert_int_equal(hkf_set_noise(&f, n), HKF_OK);
    set3(z, D(hkf_paper_settings.noise[0].mu), D(hkf_paper_settings.noise[1].mu), D(hkf_paper_settings.noise[2].mu));
    assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK); /* the track's start */
    assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK);
    assert_near_at(D(out.r[0]), 0.5, 2e-3, "R at mu, pitch", __FILE__, __LINE__);
    assert_near_at(D(out.r[1]), 0.25, 2e-3, "R at mu, yaw", __FILE__, __LINE__);
    assert_near_at(D(out.r[2]), 2.0, 2e-3, "R at mu, roll", __FILE__, __LINE__);
    set3(z, 0, 60, 0); /* yaw far out: Eq. 8's rise, scaled by n / e(mu) */
    assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK);
    assert_near_at(D(out.r[1]), 0.25 * D(hkf_observation_noise(&f, 1, R(60))) /
                                    D(hkf_observation_noise(&f, 1, hkf_paper_settings.noise[1].mu)),
                   2e-3, "R far out, yaw", __FILE__, __LINE__);
    hkf_reset(&f);
    assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK);
    assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK);
    assert_true(D(out.r[1]) < 0.5 * D(hkf_observation_noise(&f, 1, R(60)))); /* kept */
    before = f;
    for (a = 0; a < 3; ++a) { /* each axis alone bad, the others good */
        set3(bad, 0.5, 0.25, 2.0);
        bad[a] = 0;
        assert_int_equal(hkf_set_noise(&f, bad), HKF_ERROR_NOISE_RANGE);
        bad[a] = R(-0.5);
        assert_int_equal(hkf_set_noise(&f, bad), HKF_ERROR_NOISE_RANGE);
#if TEST_HAS_NON_FINITE
        bad[a] = NAN;
        assert_int_equal(hkf_set_noise(&f, bad), HKF_ERROR_NON_FINITE);
        bad[a] = INFINITY;
        assert_int_equal(hkf_set_noise(&f, bad), HKF_ERROR_NON_FINITE);
#endif
    }
    assert_memory_equal(&f, &before, sizeof f);
    assert_int_equal(hkf_set_noise(NULL, n), HKF_ERROR_NULL_ARGUMENT);

    assert_int_equal(hkf_set_noise(&f, NULL), HKF_OK);
    assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK);
    assert_near_at(D(out.r[1]), D(hkf_observation_noise(&f, 1, R(60))), 1e-3, "Eq. 8's own R", __FILE__, __LINE__);
}

/* The estimate's history: a frame without a measurement breaks the second difference (n holds for the
 * next two measurements, however far they jump); hkf_calibration_reset starts n again at e(mu). */
static void test_history_and_reset(void **state)
{
    const hkf_settings_t s = calibrated_settings();
    calibrated_t t;
    hkf_output_t out;
    hkf_real_t z[3], held[3], now[3], start[3];
    int i;
    (void)state;
    calibrated_init(&t, &s);
    assert_int_equal(hkf_calibration_get_noise(&t.c, start), HKF_OK);
    assert_true(D(start[1]) > 1.0); /* e(mu): the constant R of the settings, 3.53 */
    for (i = 0; i < 90; ++i) {
        set3(z, 0, 0.1 * ((i * 7) % 5 - 2), 0);
        calibrated_update(&t, z, R(frame_s), &out);
    }
    assert_int_equal(hkf_calibration_get_noise(&t.c, held), HKF_OK);
    assert_true(D(held[1]) < 0.1 * D(start[1])); /* it fell to this noise */
    assert_int_equal(hkf_predict(&t.f, R(frame_s), &out), HKF_OK);
    assert_int_equal(hkf_calibration_update(&t.c, &t.f, NULL, R(frame_s)), HKF_OK);
    for (i = 0; i < 2; ++i) { /* two measurements rebuild the history: no second difference yet */
        set3(z, 0, 20.0 * (i + 1), 0);
        calibrated_update(&t, z, R(frame_s), &out);
        assert_int_equal(hkf_calibration_get_noise(&t.c, now), HKF_OK);
        assert_memory_equal(now, held, sizeof now);
    }
    set3(z, 0, 90, 0); /* the third: a second difference of 30 deg */
    calibrated_update(&t, z, R(frame_s), &out);
    assert_int_equal(hkf_calibration_get_noise(&t.c, now), HKF_OK);
    assert_true(D(now[1]) > D(held[1]));
    hkf_reset(&t.f);
    assert_int_equal(hkf_calibration_reset(&t.c, &t.f), HKF_OK);
    assert_int_equal(hkf_calibration_get_noise(&t.c, now), HKF_OK);
    assert_memory_equal(now, start, sizeof now);
    assert_int_equal(hkf_calibration_update(NULL, &t.f, z, R(frame_s)), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_calibration_get_noise(&t.c, NULL), HKF_ERROR_NULL_ARGUMENT);
    {
        hkf_calibration_state_t st;
        assert_int_equal(hkf_calibration_get_state(NULL, &st), HKF_ERROR_NULL_ARGUMENT);
        assert_int_equal(hkf_calibration_get_state(&t.c, NULL), HKF_ERROR_NULL_ARGUMENT);
        assert_int_equal(hkf_calibration_get_state(&t.c, &st), HKF_OK);
        assert_true(st.noise[0] == now[0] && st.noise[2] == now[2] && D(st.power[1]) >= 0.0);
    }
}

/* Yaw's frame-to-frame step is taken the short way round: a still head at the +-180 seam (its measurements
 * cross it) reads the same noise as one facing the camera, whether they are given past 180 (179.8 ..
 * 180.2) or wrapped, as an estimator publishes them (179.8 .. 180 and -180 .. -179.8). */
static void test_noise_at_the_yaw_seam(void **state)
{
    const hkf_settings_t s = calibrated_settings();
    calibrated_t seam, wrapped, front;
    hkf_output_t out;
    hkf_real_t z[3], n_seam[3], n_wrapped[3], n_front[3];
    sim_rng_t rng;
    int i;
    (void)state;
    calibrated_init(&seam, &s);
    calibrated_init(&wrapped, &s);
    calibrated_init(&front, &s);
    sim_rng_seed(&rng, 8u);
    for (i = 0; i < 300; ++i) {
        const double noise = 0.2 * sim_rng_gaussian(&rng);
        set3(z, 0, 180.0 + noise, 0);
        calibrated_update(&seam, z, R(frame_s), &out);
        set3(z, 0, noise > 0 ? noise - 180.0 : 180.0 + noise, 0);
        calibrated_update(&wrapped, z, R(frame_s), &out);
        set3(z, 0, noise, 0);
        calibrated_update(&front, z, R(frame_s), &out);
    }
    assert_int_equal(hkf_calibration_get_noise(&seam.c, n_seam), HKF_OK);
    assert_int_equal(hkf_calibration_get_noise(&wrapped.c, n_wrapped), HKF_OK);
    assert_int_equal(hkf_calibration_get_noise(&front.c, n_front), HKF_OK);
    print_message("yaw noise at the seam %.4f (wrapped %.4f), facing the camera %.4f deg^2\n", D(n_seam[1]),
                  D(n_wrapped[1]), D(n_front[1]));
    assert_near_at(D(n_seam[1]), D(n_front[1]), 0.2 * D(n_front[1]) + 1e-3, "n at the seam", __FILE__, __LINE__);
    assert_near_at(D(n_wrapped[1]), D(n_front[1]), 0.2 * D(n_front[1]) + 1e-3, "n at the seam, wrapped", __FILE__,
                   __LINE__);
}

/* Out-of-range calibration and motion settings are refused by name. */
static void test_calibration_settings_checked(void **state)
{
    hkf_filter_t f;
    hkf_settings_t s;
    hkf_calibration_settings_t c = hkf_default_calibration_settings;
    hkf_calibration_t cal;
    (void)state;
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    c.noise_time = R(-1);
    assert_int_equal(hkf_calibration_init(&cal, &c, &f), HKF_ERROR_SETTING_CALIBRATION);
    c = hkf_default_calibration_settings;
    c.noise_rise = R(200);
    assert_int_equal(hkf_calibration_init(&cal, &c, &f), HKF_ERROR_SETTING_CALIBRATION);
#if TEST_HAS_NON_FINITE
    c = hkf_default_calibration_settings;
    c.noise_time = R(NAN);
    assert_int_equal(hkf_calibration_init(&cal, &c, &f), HKF_ERROR_SETTING_NON_FINITE);
#endif
    assert_int_equal(hkf_calibration_init(NULL, &c, &f), HKF_ERROR_NULL_ARGUMENT);
    s = hkf_default_settings;
    s.still_wander = R(-0.5);
    assert_int_equal(hkf_init(&f, &s), HKF_ERROR_SETTING_MOTION);
    s = hkf_default_settings;
    s.start_rate = R(2 * HKF_MAX_RATE);
    assert_int_equal(hkf_init(&f, &s), HKF_ERROR_SETTING_MOTION);
    s = hkf_default_settings;
    s.stop_rate = R(-1);
    assert_int_equal(hkf_init(&f, &s), HKF_ERROR_SETTING_MOTION);
}

/* The power n follows is the low-pass of Eq. "power += beta (d^2 / 6 - power)" with beta = dt /
 * (dt + noise_time), step by step (hkf_calibration.h), read through hkf_calibration_get_state: a head
 * turning at a steady acceleration gives every frame the same second difference d. */
static void test_power_low_pass(void **state)
{
    calibrated_t t;
    hkf_output_t out;
    hkf_calibration_state_t before, after;
    const hkf_settings_t s = calibrated_settings();
    const double d = 0.3, dt = frame_s;
    const double beta = dt / (dt + D(hkf_default_calibration_settings.noise_time));
    int k;
    (void)state;
    calibrated_init(&t, &s);
    for (k = 0; k < 12; ++k) {
        const hkf_real_t z[3] = {R(0.5 * d * k * k), R(0.0), R(0.0)}; /* second difference d on pitch */
        assert_int_equal(hkf_calibration_get_state(&t.c, &before), HKF_OK);
        calibrated_update(&t, z, R(dt), &out);
        assert_int_equal(hkf_calibration_get_state(&t.c, &after), HKF_OK);
        if (k >= 2) { /* three measurements in a row: a second difference */
            const double expected = D(before.power[0]) + beta * (d * d / 6.0 - D(before.power[0]));
            assert_near_at(D(after.power[0]), expected, 4 * TEST_TOL + 1e-4 * fabs(expected), "power's low-pass",
                           __FILE__, __LINE__);
        }
    }
    assert_true(D(after.power[0]) < 0.5 * D(hkf_observation_noise(&t.f, 0, R(0.0)))); /* it came down toward d^2 / 6 */
}

/* How fast n may rise (hkf_calibration.h): by at most the factor 1 + noise_rise dt a step, so that a
 * head's motion, whose second differences are large, does not pass for noise. A settled n, then a
 * head shaking (a second difference of 4 deg every frame for 1 s): n rises by that factor a frame and
 * no faster, while the power it follows jumps at once. Beside it, the rest's measurement
 * (test_rest.c) reads n from a rest alone. */
static void test_noise_rises_at_most_by_noise_rise(void **state)
{
    calibrated_t t;
    hkf_output_t out;
    hkf_calibration_state_t before, after;
    const hkf_settings_t s = calibrated_settings();
    const double dt = frame_s, rise = 1.0 + D(hkf_default_calibration_settings.noise_rise) * dt;
    double settled;
    int k;
    (void)state;
    calibrated_init(&t, &s);
    for (k = 0; k < 300; ++k) { /* a still head with a little alternating noise: n settles low */
        const hkf_real_t z[3] = {R(0.0), R(0.05 * ((k % 2) * 2 - 1)), R(0.0)};
        calibrated_update(&t, z, R(dt), &out);
    }
    assert_int_equal(hkf_calibration_get_state(&t.c, &before), HKF_OK);
    settled = D(before.noise[1]);
    for (k = 0; k < 30; ++k) { /* shaking: the yaw's second difference alternates +-4 deg */
        const hkf_real_t z[3] = {R(0.0), R(2.0 * ((k % 2) * 2 - 1)), R(0.0)};
        assert_int_equal(hkf_calibration_get_state(&t.c, &before), HKF_OK);
        calibrated_update(&t, z, R(dt), &out);
        assert_int_equal(hkf_calibration_get_state(&t.c, &after), HKF_OK);
        assert_true(D(after.noise[1]) <= D(before.noise[1]) * rise + 2e-4); /* no faster than noise_rise */
        assert_true(D(after.noise[1]) >= D(before.noise[1]) - 2e-4);        /* and it does rise toward the power */
    }
    print_message("n %.4f settled, %.4f after 1 s of shaking (the power %.2f): at most x%.4f a frame\n", settled,
                  D(after.noise[1]), D(after.power[1]), rise);
    assert_true(D(after.power[1]) > 100.0 * D(after.noise[1])); /* the power followed the shaking at once */
    assert_true(D(after.noise[1]) > settled);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_noise_estimate_follows_the_noise),
        cmocka_unit_test(test_jitter_share_holds_with_more_noise),
        cmocka_unit_test(test_glance_followed_without_overshoot),
        cmocka_unit_test(test_blip_gone_motion_followed),
        cmocka_unit_test(test_yaw_r_read_wrapped),
        cmocka_unit_test(test_off_is_the_paper),
        cmocka_unit_test(test_set_noise),
        cmocka_unit_test(test_history_and_reset),
        cmocka_unit_test(test_noise_at_the_yaw_seam),
        cmocka_unit_test(test_calibration_settings_checked),
        cmocka_unit_test(test_power_low_pass),
        cmocka_unit_test(test_noise_rises_at_most_by_noise_rise),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

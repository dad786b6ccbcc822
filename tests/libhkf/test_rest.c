/*
 * test_rest.c - the player's rest, measured (hkf_rest.h): the wander's rate and the frame noise from
 * synthetic rests of a known random walk and a known white noise, 2 s at 30 fps; pure white noise
 * keeps raw's onset; a move spoils a rest and the rest is measured again; the rest's centre (also at
 * the yaw seam); HOLD's wander per axis (hkf_set_wander); errors.
 */
#include "test_support.h"

#include <stdlib.h>

#include "head_motion_sim.h"
#include "hkf/hkf_rest.h"

static const double frame_s = 1.0 / 30.0;

#define HKF_TEXT_FOR_TEST(x) TEXT_OF_FOR_TEST(x)
#define TEXT_OF_FOR_TEST(x) #x

enum { SEEDS = 41, REST_FRAMES = 61 }; /* 2 s at 30 fps: 61 frames, 60 steps */

static int by_value(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double median(double *v, int count)
{
    qsort(v, (size_t)count, sizeof v[0], by_value);
    return v[count / 2];
}

static double mean_of(const double *v, int count)
{
    double sum = 0.0;
    int i;
    for (i = 0; i < count; ++i) {
        sum += v[i];
    }
    return sum / count;
}

/* One synthetic rest on every axis: a rest angle at `base` drifting as a random walk of q deg^2/s, plus
 * white noise of n deg^2; measured until hkf_rest_update says it is done (a walk that strays beyond the
 * reach spoils it, and it is measured again). The result, and the frames the last rest took. */
static int measure_rest_into(hkf_rest_t *r, const hkf_rest_settings_t *settings, double n, double q,
                             const double base[3], unsigned seed, hkf_rest_result_t *found)
{
    sim_rng_t rng;
    double level[3];
    int frame, a, first = 0;
    assert_int_equal(hkf_rest_init(r, settings), HKF_OK);
    assert_int_equal(hkf_rest_start(r), HKF_OK);
    sim_rng_seed(&rng, seed);
    memcpy(level, base, sizeof level);
    for (frame = 0; frame < 10 * REST_FRAMES; ++frame) {
        hkf_real_t z[3];
        int event;
        for (a = 0; a < 3; ++a) {
            level[a] += sqrt(q * frame_s) * sim_rng_gaussian(&rng);
            z[a] = R(level[a] + sqrt(n) * sim_rng_gaussian(&rng));
        }
        if (fabs(D(z[1])) > 180.0) {
            z[1] = R(D(z[1]) - copysign(360.0, D(z[1]))); /* yaw as an estimator gives it, in [-180, 180) */
        }
        event = hkf_rest_update(r, z, R(frame_s));
        assert_true(event == HKF_REST_MEASURING || event == HKF_REST_MEASURED || event == HKF_REST_SPOILED);
        first = event == HKF_REST_SPOILED ? frame : first;
        if (event == HKF_REST_MEASURED) {
            assert_int_equal(hkf_rest_get_result(r, found), HKF_OK);
            return frame + 1 - first;
        }
    }
    fail_msg("a rest of white noise and a small random walk was never measured");
    return 0;
}

static int measure_rest_with(const hkf_rest_settings_t *settings, double n, double q, const double base[3],
                             unsigned seed, hkf_rest_result_t *found)
{
    hkf_rest_t rest;
    return measure_rest_into(&rest, settings, n, q, base, seed, found);
}

static int measure_rest(double n, double q, const double base[3], unsigned seed, hkf_rest_result_t *found)
{
    return measure_rest_with(&hkf_default_rest_settings, n, q, base, seed, found);
}

/* The player's stillness scales the measured wander, and nothing else. */
static void test_stillness_scales_the_wander(void **state)
{
    hkf_rest_settings_t stiller = hkf_default_rest_settings;
    hkf_rest_result_t one, two;
    const double base[3] = {0.0, 0.0, 0.0};
    (void)state;
    stiller.stillness = R(2.0);
    measure_rest(0.05, 1.0, base, 21u, &one);
    measure_rest_with(&stiller, 0.05, 1.0, base, 21u, &two);
    print_message("stillness 1: w %.4f deg^2; stillness 2: %.4f\n", D(one.wander), D(two.wander));
    assert_true(D(one.wander) > 0.05);
    assert_near_at(D(two.wander), 2.0 * D(one.wander), 1e-3, "stillness 2", __FILE__, __LINE__);
    assert_true(D(two.noise[0]) == D(one.noise[0]) && D(two.center[1]) == D(one.center[1]));
}

/* The stillness turned while tracking: the held rest's wander becomes what a rest measured with it from the
 * start gives; a value the config would refuse changes nothing. */
static void test_stillness_turned_while_tracking(void **state)
{
    hkf_rest_settings_t stiller = hkf_default_rest_settings;
    hkf_rest_t rest;
    hkf_rest_result_t before, turned, from_start;
    const double base[3] = {0.0, 0.0, 0.0};
    (void)state;
    stiller.stillness = R(2.0);
    measure_rest_into(&rest, &hkf_default_rest_settings, 0.05, 1.0, base, 21u, &before);
    measure_rest_with(&stiller, 0.05, 1.0, base, 21u, &from_start);
    assert_int_equal(hkf_rest_set_stillness(&rest, R(2.0)), HKF_OK);
    assert_int_equal(hkf_rest_get_result(&rest, &turned), HKF_OK);
    assert_true(D(turned.wander) == D(from_start.wander));
    assert_true(D(turned.wander) > 1.9 * D(before.wander));
    assert_true(D(turned.noise[0]) == D(before.noise[0]) && D(turned.center[1]) == D(before.center[1]));
    assert_int_equal(hkf_rest_set_stillness(&rest, R(-0.5)), HKF_ERROR_SETTING_REST);
    assert_int_equal(hkf_rest_set_stillness(&rest, R(HKF_MAX_STILLNESS + 1.0)), HKF_ERROR_SETTING_REST);
    assert_int_equal(hkf_rest_set_stillness(NULL, R(1.0)), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_rest_get_result(&rest, &turned), HKF_OK);
    assert_true(D(turned.wander) == D(from_start.wander) && D(rest.settings.stillness) == 2.0);
    assert_int_equal(hkf_rest_set_stillness(&rest, R(0.0)), HKF_OK); /* 0: the view follows every wander */
    assert_int_equal(hkf_rest_get_result(&rest, &turned), HKF_OK);
    assert_true(D(turned.wander) == 0.0);
}

/* The goal: 2 s at 30 fps give the wander's rate q within 30 % (median over seeds), on rests of
 * a known white noise n and a known random walk q, noisier and quieter cameras alike; n too. */
static void test_drift_rate_measured(void **state)
{
    static const double cases[][2] = {{0.02, 0.5}, {0.05, 1.0}, {0.1, 0.75}, {0.3, 0.3}}; /* n deg^2, q deg^2/s */
    const double base[3] = {0.0, 0.0, 0.0};
    size_t c;
    (void)state;
    for (c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        double q[3 * SEEDS], n[3 * SEEDS], spread[3 * SEEDS];
        int s, a, frames = 0;
        for (s = 0; s < SEEDS; ++s) {
            hkf_rest_result_t found;
            frames = measure_rest(cases[c][0], cases[c][1], base, 100u + (unsigned)s, &found);
            for (a = 0; a < 3; ++a) {
                q[3 * s + a] = D(found.drift[a]);
                n[3 * s + a] = D(found.noise[a]);
                spread[3 * s + a] = D(found.spread[a]) - D(found.noise[a]);
            }
        }
        const double q_med = median(q, 3 * SEEDS), n_med = median(n, 3 * SEEDS);
        const double beyond = mean_of(spread, 3 * SEEDS), expected = cases[c][1] * (REST_FRAMES - 1) * frame_s / 6.0;
        print_message("n %.2f deg^2, q %.1f deg^2/s: measured in %d frames, median q %.3f (%.0f %%), n %.4f (%.0f %%)\n",
                      cases[c][0], cases[c][1], frames, q_med, 100.0 * q_med / cases[c][1], n_med,
                      100.0 * n_med / cases[c][0]);
        assert_true(frames == REST_FRAMES);
        assert_true(fabs(q_med / cases[c][1] - 1.0) <= 0.30);
        assert_true(fabs(n_med / cases[c][0] - 1.0) <= 0.30);
        print_message("  spread beyond n: mean %.3f deg^2, q T / 6 = %.3f\n", beyond, expected);
        if (3.0 * expected < HKF_REST_MOVED_WANDER) {
            assert_true(fabs(beyond / expected - 1.0) <= 0.20); /* an expectation: the mean over seeds */
        } else { /* rests whose largest axis spread over HKF_REST_MOVED_WANDER were refused: the rest kept less */
            assert_true(beyond < expected && beyond <= HKF_REST_MOVED_WANDER);
        }
    }
}

/* The frame at which the filtered yaw first shows 1 deg of a glance (30 deg/s from frame `start`)
 * with HOLD's wander w, after the rest, on the noise of `seed`. */
static int onset_frame(hkf_real_t wander, double n, unsigned seed, int start)
{
    hkf_filter_t f;
    hkf_output_t out;
    sim_rng_t rng;
    int k;
    const hkf_real_t noise[3] = {R(n), R(n), R(n)}; /* the level the calibration (or the rest) measures */
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    assert_int_equal(hkf_set_noise(&f, noise), HKF_OK);
    assert_int_equal(hkf_set_wander(&f, wander), HKF_OK);
    sim_rng_seed(&rng, seed);
    for (k = 0; k < start + 30; ++k) {
        const double truth = k < start ? 0.0 : 30.0 * frame_s * (k - start + 1); /* 1 deg at `start` */
        hkf_real_t z[3];
        set3(z, sqrt(n) * sim_rng_gaussian(&rng), truth + sqrt(n) * sim_rng_gaussian(&rng),
             sqrt(n) * sim_rng_gaussian(&rng));
        assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK);
        if (k >= start && D(out.angle[1]) >= 1.0) {
            return k;
        }
    }
    return k;
}

/* Pure white noise (no wander): the measured w is small (the rest's q reads about 0), and the glance
 * after it is shown at the frame it is with w = 0, raw's onset, and earlier than with the
 * constant 0.3 deg^2 of release 0.3. */
static void test_white_noise_keeps_onset(void **state)
{
    const double n = 0.05, base[3] = {0.0, 0.0, 0.0};
    double w[SEEDS], measured[SEEDS], none[SEEDS], old[SEEDS];
    int s;
    (void)state;
    for (s = 0; s < SEEDS; ++s) {
        hkf_rest_result_t found;
        measure_rest(n, 0.0, base, 200u + (unsigned)s, &found);
        w[s] = D(found.wander);
        measured[s] = onset_frame(found.wander, n, 300u + (unsigned)s, 60);
        none[s] = onset_frame(R(0), n, 300u + (unsigned)s, 60);
        old[s] = onset_frame(R(0.3), n, 300u + (unsigned)s, 60);
    }
    const double w_med = median(w, SEEDS), on_measured = median(measured, SEEDS), on_none = median(none, SEEDS),
                 on_old = median(old, SEEDS);
    print_message("white noise n %.2f: median w %.4f deg^2; onset frame (glance at 60) measured %.0f, w 0 %.0f, "
                  "w 0.3 %.0f\n", n, w_med, on_measured, on_none, on_old);
    assert_true(w_med <= 0.2 * n); /* sampling noise of 2 s; 0.03 deg^2 is the built-in still_wander */
    assert_true(on_measured <= on_none);
    assert_true(on_measured < on_old);
}

/* A rest that is a rest: a player who talks or settles during the countdown: the head sways 1.2 deg at 0.5 Hz, every frame
 * within the reach. Its spread beyond the noise (0.72 deg^2) is a head that moved: each rest is refused at its
 * end (counted as spoiled and refused, what it measured kept for the runners to say) and asked again; none is
 * taken in 10 s, so the filter keeps its built-in wander. */
static void test_swaying_head_refused(void **state)
{
    hkf_rest_t rest;
    unsigned spoiled;
    int k, refused = 0, measured;
    (void)state;
    assert_int_equal(hkf_rest_init(&rest, &hkf_default_rest_settings), HKF_OK);
    assert_int_equal(hkf_rest_start(&rest), HKF_OK);
    for (k = 0; k < 300; ++k) {
        const double sway = 1.2 * sin(2.0 * M_PI * 0.5 * k * frame_s), noise = 0.1 * ((k * 7919) % 11 - 5) / 5.0;
        hkf_real_t z[3];
        int event;
        set3(z, noise, 10.0 + sway, -noise);
        event = hkf_rest_update(&rest, z, R(frame_s));
        assert_true(event == HKF_REST_MEASURING || event == HKF_REST_SPOILED);
        refused += event == HKF_REST_SPOILED;
    }
    assert_int_equal(hkf_rest_get_progress(&rest, NULL, NULL, &spoiled, &measured), HKF_OK);
    print_message("a 1.2 deg, 0.5 Hz sway: %d rests refused in 10 s (the last: spread beyond its noise %.2f deg^2 on "
                  "yaw, drift %.2f deg^2/s)\n", refused, D(rest.last_refused.spread[1]) - D(rest.last_refused.noise[1]),
                  D(rest.last_refused.drift[1]));
    assert_true(refused >= 4 && !measured);
    assert_int_equal(rest.refused, (unsigned)refused);
    assert_int_equal(spoiled, (unsigned)refused);
}

/* A head that jiggles fast and little (3 Hz, 0.8 deg: a player who talks) spreads only 0.3 deg^2 beyond its
 * noise, under HKF_REST_MOVED_WANDER, but wanders at over HKF_REST_MOVED_DRIFT: refused by its drift. */
static void test_jiggling_head_refused_by_its_drift(void **state)
{
    hkf_rest_t rest;
    int k, refused = 0, measured;
    (void)state;
    assert_int_equal(hkf_rest_init(&rest, &hkf_default_rest_settings), HKF_OK);
    assert_int_equal(hkf_rest_start(&rest), HKF_OK);
    for (k = 0; k < 2 * REST_FRAMES; ++k) {
        hkf_real_t z[3];
        set3(z, 0.0, 0.8 * sin(2.0 * M_PI * 3.0 * k * frame_s), 0.0);
        refused += hkf_rest_update(&rest, z, R(frame_s)) == HKF_REST_SPOILED;
    }
    assert_int_equal(hkf_rest_get_progress(&rest, NULL, NULL, NULL, &measured), HKF_OK);
    print_message("a 3 Hz jiggle of 0.8 deg: %d refused; spread beyond noise %.2f deg^2, drift %.1f deg^2/s\n", refused,
                  D(rest.last_refused.spread[1]) - D(rest.last_refused.noise[1]), D(rest.last_refused.drift[1]));
    assert_true(refused >= 1 && !measured);
    assert_true(D(rest.last_refused.spread[1]) - D(rest.last_refused.noise[1]) < HKF_REST_MOVED_WANDER);
    assert_true(D(rest.last_refused.drift[1]) > HKF_REST_MOVED_DRIFT);
}

/* The frames after raw's own that the filter with HOLD's wander w shows 1 deg of a 2 deg glance (a step at
 * frame `start`), on the noise n of `seed`. */
static int frames_behind_raw(hkf_real_t wander, double n, unsigned seed, int start)
{
    hkf_filter_t f;
    hkf_output_t out;
    sim_rng_t rng;
    int k, raw = -1;
    const hkf_real_t noise[3] = {R(n), R(n), R(n)};
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    assert_int_equal(hkf_set_noise(&f, noise), HKF_OK);
    assert_int_equal(hkf_set_wander(&f, wander), HKF_OK);
    sim_rng_seed(&rng, seed);
    for (k = 0; k < start + 40; ++k) {
        hkf_real_t z[3];
        set3(z, sqrt(n) * sim_rng_gaussian(&rng), (k < start ? 0.0 : 2.0) + sqrt(n) * sim_rng_gaussian(&rng),
             sqrt(n) * sim_rng_gaussian(&rng));
        assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK);
        raw = k >= start && raw < 0 && D(z[1]) >= 1.0 ? k : raw;
        if (k >= start && D(out.angle[1]) >= 1.0) {
            return raw < 0 ? 40 : k - raw;
        }
    }
    return 40;
}

/* The wander's bound: a rest that spreads 0.4-0.5 deg^2 beyond its noise (a still head whose estimate wanders,
 * under HKF_REST_MOVED_WANDER) is taken with HOLD's wander at HKF_REST_MAX_WANDER; at that wander a 2 deg
 * glance is still shown within one frame of raw (the median over seeds), and at twice it no longer is. */
static void test_wander_bounded_where_a_glance_follows(void **state)
{
    hkf_rest_result_t found;
    const double base[3] = {0.0, 0.0, 0.0}, n = 0.05;
    double at_bound[SEEDS], at_twice[SEEDS];
    int s;
    (void)state;
    for (s = 0; s < SEEDS; ++s) {
        at_bound[s] = frames_behind_raw(R(HKF_REST_MAX_WANDER), n, 500u + (unsigned)s, 60);
        at_twice[s] = frames_behind_raw(R(2.0 * HKF_REST_MAX_WANDER), n, 500u + (unsigned)s, 60);
    }
    print_message("a 2 deg glance: median %.0f frame(s) behind raw at w %.2f deg^2, %.0f at %.2f\n",
                  median(at_bound, SEEDS), HKF_REST_MAX_WANDER, median(at_twice, SEEDS), 2.0 * HKF_REST_MAX_WANDER);
    assert_true(median(at_bound, SEEDS) <= 1.0);
    assert_true(median(at_twice, SEEDS) > 1.0);
    for (s = 0; s < SEEDS; ++s) { /* a still head with a slow sine wander of 0.9 deg on yaw: 0.4 deg^2 */
        hkf_rest_t rest;
        int k, event = HKF_REST_MEASURING;
        assert_int_equal(hkf_rest_init(&rest, &hkf_default_rest_settings), HKF_OK);
        assert_int_equal(hkf_rest_start(&rest), HKF_OK);
        for (k = 0; event != HKF_REST_MEASURED && k < 2 * REST_FRAMES; ++k) {
            hkf_real_t z[3];
            set3(z, 0.0, 0.9 * sin(2.0 * M_PI * (k + s) / 40.0) + 0.05 * ((k * 7919) % 11 - 5) / 5.0, 0.0);
            event = hkf_rest_update(&rest, z, R(frame_s));
        }
        assert_int_equal(event, HKF_REST_MEASURED);
        assert_int_equal(hkf_rest_get_result(&rest, &found), HKF_OK);
        assert_true(D(found.spread[1]) - D(found.noise[1]) > HKF_REST_MAX_WANDER);
        assert_near_at(D(found.wander), HKF_REST_MAX_WANDER, 1e-3, "the bounded wander", __FILE__, __LINE__);
    }
    (void)base;
}

/* A glance in the middle of a rest spoils it at its second frame: the rest so far is dropped, the count
 * of spoiled rests says so, and the rest is measured again from that frame: done 2 s after it, centred
 * on the new rest. A single frame beyond the reach (an outlier) is skipped and spoils nothing. */
static void test_move_spoils_the_rest(void **state)
{
    hkf_rest_t rest;
    hkf_rest_result_t found;
    hkf_real_t progress;
    unsigned spoiled;
    int measuring, measured, k, done = -1, spoiled_at = -1;
    (void)state;
    assert_int_equal(hkf_rest_init(&rest, &hkf_default_rest_settings), HKF_OK);
    assert_int_equal(hkf_rest_update(&rest, NULL, R(frame_s)), HKF_REST_IDLE); /* not asked for yet */
    assert_int_equal(hkf_rest_get_result(&rest, &found), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_rest_start(&rest), HKF_OK);
    for (k = 0; k < 200 && done < 0; ++k) {
        const double yaw = k == 12 ? 8.0 : k < 30 ? 0.0 : 10.0 + 0.1 * ((k % 3) - 1); /* an outlier; a glance at 30 */
        hkf_real_t z[3];
        int event;
        set3(z, 0.1 * ((k % 2) - 0.5), yaw, 0.0);
        event = hkf_rest_update(&rest, z, R(frame_s));
        if (event == HKF_REST_SPOILED) {
            assert_int_equal(spoiled_at, -1);
            spoiled_at = k;
        } else if (event == HKF_REST_MEASURED) {
            done = k;
        } else {
            assert_int_equal(event, HKF_REST_MEASURING);
        }
        if (k == 45) {
            assert_int_equal(hkf_rest_get_progress(&rest, &measuring, &progress, &spoiled, &measured), HKF_OK);
            assert_true(measuring && !measured);
            assert_int_equal(spoiled, 1u);
            assert_near_at(D(progress), 14 * frame_s / 2.0, 0.01, "progress", __FILE__, __LINE__);
        }
    }
    assert_int_equal(spoiled_at, 31);
    assert_int_equal(done, 31 + REST_FRAMES - 1);
    assert_int_equal(hkf_rest_get_result(&rest, &found), HKF_OK);
    assert_near_at(D(found.center[1]), 10.0, 0.05, "the new rest's centre", __FILE__, __LINE__);
    assert_int_equal(hkf_rest_get_progress(&rest, &measuring, &progress, &spoiled, &measured), HKF_OK);
    assert_true(!measuring && measured);
    assert_near_at(D(progress), 1.0, 1e-4, "progress when done", __FILE__, __LINE__);
    assert_int_equal(hkf_rest_update(&rest, NULL, R(frame_s)), HKF_REST_IDLE); /* it runs only during a rest */
}

/* A slow turn, 2.8 deg/s, every frame within the reach of the rest's mean: at the rest's end its spread
 * beyond the noise (2.6 deg^2, a move across 5.6 deg) is a move's, so the rest is spoiled, not measured. */
static void test_slow_turn_is_not_a_rest(void **state)
{
    hkf_rest_t rest;
    int k, spoiled_at = -1;
    (void)state;
    assert_int_equal(hkf_rest_init(&rest, &hkf_default_rest_settings), HKF_OK);
    assert_int_equal(hkf_rest_start(&rest), HKF_OK);
    for (k = 0; k < REST_FRAMES && spoiled_at < 0; ++k) {
        hkf_real_t z[3];
        int event;
        set3(z, 0.02 * ((k % 2) * 2 - 1), 2.8 * frame_s * k, 0.0);
        event = hkf_rest_update(&rest, z, R(frame_s));
        assert_true(event != HKF_REST_MEASURED);
        spoiled_at = event == HKF_REST_SPOILED ? k : -1;
    }
    print_message("a 2.8 deg/s turn: spoiled at frame %d\n", spoiled_at);
    assert_int_equal(spoiled_at, REST_FRAMES - 1); /* at the end: no frame was beyond the reach */
    assert_int_equal(rest.refused, 0u); /* a move across half the reach: spoiled by that rule, before the refusal's */
}

/* A rest at the yaw seam (the head turned 179.9 deg, the estimate wrapping to -180): its centre is at the
 * seam, not at 0, and its noise is the noise's, not a jump of 360. */
static void test_rest_at_the_yaw_seam(void **state)
{
    const double base[3] = {5.0, 179.9, -3.0};
    hkf_rest_result_t found;
    double yaw;
    (void)state;
    measure_rest(0.05, 0.0, base, 7u, &found);
    yaw = D(found.center[1]);
    print_message("centre %.2f %.2f %.2f, n %.4f %.4f %.4f\n", D(found.center[0]), yaw, D(found.center[2]),
                  D(found.noise[0]), D(found.noise[1]), D(found.noise[2]));
    assert_true(180.0 - fabs(yaw) < 0.3);
    assert_near_at(D(found.center[0]), 5.0, 0.3, "pitch centre", __FILE__, __LINE__);
    assert_true(D(found.noise[1]) < 0.1);
}

/* RMS frame-to-frame change of the output's yaw over a still head of white noise n plus a slow wander. */
static double still_jitter(hkf_real_t wander, unsigned seed)
{
    const hkf_real_t noise[3] = {R(0.04), R(0.04), R(0.04)};
    hkf_filter_t f;
    hkf_output_t out;
    sim_rng_t rng;
    double level = 0.0, prev = 0.0, sum = 0.0;
    int k;
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    assert_int_equal(hkf_set_noise(&f, noise), HKF_OK);
    assert_int_equal(hkf_set_wander(&f, wander), HKF_OK);
    sim_rng_seed(&rng, seed);
    for (k = 0; k < 600; ++k) {
        hkf_real_t z[3];
        level += sqrt(0.3 * frame_s) * sim_rng_gaussian(&rng);
        set3(z, 0.0, level + 0.2 * sim_rng_gaussian(&rng), 0.0);
        assert_int_equal(hkf_update(&f, z, R(frame_s), &out), HKF_OK);
        if (k > 100) {
            sum += (D(out.angle[1]) - prev) * (D(out.angle[1]) - prev);
        }
        prev = D(out.angle[1]);
    }
    return sqrt(sum / 499.0);
}

/* hkf_set_wander: checked, kept by hkf_reset, forgotten by hkf_init; HOLD takes it: a wandering rest is
 * held stiller with the wander measured on it than with none. */
static void test_set_wander(void **state)
{
    hkf_filter_t f;
    hkf_rest_result_t found;
    hkf_real_t got;
    const double base[3] = {0.0, 0.0, 0.0};
    double with, without;
    (void)state;
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    assert_int_equal(hkf_get_wander(&f, &got), HKF_OK);
    assert_near_at(D(got), D(hkf_default_settings.still_wander), 1e-6, "still_wander", __FILE__, __LINE__);
    assert_int_equal(hkf_set_wander(&f, R(0.2)), HKF_OK);
    hkf_reset(&f);
    assert_int_equal(hkf_get_wander(&f, &got), HKF_OK);
    assert_near_at(D(got), 0.2, 1e-4, "kept by hkf_reset", __FILE__, __LINE__);
    assert_int_equal(hkf_set_wander(&f, R(-0.1)), HKF_ERROR_SETTING_MOTION);
    assert_int_equal(hkf_set_wander(&f, R(HKF_MAX_VARIANCE * 2.0)), HKF_ERROR_SETTING_MOTION);
#if TEST_HAS_NON_FINITE
    assert_int_equal(hkf_set_wander(&f, R(NAN)), HKF_ERROR_NON_FINITE);
#endif
    assert_int_equal(hkf_get_wander(&f, &got), HKF_OK);
    assert_near_at(D(got), 0.2, 1e-4, "unchanged by a bad wander", __FILE__, __LINE__);
    assert_int_equal(hkf_set_wander(NULL, R(0.1)), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_get_wander(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    assert_int_equal(hkf_get_wander(&f, &got), HKF_OK);
    assert_near_at(D(got), D(hkf_default_settings.still_wander), 1e-6, "hkf_init: still_wander", __FILE__, __LINE__);
    measure_rest(0.04, 0.3, base, 11u, &found);
    with = still_jitter(found.wander, 12u);
    without = still_jitter(R(0), 12u);
    print_message("wandering rest (q 0.3 deg^2/s): w %.3f deg^2, still jitter %.4f against %.4f with w 0\n",
                  D(found.wander), with, without);
    assert_true(with < 0.8 * without);
}

/* Settings and frames outside their ranges are refused and change nothing. */
static void test_rest_errors(void **state)
{
    hkf_rest_t rest;
    hkf_rest_settings_t s = hkf_default_rest_settings;
    const hkf_real_t far[3] = {R(0), R(4000), R(0)}, fine[3] = {R(0), R(1), R(0)};
    (void)state;
    assert_int_equal(hkf_rest_init(NULL, &s), HKF_ERROR_NULL_ARGUMENT);
    s.rest_time = R(-1);
    assert_int_equal(hkf_rest_init(&rest, &s), HKF_ERROR_SETTING_REST);
    s.rest_time = R(0); /* off: no rest is asked for */
    assert_int_equal(hkf_rest_init(&rest, &s), HKF_OK);
    assert_int_equal(hkf_rest_start(&rest), HKF_OK);
    assert_int_equal(hkf_rest_update(&rest, far, R(frame_s)), HKF_REST_IDLE);
    s = hkf_default_rest_settings;
    s.rest_reach = R(-1);
    assert_int_equal(hkf_rest_init(&rest, &s), HKF_ERROR_SETTING_REST);
    s = hkf_default_rest_settings;
    s.stillness = R(HKF_MAX_STILLNESS + 1);
    assert_int_equal(hkf_rest_init(&rest, &s), HKF_ERROR_SETTING_REST);
#if TEST_HAS_NON_FINITE
    s = hkf_default_rest_settings;
    s.stillness = R(NAN);
    assert_int_equal(hkf_rest_init(&rest, &s), HKF_ERROR_SETTING_NON_FINITE);
#endif
    assert_int_equal(hkf_rest_init(&rest, &hkf_default_rest_settings), HKF_OK);
    assert_int_equal(hkf_rest_start(&rest), HKF_OK);
    assert_int_equal(hkf_rest_update(&rest, far, R(frame_s)), HKF_ERROR_ANGLE_RANGE);
    assert_int_equal(hkf_rest_update(&rest, fine, R(0)), HKF_REST_MEASURING); /* the first: dt ignored */
    assert_int_equal(hkf_rest_update(&rest, fine, R(0)), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_rest_update(&rest, fine, R(frame_s)), HKF_REST_MEASURING);
    assert_int_equal(hkf_rest_stop(&rest), HKF_OK);
    assert_int_equal(hkf_rest_update(&rest, fine, R(frame_s)), HKF_REST_IDLE);
    assert_string_equal(hkf_result_string(HKF_ERROR_SETTING_REST),
                        "rest_time is not in [0, " HKF_TEXT_FOR_TEST(HKF_MAX_TIME) "] s, rest_reach not in (0, "
                        HKF_TEXT_FOR_TEST(HKF_MAX_LC_THETA) "] deg or stillness not in [0, "
                        HKF_TEXT_FOR_TEST(HKF_MAX_STILLNESS) "]");
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_swaying_head_refused),
        cmocka_unit_test(test_jiggling_head_refused_by_its_drift),
        cmocka_unit_test(test_wander_bounded_where_a_glance_follows),
        cmocka_unit_test(test_drift_rate_measured),
        cmocka_unit_test(test_stillness_scales_the_wander),
        cmocka_unit_test(test_white_noise_keeps_onset),
        cmocka_unit_test(test_move_spoils_the_rest),
        cmocka_unit_test(test_slow_turn_is_not_a_rest),
        cmocka_unit_test(test_rest_at_the_yaw_seam),
        cmocka_unit_test(test_set_wander),
        cmocka_unit_test(test_stillness_turned_while_tracking),
        cmocka_unit_test(test_rest_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

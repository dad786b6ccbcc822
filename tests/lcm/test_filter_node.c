/*
 * test_filter_node.c - hkf-filter's message handling (filter_node.c), case by
 * case: what it publishes, what it rejects and counts.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "filter_node.h"
#include "head_motion_sim.h"

#define T0 1700000000000000LL
#define FRAME_US 33333LL

static node_config_t config;
static filter_node_t node;

static int setup(void **state)
{
    (void)state;
    node_config_defaults(&config);
    assert_int_equal(filter_node_init(&node, &config), 0);
    return 0;
}

static int64_t next_seq; /* the estimator's frame counter: +1 per measurement made */

static hkf_head_pose_measurement_t measurement(int64_t utime, int valid, double pitch, double yaw, double roll)
{
    hkf_head_pose_measurement_t m;
    memset(&m, 0, sizeof m);
    m.seq = next_seq++;
    m.utime = utime;
    m.model = "fsanet";
    m.valid = valid;
    m.pitch = (float)pitch;
    m.yaw = (float)yaw;
    m.roll = (float)roll;
    return m;
}

/* The reference's step as the node makes it: an update (z) or a prediction (z NULL), then, when it was
 * made, the calibration beside the filter. The filter's result. */
static int reference_step(hkf_filter_t *f, hkf_calibration_t *c, const hkf_real_t *z, hkf_real_t dt, hkf_output_t *out)
{
    const int result = z != NULL ? hkf_update(f, z, dt, out) : hkf_predict(f, dt, out);
    if (result == HKF_OK) {
        assert_int_equal(hkf_calibration_update(c, f, z, dt), HKF_OK);
    }
    return result;
}

/* A published pose is the reference's posterior, at the measurement's time, in the reference's state. */
static void assert_pose_is(const hkf_head_pose_t *pose, const hkf_output_t *out, int64_t utime)
{
    assert_true(pose->yaw == out->angle[1] && pose->pitch == out->angle[0] && pose->roll == out->angle[2]);
    assert_true(pose->yaw_rate == out->rate[1] && pose->variance[1] == out->variance[1] && pose->r[2] == out->r[2]);
    assert_true(pose->utime == utime);
    assert_int_equal(pose->status, out->status == HKF_STATUS_TRACKING   ? HKF_HEAD_POSE_T_TRACKING
                                   : out->status == HKF_STATUS_COASTING ? HKF_HEAD_POSE_T_COASTING
                                                                        : HKF_HEAD_POSE_T_LOST);
}

/* Valid measurements give exactly libhkf's posterior with the model's curves. */
static void test_poses_match_libhkf(void **state)
{
    sim_config_t sc = sim_default_config();
    sim_t sim;
    hkf_filter_t reference;
    hkf_calibration_t calibration; /* the node's, beside its filter */
    int known, i, published = 0, coasting = 0, lost = 0;
    const hkf_settings_t s = node_config_for_model(&config, "fsanet", &known);
    (void)state;
    assert_true(known);
    assert_int_equal(hkf_init(&reference, &s), HKF_OK);
    assert_int_equal(hkf_calibration_init(&calibration, &config.calibration, &reference), HKF_OK);
    sim_init(&sim, &sc, 11u);
    for (i = 0; i < 900; ++i) {
        sim_frame_t frame;
        hkf_head_pose_t pose;
        hkf_output_t out;
        const int64_t utime = T0 + (int64_t)llround(i * 1e6 / 30.0);
        const hkf_real_t dt = i == 0 ? 0.0f : (hkf_real_t)((utime - (T0 + (int64_t)llround((i - 1) * 1e6 / 30.0))) * 1e-6);
        hkf_head_pose_measurement_t m;
        int ref_result;
        sim_next(&sim, &frame);
        m = measurement(utime, frame.valid, frame.measured[0], frame.measured[1], frame.measured[2]);
        {
            const hkf_real_t z[3] = {m.pitch, m.yaw, m.roll};
            ref_result = reference_step(&reference, &calibration, frame.valid ? z : NULL, dt, &out);
        }
        if (filter_node_measurement(&node, &m, &pose)) {
            ++published;
            assert_int_equal(ref_result, HKF_OK);
            assert_pose_is(&pose, &out, utime); /* the reference's state, faces or not: TRACKING, COASTING, then LOST */
            if (!frame.valid) {
                assert_int_not_equal(pose.status, HKF_HEAD_POSE_T_TRACKING);
                coasting += pose.status == HKF_HEAD_POSE_T_COASTING;
                lost += pose.status == HKF_HEAD_POSE_T_LOST;
            }
            assert_true(pose.seq == published);
            assert_false(pose.extrapolated);
        } else {
            assert_int_not_equal(ref_result, HKF_OK); /* only before the first face */
        }
    }
    assert_int_equal(node.counts.received, 900);
    assert_int_equal(node.counts.published, (unsigned long)published);
    assert_true(node.counts.without_face > 0);
    assert_true(coasting > 0 && lost > 0); /* the drive's face-less bursts reach both states */
}

/* No face: coast, and before the first face publish nothing. */
static void test_without_face(void **state)
{
    hkf_head_pose_measurement_t m = measurement(T0, 0, 0, 0, 0);
    hkf_head_pose_t pose;
    int i;
    (void)state;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 0);
    m = measurement(T0 + FRAME_US, 1, 1, 2, 3);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    for (i = 2; i < 20; ++i) {
        m = measurement(T0 + i * FRAME_US, 0, 0, 0, 0);
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        if (i <= 8) { /* (i - 1) frames = at most 0.233 s without a face < coast_time 0.25 s */
            assert_int_equal(pose.status, HKF_HEAD_POSE_T_COASTING);
        } else if (i >= 10) {
            assert_int_equal(pose.status, HKF_HEAD_POSE_T_LOST);
        }
        assert_true(pose.measurement_utime == T0 + FRAME_US); /* the last face's time */
    }
    assert_int_equal(pose.status, HKF_HEAD_POSE_T_LOST);
    assert_true(fabsf(pose.yaw - 2.0f) < 1e-4f);
    assert_int_equal(node.counts.without_face, 19);
}

/* Out-of-order and duplicate utimes are rejected and counted, and change nothing. */
static void test_out_of_order_and_duplicates(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose, expected;
    filter_node_t copy;
    (void)state;
    m = measurement(T0, 1, 0, 10, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    m = measurement(T0 + FRAME_US, 1, 0, 11, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    copy = node;
    m = measurement(T0 + FRAME_US, 1, 0, 50, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 0);
    m = measurement(T0, 1, 0, 50, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 0);
    assert_int_equal(node.counts.duplicates, 1);
    assert_int_equal(node.counts.out_of_order, 1);
    m = measurement(T0 + 2 * FRAME_US, 1, 0, 12, 0);
    assert_int_equal(filter_node_measurement(&copy, &m, &expected), 1);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.yaw == expected.yaw && pose.yaw_rate == expected.yaw_rate);
}

/* Non-finite or absurd angles are rejected; no NaN is ever published. */
static void test_bad_values_never_published(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    (void)state;
    m = measurement(T0, 1, 0, 10, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    m = measurement(T0 + FRAME_US, 1, NAN, 10, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 0);
    m = measurement(T0 + 2 * FRAME_US, 1, 0, INFINITY, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 0);
    m = measurement(T0 + 3 * FRAME_US, 1, 0, 0, 1e9);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 0);
    assert_int_equal(node.counts.bad_values, 3);
    m = measurement(T0 + 4 * FRAME_US, 1, 0, 11, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(isfinite(pose.yaw) && isfinite(pose.pitch) && isfinite(pose.roll) && isfinite(pose.variance[0]));
    /* a NaN in a frame without a face is harmless: the angles are not read */
    m = measurement(T0 + 5 * FRAME_US, 0, NAN, NAN, NAN);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(isfinite(pose.yaw));
}

/* A gap longer than max_dt restarts the track from the new measurement. */
static void test_gap_restarts_track(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    (void)state;
    m = measurement(T0, 1, 0, 10, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    m = measurement(T0 + 5000000, 1, 3, -40, 1);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_int_equal(node.counts.restarts, 1);
    assert_true(pose.yaw == -40.0f && pose.yaw_rate == 0.0f);
    /* a gap of exactly max_dt (1 s) is a step like any other; a frame more is a gap */
    m = measurement(T0 + 6000000, 1, 3, -38, 1);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_int_equal(node.counts.restarts, 1);
    assert_true(pose.yaw > -40.0f && pose.yaw < -38.0f);
    m = measurement(T0 + 7033333, 1, 3, -20, 1);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_int_equal(node.counts.restarts, 2);
    assert_true(pose.yaw == -20.0f);
    /* a frame without a face after a gap: no pose (no track), the restart counted; the next face starts one */
    m = measurement(T0 + 9000000, 0, 0, 0, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 0);
    assert_int_equal(node.counts.restarts, 3);
    m = measurement(T0 + 9033333, 1, 1, 5, 1);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_int_equal(node.counts.restarts, 3);
    assert_true(pose.yaw == 5.0f && pose.status == HKF_HEAD_POSE_T_TRACKING);
}

/* The measurement's model picks its curves; unknown models use the base ones. */
static void test_model_table(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    hkf_filter_t probe;
    int known;
    hkf_settings_t hopenet;
    (void)state;
    m = measurement(T0, 1, 0, 30, 0);
    m.model = "hopenet";
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    m = measurement(T0 + FRAME_US, 1, 0, 30, 0);
    m.model = "hopenet";
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    hopenet = node_config_for_model(&config, "hopenet", &known);
    assert_true(known);
    assert_int_equal(hkf_init(&probe, &hopenet), HKF_OK);
    assert_true(fabsf(pose.r[1] - hkf_observation_noise(&probe, HKF_AXIS_YAW, 30.0f)) < 1e-5f);
    /* Hopenet's yaw curve at 30 deg: 10.74 - 7.017 exp(-(35.57^2) / (2 48.28^2)) */
    assert_true(fabsf(pose.r[1] - (10.74f - 7.017f * expf(-35.57f * 35.57f / (2.0f * 48.28f * 48.28f)))) < 1e-3f);
    assert_int_equal(node.counts.unknown_models, 0);

    m = measurement(T0 + 2 * FRAME_US, 1, 0, 30, 0);
    m.model = "mystery-net";
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_int_equal(node.counts.unknown_models, 1);
    assert_int_equal(node.counts.restarts, 1);
    assert_true(fabsf(pose.r[1] - 7.64f + 4.11f * expf(-30.35f * 30.35f / (2.0f * 30.87f * 30.87f))) < 1e-3f);
}

static void test_commands(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    hkf_tracker_command_t command;
    hkf_real_t centre[3];
    int i;
    (void)state;
    for (i = 0; i < 10; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 0, 20 + i, 0);
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(pose.center[1] == 20.0f); /* the published centre: the first measurement */
    }
    command.utime = 0;
    command.command = HKF_TRACKER_COMMAND_T_RECENTER;
    assert_int_equal(filter_node_command(&node, &command), 0);
    assert_int_equal(hkf_get_center(&node.filter, centre), HKF_OK);
    assert_true(centre[1] == pose.yaw);
    {
        const float recentred_yaw = pose.yaw;
        m = measurement(T0 + 10 * FRAME_US - FRAME_US / 2, 1, 0, 29, 0);
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(pose.center[1] == recentred_yaw); /* and the one RECENTER set */
    }
    command.command = HKF_TRACKER_COMMAND_T_RESET;
    assert_int_equal(filter_node_command(&node, &command), 0);
    assert_int_equal(hkf_get_center(&node.filter, centre), HKF_ERROR_NOT_INITIALIZED);
    m = measurement(T0 + 10 * FRAME_US, 1, 5, -5, 5);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.yaw == -5.0f && pose.yaw_rate == 0.0f);
    command.command = 99;
    assert_int_equal(filter_node_command(&node, &command), -1);
    assert_int_equal(node.counts.commands, 2);
}

/* Extrapolated poses between measurements: rate times the time ahead. */
static void test_extrapolation(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose, ahead;
    int i;
    (void)state;
    assert_int_equal(filter_node_extrapolate(&node, T0, &ahead), 0); /* nothing yet */
    for (i = 0; i < 30; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 0, 40.0 * i * FRAME_US * 1e-6, 0);
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    }
    assert_int_equal(filter_node_extrapolate(&node, m.utime + 10000, &ahead), 1);
    assert_true(ahead.extrapolated);
    assert_true(ahead.utime == m.utime + 10000 && ahead.measurement_utime == m.utime);
    assert_true(fabsf(ahead.yaw - (pose.yaw + pose.yaw_rate * 0.01f)) < 1e-4f);
    assert_true(ahead.seq == pose.seq + 1);
    assert_int_equal(filter_node_extrapolate(&node, m.utime - 1, &ahead), 0); /* not into the past */
    /* nor further than coast_time (0.25 s) past the last message */
    assert_int_equal(filter_node_extrapolate(&node, m.utime + 240000, &ahead), 1);
    assert_int_equal(filter_node_extrapolate(&node, m.utime + 260000, &ahead), 0);
    assert_int_equal(node.counts.extrapolated, 2);
}

/* Clock rule: feed n frames from frame `first`, capture stamps shifted by
 * stamp_shift_us, arriving on time; returns how many were published. */
static int feed(int first, int n, int64_t stamp_shift_us)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    int i, published = 0;
    for (i = first; i < first + n; ++i) {
        m = measurement(T0 + i * FRAME_US + stamp_shift_us, 1, 0, 10, 0);
        if (filter_node_receive(&node, &m, T0 + i * FRAME_US, &pose)) {
            assert_true(pose.utime == m.utime && isfinite(pose.yaw)); /* never a pose at a bad stamp */
            ++published;
        }
    }
    return published;
}

/* The hostile log: 10 good stamps, one of INT64_MAX, 19 good. The bad
 * stamp is rejected; nothing freezes. */
static void test_clock_corrupt_stamp(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    (void)state;
    assert_int_equal(feed(0, 10, 0), 10);
    m = measurement(INT64_MAX, 1, 0, 10, 0);
    assert_int_equal(filter_node_receive(&node, &m, T0 + 10 * FRAME_US, &pose), 0);
    assert_int_equal(feed(11, 19, 0), 19);
    assert_int_equal(node.counts.clock_jumps, 1);
    assert_int_equal(node.counts.clock_resyncs, 0);
    assert_int_equal(node.counts.restarts, 0);
    assert_int_equal(node.counts.out_of_order, 0);
    m = measurement(INT64_MIN, 1, 0, 10, 0); /* and the other extreme */
    assert_int_equal(filter_node_receive(&node, &m, T0 + 30 * FRAME_US, &pose), 0);
    assert_int_equal(feed(31, 5, 0), 5);
    assert_int_equal(node.counts.clock_jumps, 2);
}

/* The capture clock steps back an hour and stays there: two frames are
 * rejected, the third consistent one is followed, the track restarts. */
static void test_clock_jump_backward(void **state)
{
    (void)state;
    assert_int_equal(feed(0, 10, 0), 10);
    assert_int_equal(feed(10, 20, -3600000000LL), 20 - (FILTER_NODE_RESYNC_MESSAGES - 1));
    assert_int_equal(node.counts.clock_jumps, FILTER_NODE_RESYNC_MESSAGES - 1);
    assert_int_equal(node.counts.clock_resyncs, 1);
    assert_int_equal(node.counts.restarts, 1);
    assert_true(node.last_utime == T0 + 29 * FRAME_US - 3600000000LL);
}

/* ... and forward an hour. */
static void test_clock_jump_forward(void **state)
{
    (void)state;
    assert_int_equal(feed(0, 10, 0), 10);
    assert_int_equal(feed(10, 20, 3600000000LL), 20 - (FILTER_NODE_RESYNC_MESSAGES - 1));
    assert_int_equal(node.counts.clock_jumps, FILTER_NODE_RESYNC_MESSAGES - 1);
    assert_int_equal(node.counts.clock_resyncs, 1);
    assert_int_equal(node.counts.out_of_order, 0);
}

/* A corrupt first stamp is followed once three good ones agree. */
static void test_clock_corrupt_first_stamp(void **state)
{
    hkf_head_pose_measurement_t m = measurement(INT64_MAX, 1, 0, 10, 0);
    hkf_head_pose_t pose;
    (void)state;
    assert_int_equal(filter_node_receive(&node, &m, T0 - FRAME_US, &pose), 1);
    assert_int_equal(feed(0, 20, 0), 20 - (FILTER_NODE_RESYNC_MESSAGES - 1));
    assert_int_equal(node.counts.clock_resyncs, 1);
    assert_true(node.last_utime == T0 + 19 * FRAME_US);
}

/* The wall clock steps back an hour on the tracking machine: the estimator's
 * stamps and the node's arrival times step together, so the clock rule sees
 * nothing, and every frame is older than the last one taken. Two frames are
 * rejected as out of order, the third consistent one is followed (the stale
 * rule), and the silence rule runs on the new arrival clock. (Before the
 * stale rule: 0 poses after the step, and no LOST either.) */
static void test_clock_steps_back_with_arrival(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    const int64_t back = 3600000000LL;
    const int64_t coast_us = (int64_t)(1e6 * (double)config.settings.coast_time);
    int i, published = 0;
    (void)state;
    assert_int_equal(feed(0, 10, 0), 10);
    for (i = 10; i < 30; ++i) {
        m = measurement(T0 + i * FRAME_US - back, 1, 0, 10, 0);
        if (filter_node_receive(&node, &m, T0 + i * FRAME_US - back, &pose)) {
            assert_true(pose.utime == m.utime && pose.status == HKF_HEAD_POSE_T_TRACKING);
            ++published;
        }
    }
    assert_int_equal(published, 20 - (FILTER_NODE_RESYNC_MESSAGES - 1));
    assert_int_equal(node.counts.out_of_order, FILTER_NODE_RESYNC_MESSAGES - 1);
    assert_int_equal(node.counts.clock_resyncs, 1);
    assert_int_equal(node.counts.restarts, 1);
    /* and an estimator that then falls silent is reported LOST coast_time later, on the new clock */
    assert_true(filter_node_silence_due(&node) == T0 + 29 * FRAME_US - back + coast_us);
    assert_int_equal(filter_node_silence(&node, T0 + 29 * FRAME_US - back + coast_us, &pose), 1);
    assert_int_equal(pose.status, HKF_HEAD_POSE_T_LOST);
}

/* A forged datagram (LCM has no authentication) with the estimator's next seq
 * and a stamp 4.9 s ahead is taken, as the clock rule allows 5 s; the real
 * frames after it are older. Repeated every 10 frames, it must never hold the
 * pose up for as long as coast_time: the longest run of frames without a
 * published pose is two (the stale rule's), and every real frame after those
 * is published. (Before: no real frame was published for 4.9 s.) */
static void test_forged_stamp_ahead(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    const int64_t coast_us = (int64_t)(1e6 * (double)config.settings.coast_time);
    int64_t last_published_arrival = 0, longest_wait = 0;
    int i, real_published = 0, forged = 0;
    (void)state;
    next_seq = 0; /* the frames' seq below is their index */
    assert_int_equal(feed(0, 10, 0), 10);
    last_published_arrival = T0 + 9 * FRAME_US;
    for (i = 10; i < 130; ++i) {
        const int64_t arrival = T0 + i * FRAME_US;
        if (i % 10 == 0) { /* the forgery, just before the real frame i: its seq, 4.9 s ahead, absurd angles */
            m = measurement(arrival + 4900000, 1, 0, 170, 0);
            m.seq = i;
            --next_seq;
            (void)filter_node_receive(&node, &m, arrival - 1000, &pose);
            ++forged;
        }
        m = measurement(arrival, 1, 0, 10, 0);
        m.seq = i;
        if (filter_node_receive(&node, &m, arrival, &pose)) {
            assert_true(pose.utime == arrival);
            ++real_published;
            if (arrival - last_published_arrival > longest_wait) {
                longest_wait = arrival - last_published_arrival;
            }
            last_published_arrival = arrival;
        }
    }
    /* per forgery: the real frame with its seq (another publisher's now), and two stale ones */
    assert_int_equal(real_published, 120 - forged * (1 + FILTER_NODE_RESYNC_MESSAGES - 1));
    assert_true(longest_wait <= (1 + FILTER_NODE_RESYNC_MESSAGES) * FRAME_US);
    assert_true(longest_wait < coast_us);
    assert_int_equal(node.counts.clock_resyncs, forged);
}

/* What is not a jump: a replay at 2x speed with a 3 s gap (capture steps twice
 * the arrival steps), and a one-frame reorder (still out of order). */
static void test_clock_not_a_jump(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    int i, published = 0;
    (void)state;
    for (i = 0; i < 40; ++i) {
        const int64_t stamp = T0 + i * FRAME_US + (i >= 20 ? 3000000 : 0);
        m = measurement(stamp, 1, 0, 10, 0);
        published += filter_node_receive(&node, &m, T0 + (stamp - T0) / 2, &pose);
    }
    assert_int_equal(published, 40);
    assert_int_equal(node.counts.clock_jumps, 0);
    m = measurement(node.last_utime - FRAME_US, 1, 0, 10, 0);
    assert_int_equal(filter_node_receive(&node, &m, T0 + 3000000, &pose), 0);
    assert_int_equal(node.counts.out_of_order, 1);
    assert_int_equal(node.counts.clock_jumps, 0);
}

/* The position: filtered from the measurements that carry one (z > 0), published with its
 * centre; a message without one leaves it alone; RECENTER sets the centre, RESET forgets it;
 * a box-based model's position moves the filter less than the mesh's (a deviation the size
 * of the measured noise: the filter is calibrated on the +-0.2 cm the positions carry). */
static void test_position_filtered(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RECENTER};
    float mesh_step, box_step;
    int i;
    (void)state;
    m = measurement(T0, 1, 0, 0, 0);
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.z == 0.0f && pose.position_center[2] == 0.0f); /* no position measured yet */
    for (i = 1; i <= 30; ++i) {
        const float noise = i % 2 ? 0.2f : -0.2f;
        m = measurement(T0 + i * FRAME_US, 1, 0, 0, 0);
        m.model = "mesh_pnp";
        m.x = 2.0f + 0.1f * noise, m.y = -1.0f, m.z = 60.0f + noise;
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    }
    assert_true(fabsf(pose.z - 60.0f) < 0.1f && fabsf(pose.x - 2.0f) < 0.05f);
    assert_true(fabsf(pose.position_center[2] - 60.2f) < 1e-4f); /* the first measurement */
    assert_true(pose.position_variance[2] > 0.0f && pose.position_variance[2] < 0.05f);
    {
        const float held = pose.z;
        m = measurement(T0 + 31 * FRAME_US, 1, 0, 0, 0); /* no position: held */
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(fabsf(pose.z - held) < 0.05f);
    }
    {
        filter_node_t mesh = node, box = node;
        const float before = pose.z;
        m = measurement(T0 + 32 * FRAME_US, 1, 0, 0, 0);
        m.model = "mesh_pnp";
        m.z = before + 0.4f, m.x = 2.0f, m.y = -1.0f;
        assert_int_equal(filter_node_measurement(&mesh, &m, &pose), 1);
        mesh_step = pose.z - before;
        m.model = "whenet"; /* a model change restarts the angles' track, not the position's */
        assert_int_equal(filter_node_measurement(&box, &m, &pose), 1);
        box_step = pose.z - before;
        print_message("a 0.4 cm deviation moves the position %.3f cm (mesh), %.3f cm (face box)\n", mesh_step, box_step);
        assert_true(mesh_step > 0.0f && box_step > 0.0f && box_step < 0.5f * mesh_step);
    }
    m = measurement(T0 + 32 * FRAME_US, 1, 0, 0, 0);
    m.model = "mesh_pnp";
    m.z = 50.0f, m.x = 2.0f, m.y = -1.0f;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.z < 59.0f); /* a lean of 10 cm: the motion detector follows at once */
    assert_int_equal(filter_node_command(&node, &command), 0);
    m = measurement(T0 + 33 * FRAME_US, 1, 0, 0, 0);
    m.model = "mesh_pnp";
    m.z = 50.0f, m.x = 2.0f, m.y = -1.0f;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.position_center[2] < 59.0f); /* the centre moved to where the head was */
    command.command = HKF_TRACKER_COMMAND_T_RESET;
    assert_int_equal(filter_node_command(&node, &command), 0);
    m = measurement(T0 + 34 * FRAME_US, 1, 0, 0, 0);
    m.model = "mesh_pnp";
    m.z = 40.0f, m.x = 0.0f, m.y = 0.0f;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    assert_true(pose.z == 40.0f && pose.position_center[2] == 40.0f); /* a new track, and centre */
}

/* The second model's positions: where the mesh measured none (a profile) WHENet's box position
 * of the frame stands in, moved onto the mesh's by their running difference (the box reads the
 * head 3 cm farther here): the position holds where the head is, then follows a lean; a second
 * measurement of a frame the mesh measured only teaches the offset. */
static void test_second_model_position(void **state)
{
    hkf_head_pose_measurement_t first, second;
    hkf_head_pose_t pose;
    int64_t utime = T0;
    int i;
    (void)state;
    for (i = 0; i < 90; ++i) { /* 0-29 both measure; 30-59 the mesh folds, the head still; 60-89 a lean to 50 cm */
        const float truth = i < 60 ? 60.0f : 50.0f;
        const float noise = i % 2 ? 0.2f : -0.2f;
        utime += FRAME_US;
        first = measurement(utime, i < 30, 0, i < 30 ? 5 : 70, 0);
        first.model = "mesh_pnp";
        if (i < 30) {
            first.x = 1.0f, first.y = -2.0f, first.z = truth + noise;
        }
        (void)filter_node_receive(&node, &first, utime, &pose);
        second = first;
        second.model = "whenet";
        second.valid = 1;
        second.yaw = i < 30 ? 5.0f : 70.0f;
        second.x = 1.5f, second.y = -2.0f, second.z = truth + 3.0f - noise;
        (void)filter_node_receive(&node, &second, utime + 1000, &pose);
        if (i == 29 || i == 59) {
            const int64_t at = node.position_utime;
            assert_true(filter_node_extrapolate(&node, utime + 2000, &pose) >= 0);
            print_message("frame %d: z %.2f cm (the head at %.0f cm; the last position taken at frame %lld)\n", i,
                          pose.z, truth, (long long)((at - T0) / FRAME_US - 1));
            assert_true(fabsf(pose.z - truth) < 0.5f && fabsf(pose.x - 1.0f) < 0.2f);
            assert_true(at == utime);
        }
    }
    assert_true(filter_node_extrapolate(&node, utime + 2000, &pose) >= 0);
    print_message("after the lean: z %.2f cm (the head at 50 cm)\n", pose.z);
    assert_true(fabsf(pose.z - 50.0f) < 1.0f);
}

/* A mesh frame at utime with the position (x, y, z); both models' measurements of it go to the node
 * (the second's position `box_offset` cm farther in z), unless mesh_position is 0 (the mesh folds). */
static void feed_two_models(int64_t utime, int64_t arrival, float x, float z, int mesh_position, float box_offset,
                            hkf_head_pose_t *pose)
{
    hkf_head_pose_measurement_t first = measurement(utime, 1, 0, 5, 0), second;
    hkf_head_pose_t ignored;
    first.model = "mesh_pnp";
    if (mesh_position) {
        first.x = x, first.y = 0.0f, first.z = z;
    }
    second = first;
    second.model = "whenet";
    second.x = x, second.y = 0.0f, second.z = z + box_offset;
    (void)filter_node_receive(&node, &first, arrival, pose);
    (void)filter_node_receive(&node, &second, arrival + 1000, &ignored);
}

/* Hardening round 3, item 1: the mesh misses a frame, the clock steps back 1 h, and the second
 * model's measurement of the missed frame arrives after the node has followed the new clock.
 * Before, the position track took that old (1 h later) stamp and then froze for the hour; now
 * the resync forgets the kept frames and the position follows the head on the new clock. */
static void test_position_follows_after_clock_step_back(void **state)
{
    hkf_head_pose_measurement_t m, late;
    hkf_head_pose_t pose;
    const int64_t back = 3600000000LL;
    int i;
    (void)state;
    for (i = 0; i < 20; ++i) {
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 60.0f, 1, 2.0f, &pose);
    }
    m = measurement(T0 + 20 * FRAME_US, 1, 0, 5, 0); /* frame 20: the mesh finds no position */
    m.model = "mesh_pnp";
    (void)filter_node_receive(&node, &m, m.utime, &pose);
    late = m;
    late.model = "whenet";
    late.x = 0.0f, late.y = 0.0f, late.z = 62.0f;
    for (i = 21; i < 21 + FILTER_NODE_RESYNC_MESSAGES; ++i) { /* the clock steps back 1 h: followed */
        m = measurement(T0 + i * FRAME_US - back, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = 0.0f, m.y = 0.0f, m.z = 60.0f;
        (void)filter_node_receive(&node, &m, m.utime, &pose);
    }
    assert_int_equal(node.counts.clock_resyncs, 1);
    (void)filter_node_receive(&node, &late, T0 + i * FRAME_US - back + 2000, &pose); /* frame 20's second, late */
    for (; i < 60; ++i) { /* a steady move in x: 0.5 cm a frame */
        const float x = 0.5f * (float)(i - 20);
        m = measurement(T0 + i * FRAME_US - back, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = x, m.y = 0.0f, m.z = 60.0f;
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    print_message("after the clock step: x %.2f cm (the head at %.1f cm)\n", pose.x, 0.5 * (59 - 20));
    assert_true(fabsf(pose.x - 0.5f * (59 - 20)) < 1.0f);
    assert_true(pose.x_rate > 10.0f); /* 15 cm/s */
}

/* Item 5: positions far off, once or for long, never publish a position beyond the range the
 * node accepts, nor z below FILTER_NODE_MIN_Z; one forged message is refused by the gate; bad
 * positions (NaN, inf, z < 0, beyond 1000 cm) are counted and change nothing. */
static void test_position_gated_and_bounded(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    const float bad[][3] = {{NAN, 0, 60}, {0, INFINITY, 60}, {0, 0, -4.65f}, {1001, 0, 60}, {0, 0, 0.5f}};
    int i, frame = 0;
    (void)state;
    for (i = 0; i < 30; ++i, ++frame) { /* a still head at 60 cm */
        m = measurement(T0 + frame * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = 1.0f + (i % 2 ? 0.05f : -0.05f), m.y = 0.0f, m.z = 60.0f;
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    }
    m = measurement(T0 + frame++ * FRAME_US, 1, 0, 5, 0); /* one forged message */
    m.model = "mesh_pnp";
    m.x = 1000.0f, m.y = -1000.0f, m.z = 1000.0f;
    assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
    print_message("a forged (1000, -1000, 1000): published (%.2f, %.2f, %.2f)\n", pose.x, pose.y, pose.z);
    assert_true(fabsf(pose.x - 1.0f) < 0.5f && fabsf(pose.z - 60.0f) < 0.5f);
    assert_int_equal(node.counts.positions_gated, 1);
    for (i = 0; i < (int)(sizeof bad / sizeof bad[0]); ++i, ++frame) {
        m = measurement(T0 + frame * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = bad[i][0], m.y = bad[i][1], m.z = bad[i][2];
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(fabsf(pose.x - 1.0f) < 0.5f && fabsf(pose.z - 60.0f) < 0.5f);
    }
    assert_int_equal(node.counts.bad_positions, sizeof bad / sizeof bad[0]);
    /* x -1000 cm for 10 frames, +1000 once, then frames without a position for 3 s */
    for (i = 0; i < 100; ++i, ++frame) {
        m = measurement(T0 + frame * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        if (i <= 10) {
            m.x = i < 10 ? -1000.0f : 1000.0f, m.y = 0.0f, m.z = i < 10 ? 2.0f : 1000.0f;
        }
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(isfinite(pose.x) && fabsf(pose.x) <= HKF_MAX_ABS_POSITION && fabsf(pose.y) <= HKF_MAX_ABS_POSITION);
        assert_true(pose.z >= FILTER_NODE_MIN_Z && pose.z <= HKF_MAX_ABS_POSITION);
    }
    print_message("after -1000 x 10, +1000 once, 3 s without: x %.1f cm, z %.1f cm\n", pose.x, pose.z);
    for (i = 0; i < 60; ++i, ++frame) { /* toward the camera at 60 cm/s to 2 cm, then no position: the coast stops at 1 cm */
        m = measurement(T0 + frame * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        if (i < 30) {
            m.x = 0.0f, m.y = 0.0f, m.z = 2.0f + 2.0f * (float)(29 - i);
        }
        assert_int_equal(filter_node_measurement(&node, &m, &pose), 1);
        assert_true(pose.z >= FILTER_NODE_MIN_Z && pose.z <= HKF_MAX_ABS_POSITION);
    }
    assert_true(pose.z == FILTER_NODE_MIN_Z);
}

/* Item 6: a head leaning at 15 cm/s whose positions stop while the angles go on. The position
 * coasts for the position's max_dt, then is held there with rate 0 (no jump back when the angles
 * are LOST), its variance growing; a RECENTER during the hold centres on what was published;
 * positions that resume where the head is do not jump. */
static void test_position_coast_bounded(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose, held;
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RECENTER};
    const double max_dt = (double)config.position.max_dt;
    const int64_t coast_us = (int64_t)(1e6 * (double)config.settings.coast_time);
    float last_variance = 0.0f, last_measured = 0.0f, rate;
    int i;
    (void)state;
    for (i = 0; i < 60; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        m.x = last_measured = 15.0f * (float)(i * FRAME_US * 1e-6), m.y = 0.0f, m.z = 60.0f;
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    print_message("leaning at 15 cm/s: x %.2f cm (measured %.2f), rate %.2f cm/s\n", pose.x, last_measured, pose.x_rate);
    assert_true(pose.x_rate > 5.0f);
    rate = pose.x_rate;
    for (; i < 150; ++i) { /* 3 s of angles without a position */
        const double since = (double)(i - 59) * FRAME_US * 1e-6;
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        m.model = "mesh_pnp";
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
        assert_true(pose.x <= last_measured + rate * (float)max_dt + 0.1f); /* at most max_dt of coast */
        assert_true(pose.position_variance[0] > last_variance); /* growing */
        last_variance = pose.position_variance[0];
        if (since > max_dt) {
            assert_true(pose.x_rate == 0.0f);
        }
    }
    held = pose;
    print_message("held at x %.2f cm (last measured %.2f), variance %.3f cm^2, rate %.1f\n", held.x, last_measured,
                  held.position_variance[0], held.x_rate);
    assert_int_equal(filter_node_silence(&node, m.utime + coast_us, &pose), 1); /* the angles fall silent */
    assert_int_equal(pose.status, HKF_HEAD_POSE_T_LOST);
    assert_true(pose.x == held.x); /* no jump at LOST */
    assert_int_equal(filter_node_command(&node, &command), 0);
    m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
    m.model = "mesh_pnp";
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    assert_true(fabsf(pose.x - pose.position_center[0]) < 1e-4f); /* TX 0 after RECENTER */
    ++i;
    m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0); /* positions resume where the head is held */
    m.model = "mesh_pnp";
    m.x = held.x, m.y = 0.0f, m.z = 60.0f;
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    assert_true(fabsf(pose.x - held.x) < 0.01f && fabsf(pose.x - pose.position_center[0]) < 0.01f);
}

/* Item 7: RESET forgets the second model's position offset with the rest: after it, the box
 * positions (10 cm farther than the mesh's before) are not moved by the old offset. */
static void test_reset_forgets_second_offset(void **state)
{
    hkf_head_pose_t pose;
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RESET};
    int i;
    (void)state;
    for (i = 0; i < 30; ++i) { /* both measure: the box reads 10 cm farther */
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 60.0f, 1, 10.0f, &pose);
    }
    assert_int_equal(filter_node_command(&node, &command), 0);
    for (; i < 60; ++i) { /* after RESET the mesh folds; the box alone, not yet aligned, with a new person at 70 cm */
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 70.0f, 0, 0.0f, &pose);
        assert_true(pose.z == 0.0f || fabsf(pose.z - 70.0f) < 1.0f); /* never moved 10 cm by the old offset */
    }
    for (; i < 70; ++i) { /* the mesh back: the offset learnt anew (0 cm) */
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 70.0f, 1, 0.0f, &pose);
    }
    for (; i < 80; ++i) {
        feed_two_models(T0 + i * FRAME_US, T0 + i * FRAME_US, 0.0f, 70.0f, 0, 0.0f, &pose);
        assert_true(fabsf(pose.z - 70.0f) < 1.0f);
    }
}

/* One publisher: a second estimator on the same channel (its own frame
 * counter, another face at yaw 40) is rejected and counted, never mixed in. */
static void test_two_publishers_not_mixed(void **state)
{
    hkf_head_pose_measurement_t a, b;
    hkf_head_pose_t pose;
    int i, published = 0;
    (void)state;
    for (i = 0; i < 30; ++i) {
        a = measurement(T0 + i * FRAME_US, 1, 0, 10, 0);
        a.seq = 100 + i;
        if (filter_node_receive(&node, &a, a.utime, &pose)) {
            assert_true(fabsf(pose.yaw - 10.0f) < 0.5f);
            ++published;
        }
        b = measurement(T0 + i * FRAME_US + 10000, 1, 0, 40, 0);
        b.seq = 5000 + i;
        assert_int_equal(filter_node_receive(&node, &b, b.utime, &pose), 0);
    }
    assert_int_equal(published, 30);
    assert_int_equal(node.counts.other_publisher, 30);
}

/* The rules' boundaries, each stated: a clock step of 6 s is a jump (the
 * limit is 5 s) and of 4 s is not; rejected stamps must also be in order to
 * count as a new clock (three that go backwards are not followed); a seq step
 * of exactly FILTER_NODE_MAX_SEQ_STEP continues the followed counter, one more
 * is another publisher; a message with an angle beyond HKF_MAX_ABS_ANGLE is
 * rejected before it can move the node's time reference. */
static void test_rule_boundaries(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    int i;
    (void)state;
    next_seq = 0;
    assert_int_equal(feed(0, 10, 0), 10);
    m = measurement(T0 + 10 * FRAME_US + 6000000, 1, 0, 10, 0); /* 6 s ahead of its arrival */
    assert_int_equal(filter_node_receive(&node, &m, T0 + 10 * FRAME_US, &pose), 0);
    assert_int_equal(node.counts.clock_jumps, 1);
    m = measurement(T0 + 11 * FRAME_US + 4000000, 1, 0, 10, 0); /* 4 s: a replay's pacing, not a jump */
    assert_int_equal(filter_node_receive(&node, &m, T0 + 11 * FRAME_US, &pose), 1);
    assert_int_equal(node.counts.clock_jumps, 1);
    /* three stamps an hour ahead, each older than the one before: no new clock */
    for (i = 0; i < 3; ++i) {
        m = measurement(T0 + 3600000000LL - i * FRAME_US, 1, 0, 10, 0);
        assert_int_equal(filter_node_receive(&node, &m, T0 + (12 + i) * FRAME_US + 4000000, &pose), 0);
    }
    assert_int_equal(node.counts.clock_resyncs, 0);
    /* the seq boundary */
    assert_int_equal(filter_node_init(&node, &config), 0);
    next_seq = 0;
    assert_int_equal(feed(0, 5, 0), 5);
    m = measurement(T0 + 5 * FRAME_US, 1, 0, 10, 0);
    m.seq = 4 + FILTER_NODE_MAX_SEQ_STEP;
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1); /* frames dropped: still the same one */
    m = measurement(T0 + 6 * FRAME_US, 1, 0, 10, 0);
    m.seq = 4 + 2 * FILTER_NODE_MAX_SEQ_STEP + 1;
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 0);
    assert_int_equal(node.counts.other_publisher, 1);
    /* an absurd angle does not move the time reference: the next real frame, older than it, is taken */
    assert_int_equal(filter_node_init(&node, &config), 0);
    next_seq = 0;
    assert_int_equal(feed(0, 5, 0), 5);
    m = measurement(T0 + 7 * FRAME_US, 1, 0, 4000, 0);
    assert_int_equal(filter_node_receive(&node, &m, T0 + 5 * FRAME_US, &pose), 0);
    assert_int_equal(node.counts.bad_values, 1);
    m = measurement(T0 + 6 * FRAME_US, 1, 0, 10, 0);
    assert_int_equal(filter_node_receive(&node, &m, T0 + 6 * FRAME_US, &pose), 1);
    assert_int_equal(node.counts.out_of_order, 0);
}

/* RECENTER forgets the kept frames: a second model's measurement of a frame
 * from before the command is not fused (it would redo frames on the old
 * centre) but counted. */
static void test_second_model_after_recenter(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    hkf_tracker_command_t command;
    int i;
    (void)state;
    for (i = 0; i < 5; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 0, 5, 0);
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    second = m;
    second.model = "hopenet";
    command.utime = 0;
    command.command = HKF_TRACKER_COMMAND_T_RECENTER;
    assert_int_equal(filter_node_command(&node, &command), 0);
    assert_int_equal(filter_node_receive(&node, &second, m.utime + 10000, &pose), 0);
    assert_int_equal(node.counts.paired, 0);
    assert_int_equal(node.counts.unpaired, 1);
}

/* The followed estimator restarts (its counter starts again at 0): after 1 s
 * of silence the node follows the new one; sooner, it does not. */
static void test_publisher_restart_followed(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    int i, published = 0;
    (void)state;
    for (i = 0; i < 20; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 0, 10, 0);
        m.seq = 100 + i;
        published += filter_node_receive(&node, &m, m.utime, &pose);
    }
    m = measurement(T0 + 20 * FRAME_US, 1, 0, 10, 0);
    m.seq = 0; /* restarted, but only 33 ms later: not yet */
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 0);
    for (i = 0; i < 20; ++i) {
        m = measurement(T0 + 2000000 + i * FRAME_US, 1, 0, 12, 0);
        m.seq = i;
        published += filter_node_receive(&node, &m, m.utime, &pose);
    }
    assert_int_equal(published, 40);
    assert_int_equal(node.counts.other_publisher, 1);
    assert_int_equal(node.counts.restarts, 1); /* 2 s > max_dt: a new track */
}

/* An estimator that falls silent: LOST after coast_time (angles held, rates
 * zero), stamped on the capture clock, repeated each second, never before a
 * track, and over as soon as a measurement arrives. */
static void test_silence_reported_lost(void **state)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose, last;
    const int64_t shift = 5000; /* arrival = capture + 5 ms */
    const int64_t coast_us = (int64_t)(1e6 * (double)config.settings.coast_time);
    int64_t arrival;
    int i;
    (void)state;
    assert_int_equal(filter_node_silence_due(&node), 0); /* no track: nothing to report */
    assert_int_equal(filter_node_silence(&node, T0 + 10000000, &pose), 0);
    for (i = 0; i < 30; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 2.0 + 0.1 * i, 10.0 + i, -3.0);
        assert_int_equal(filter_node_receive(&node, &m, m.utime + shift, &last), 1);
    }
    arrival = T0 + 29 * FRAME_US + shift;
    assert_true(filter_node_silence_due(&node) == arrival + coast_us);
    assert_int_equal(filter_node_silence(&node, arrival + coast_us - 1, &pose), 0); /* still coasting */
    assert_int_equal(filter_node_silence(&node, arrival + coast_us, &pose), 1);
    assert_int_equal(pose.status, HKF_HEAD_POSE_T_LOST);
    assert_true(pose.extrapolated);
    assert_true(pose.utime == m.utime + coast_us);
    assert_true(pose.measurement_utime == m.utime);
    assert_float_equal(pose.yaw, last.yaw, 0.0);
    assert_float_equal(pose.pitch, last.pitch, 0.0);
    assert_float_equal(pose.yaw_rate, 0.0, 0.0);
    assert_int_equal(filter_node_silence(&node, arrival + coast_us + 500000, &pose), 0); /* said already */
    assert_int_equal(filter_node_silence(&node, arrival + coast_us + FILTER_NODE_LOST_REPEAT_US, &pose), 1);
    assert_true(pose.utime == m.utime + coast_us + FILTER_NODE_LOST_REPEAT_US);
    assert_int_equal(node.counts.silences, 1);
    /* the estimator comes back within max_dt: filtered as usual, the silence is over */
    m = measurement(T0 + 29 * FRAME_US + 900000, 1, 2.0, 12.0, -3.0);
    assert_int_equal(filter_node_receive(&node, &m, m.utime + shift, &pose), 1);
    assert_int_equal(pose.status, HKF_HEAD_POSE_T_TRACKING);
    assert_true(filter_node_silence_due(&node) == m.utime + shift + coast_us);
    assert_int_equal(node.counts.restarts, 0);
}

/* Two models on one channel: every frame's second measurement (model
 * "hopenet", from the same simulated head with its own noise) arrives 3 frames
 * late, as from a second core; on some frames only the second model found the
 * face. Nothing is published for a second measurement, each is fused into its
 * own frame, and in the end the node's filter is where libhkf gets stepping
 * frame by frame with hkf_update_pair (z NULL where the first found no face). */
/* frames frames of the simulated drive as the first model's measurements (every tenth frame's face missed)
 * and a second model's of each (its own errors), and the reference's pair step on each, the calibration
 * beside it; the frames only the second model measured. */
static int make_pair_frames(hkf_head_pose_measurement_t *first, hkf_head_pose_measurement_t *second, int frames,
                            hkf_filter_t *reference, const hkf_model_noise_t *s2)
{
    sim_config_t sc = sim_default_config();
    sim_t sim;
    hkf_calibration_t calibration;
    int i, second_only = 0;
    assert_int_equal(hkf_calibration_init(&calibration, &config.calibration, reference), HKF_OK);
    sim_init(&sim, &sc, 5u);
    for (i = 0; i < frames; ++i) {
        sim_frame_t frame;
        const int64_t utime = T0 + i * FRAME_US;
        sim_next(&sim, &frame);
        first[i] = measurement(utime, frame.valid && i % 10 != 7, frame.measured[0], frame.measured[1], frame.measured[2]);
        second[i] = first[i];
        second[i].model = "hopenet";
        second[i].valid = 1;
        second[i].pitch = (float)(frame.truth[0] + 3.0 * sin(0.7 * i));
        second[i].yaw = (float)(frame.truth[1] - 2.0 * cos(1.3 * i));
        second[i].roll = (float)(frame.truth[2] + 2.5 * sin(2.1 * i));
        second_only += !first[i].valid;
        {
            const hkf_real_t z[3] = {first[i].pitch, first[i].yaw, first[i].roll};
            const hkf_real_t z2[3] = {second[i].pitch, second[i].yaw, second[i].roll};
            const hkf_real_t dt = (hkf_real_t)(i == 0 ? 0.0 : FRAME_US * 1e-6);
            assert_int_equal(hkf_update_pair(reference, first[i].valid ? z : NULL, z2, s2, dt, NULL), HKF_OK);
            assert_int_equal(hkf_calibration_update(&calibration, reference, first[i].valid ? z : z2, dt), HKF_OK);
        }
    }
    return second_only;
}

static void test_second_model_fused_into_its_frame(void **state)
{
    enum { FRAMES = 300, LATE = 3 };
    static hkf_head_pose_measurement_t first[FRAMES], second[FRAMES];
    hkf_filter_t reference, before;
    hkf_output_t ours, theirs;
    int known1, known2, i, a, published = 0, second_only; /* frames only the second model measured */
    const hkf_settings_t s1 = node_config_for_model(&config, "fsanet", &known1);
    const hkf_settings_t hopenet = node_config_for_model(&config, "hopenet", &known2);
    const hkf_model_noise_t s2 = hkf_model_noise_of(&hopenet);
    (void)state;
    node.second.align_frames = 0; /* the models' offset is another test's */
    config.second_alone_from_yaw = 180; /* and so is the rule for large turns: fused on every frame */
    assert_true(known1 && known2);
    assert_int_equal(hkf_init(&reference, &s1), HKF_OK);
    second_only = make_pair_frames(first, second, FRAMES, &reference, &s2);
    for (i = 0; i < FRAMES + LATE; ++i) {
        hkf_head_pose_t pose;
        if (i < FRAMES) {
            published += filter_node_receive(&node, &first[i], first[i].utime + 2000, &pose);
        }
        if (i >= LATE) {
            memcpy(&before, &node.filter, sizeof before);
            assert_int_equal(filter_node_receive(&node, &second[i - LATE], first[i - LATE].utime + 40000, &pose), 0);
            assert_true(memcmp(&before, &node.filter, sizeof before) != 0); /* taken */
        }
    }
    assert_true(second_only > 20);
    /* every frame once a track exists: from the first model's first face, or the
     * second model's of frame 0, fused when frame LATE has come */
    for (i = 0; i < FRAMES && !first[i].valid; ++i) {
    }
    assert_int_equal(published, FRAMES - (i < LATE + 1 ? i : LATE + 1));
    assert_int_equal(node.counts.paired, FRAMES);
    assert_int_equal(node.counts.unpaired, 0);
    assert_int_equal(node.counts.other_publisher, 0);
    assert_int_equal(node.counts.unknown_models, 0);
    assert_int_equal(hkf_get_output(&node.filter, &ours), HKF_OK);
    assert_int_equal(hkf_get_output(&reference, &theirs), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_float_equal(ours.angle[a], theirs.angle[a], 1e-4);
        assert_float_equal(ours.variance[a], theirs.variance[a], 1e-6);
    }
}

/* A second measurement is used once per frame, only with a face, and only
 * while its frame is kept: otherwise it is counted and changes nothing. */
static void test_second_model_late_or_repeated_not_used(void **state)
{
    hkf_head_pose_measurement_t m[40], other;
    hkf_head_pose_t pose;
    hkf_filter_t before;
    int i;
    (void)state;
    for (i = 0; i < 40; ++i) {
        m[i] = measurement(T0 + i * FRAME_US, 1, 1.0, 10.0, -2.0);
        assert_int_equal(filter_node_receive(&node, &m[i], m[i].utime + 2000, &pose), 1);
    }
    memcpy(&before, &node.filter, sizeof before);
    other = m[39 - FILTER_NODE_PAIR_FRAMES]; /* just older than the kept frames */
    other.model = "hopenet";
    other.yaw = 30.0f;
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    other = m[35];
    other.model = "hopenet";
    other.valid = 0; /* no face: nothing to add */
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    other.valid = 1;
    other.yaw = NAN;
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    assert_memory_equal(&before, &node.filter, sizeof before);
    other.yaw = 12.0f;
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    assert_true(memcmp(&before, &node.filter, sizeof before) != 0);
    memcpy(&before, &node.filter, sizeof before);
    other.yaw = 14.0f; /* the same frame's second again */
    assert_int_equal(filter_node_receive(&node, &other, T0 + 40 * FRAME_US, &pose), 0);
    assert_memory_equal(&before, &node.filter, sizeof before);
    assert_int_equal(node.counts.paired, 1);
    assert_int_equal(node.counts.unpaired, 3);
    assert_int_equal(node.counts.bad_values, 1);
    assert_int_equal(node.counts.other_publisher, 0);
    assert_int_equal(node.counts.restarts, 0);
    /* the next frame's pose carries the fused frame; the model table is not switched */
    m[0] = measurement(T0 + 40 * FRAME_US, 1, 1.0, 10.0, -2.0);
    m[0].seq = m[39].seq + 1;
    assert_int_equal(filter_node_receive(&node, &m[0], m[0].utime + 2000, &pose), 1);
    assert_string_equal(node.model, "fsanet");
}

/* A face only the second model sees (a profile the mesh gives up on): the
 * track starts from it, and the first model's empty frames coast on it. */
static void test_second_model_alone_starts_and_keeps_track(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    int i, published = 0;
    (void)state;
    for (i = 0; i < 30; ++i) {
        m = measurement(T0 + i * FRAME_US, 0, 0, 0, 0);
        published += filter_node_receive(&node, &m, m.utime + 2000, &pose);
        if (i > 0) {
            assert_int_equal(pose.status == HKF_HEAD_POSE_T_LOST, 0);
            assert_true(fabsf(pose.yaw - 70.0f) < 1.0f);
        }
        second = m;
        second.model = "hopenet";
        second.valid = 1;
        second.pitch = -5.0f;
        second.yaw = 70.0f;
        second.roll = 3.0f;
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 30000, &pose), 0);
    }
    assert_int_equal(published, 29);
    assert_int_equal(node.counts.paired, 30);
    assert_string_equal(node.model, "fsanet");
}

/* Two models that disagree by a steady offset (the second reads pitch 4 deg
 * higher, yaw 3 deg lower): the second is moved onto the first's frame, so the
 * fused track keeps to where the first model alone puts it (on average over
 * the second half; the lag differs, as fusing halves R) - without the
 * alignment it sits between the two. */
static void test_second_model_offset_aligned(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    filter_node_t alone, unaligned;
    double bias_aligned[2] = {0, 0}, bias_unaligned[2] = {0, 0};
    int i;
    (void)state;
    assert_int_equal(filter_node_init(&alone, &config), 0);
    assert_int_equal(filter_node_init(&unaligned, &config), 0);
    unaligned.second.align_frames = 0;
    for (i = 0; i < 400; ++i) {
        hkf_head_pose_t p_alone, p_unaligned;
        const double pitch = 5.0 * sin(0.05 * i), yaw = 20.0 * sin(0.03 * i), noise = 0.5 * sin(1.7 * i);
        m = measurement(T0 + i * FRAME_US, 1, pitch + noise, yaw - noise, 1.0);
        second = m;
        second.model = "hopenet";
        second.pitch = (float)(pitch + 4.0 - noise);
        second.yaw = (float)(yaw - 3.0 + noise);
        assert_int_equal(filter_node_receive(&node, &m, m.utime + 2000, &pose), 1);
        assert_int_equal(filter_node_receive(&alone, &m, m.utime + 2000, &p_alone), 1);
        assert_int_equal(filter_node_receive(&unaligned, &m, m.utime + 2000, &p_unaligned), 1);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 30000, &pose), 0);
        assert_int_equal(filter_node_receive(&unaligned, &second, m.utime + 30000, &p_unaligned), 0);
        if (i >= 200) {
            bias_aligned[0] += (pose.pitch - p_alone.pitch) / 200.0;
            bias_aligned[1] += (pose.yaw - p_alone.yaw) / 200.0;
            bias_unaligned[0] += (p_unaligned.pitch - p_alone.pitch) / 200.0;
            bias_unaligned[1] += (p_unaligned.yaw - p_alone.yaw) / 200.0;
        }
    }
    print_message("mean offset from the first model's track, pitch / yaw: aligned %.3f / %.3f deg, unaligned "
                  "%.3f / %.3f deg\n", bias_aligned[0], bias_aligned[1], bias_unaligned[0], bias_unaligned[1]);
    assert_true(fabs(bias_aligned[0]) < 0.1 && fabs(bias_aligned[1]) < 0.1);
    /* unaligned, the second model pulls the track by its weight, R1 / (R1 + R2) of its offset: in pitch it is
     * visible (0.23 deg of 4 with the defaults); in yaw hopenet's curve leaves it next to none */
    assert_true(bias_unaligned[0] > 0.15 && bias_unaligned[0] > 5.0 * fabs(bias_aligned[0]));
    assert_float_equal(node.second.offset[0], -4.0, 0.05);
    assert_float_equal(node.second.offset[1], 3.0, 0.05);
}

/* The offset is a running mean from the first frame on: after 10 frames
 * that both models measured 4 deg apart in pitch (and 3 in yaw), the node has
 * learnt 4 (and -3), not a fraction of it on its way to the window. */
static void test_second_model_offset_from_the_first_frames(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    int i;
    (void)state;
    for (i = 0; i < 10; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 2.0 + 0.3 * i, 5.0, 0.0);
        second = m;
        second.model = "hopenet";
        second.pitch = m.pitch - 4.0f;
        second.yaw = m.yaw + 3.0f;
        (void)filter_node_receive(&node, &m, m.utime + 2000, &pose);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 20000, &pose), 0);
    }
    assert_int_equal(node.second.offset_frames, 10);
    assert_float_equal(node.second.offset[0], 4.0, 1e-4);
    assert_float_equal(node.second.offset[1], -3.0, 1e-4);
    /* at a large turn (the first model's |yaw| >= 25 deg) the first is not trusted: nothing is learnt there */
    for (i = 10; i < 20; ++i) {
        m = measurement(T0 + i * FRAME_US, 1, 2.0, 40.0, 0.0);
        second = m;
        second.model = "hopenet";
        second.pitch = m.pitch - 12.0f;
        (void)filter_node_receive(&node, &m, m.utime + 2000, &pose);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 20000, &pose), 0);
    }
    assert_int_equal(node.second.offset_frames, 10);
    assert_float_equal(node.second.offset[0], 4.0, 1e-4);
}

/* Both models near the yaw seam (WHENet reports up to +-180): the head sways
 * across it and the second model reads 2 deg further right, so their
 * difference is -2 deg, whichever side of the seam each reading falls on. The
 * offset learnt is -2 (not a mean of -2 and 358), and the fused yaw stays
 * with the first model's, across the seam. */
static void test_second_model_offset_across_the_seam(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose, first_alone;
    filter_node_t alone;
    double worst = 0.0;
    int i;
    (void)state;
    config.second_alone_from_yaw = 180; /* fused at every yaw: the offset is learnt at the seam too */
    assert_int_equal(filter_node_init(&node, &config), 0);
    assert_int_equal(filter_node_init(&alone, &config), 0);
    for (i = 0; i < 120; ++i) {
        const double yaw = 179.0 + 2.0 * sin(0.2 * i); /* 177 .. 181 deg, i.e. across +-180 */
        m = measurement(T0 + i * FRAME_US, 1, 0.0, yaw >= 180.0 ? yaw - 360.0 : yaw, 0.0);
        second = m;
        second.model = "hopenet";
        second.yaw = (float)(yaw + 2.0 >= 180.0 ? yaw + 2.0 - 360.0 : yaw + 2.0);
        assert_int_equal(filter_node_receive(&node, &m, m.utime + 2000, &pose), 1);
        assert_int_equal(filter_node_receive(&alone, &m, m.utime + 2000, &first_alone), 1);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 20000, &pose), 0);
        if (i >= 20) {
            const double d = fabs(fmod(pose.yaw - first_alone.yaw + 540.0, 360.0) - 180.0);
            worst = d > worst ? d : worst;
        }
    }
    assert_float_equal(node.second.offset[1], -2.0, 1e-3);
    print_message("largest distance from the first model's track: %.3f deg\n", worst);
    /* the fused track stays with the first model's: a seam error would put it 2 deg (the offset) or a turn
     * away; what remains is the dynamics of a halved R (0.59 deg on this noise-free turn) */
    assert_true(worst < 1.0);
}

/* Where the first model measures a large turn (|yaw| >= pair_second_alone_from_yaw,
 * 25 deg), a frame the second model also measured takes the second's
 * measurement alone, with its own R; below, both are fused. The node's track
 * is libhkf's stepped that way. */
static void test_second_model_alone_at_large_yaw(void **state)
{
    hkf_head_pose_measurement_t m, second;
    hkf_head_pose_t pose;
    hkf_filter_t reference;
    hkf_calibration_t calibration;
    hkf_output_t ours, theirs;
    int known, i, a;
    const hkf_settings_t s1 = node_config_for_model(&config, "fsanet", &known);
    const hkf_settings_t hopenet = node_config_for_model(&config, "hopenet", &known);
    const hkf_model_noise_t s2 = hkf_model_noise_of(&hopenet);
    (void)state;
    node.second.align_frames = 0;
    assert_float_equal(config.second_alone_from_yaw, 25.0, 0.0);
    assert_int_equal(hkf_init(&reference, &s1), HKF_OK);
    assert_int_equal(hkf_calibration_init(&calibration, &config.calibration, &reference), HKF_OK);
    for (i = 0; i < 60; ++i) {
        const double yaw = 1.5 * i; /* 0 .. 88.5 deg: fused below 25, the second alone from there */
        const hkf_real_t z[3] = {(hkf_real_t)(2.0 + 0.3 * sin(i)), (hkf_real_t)yaw, -1.0f};
        const hkf_real_t z2[3] = {(hkf_real_t)(-1.0 + 0.4 * cos(i)), (hkf_real_t)(yaw + 4.0), 2.0f};
        m = measurement(T0 + i * FRAME_US, 1, z[0], z[1], z[2]);
        second = m;
        second.model = "hopenet";
        second.pitch = z2[0];
        second.yaw = z2[1];
        second.roll = z2[2];
        assert_int_equal(filter_node_receive(&node, &m, m.utime + 2000, &pose), 1);
        assert_int_equal(filter_node_receive(&node, &second, m.utime + 30000, &pose), 0);
        assert_int_equal(hkf_update_pair(&reference, yaw >= 25.0 ? NULL : z, z2, &s2,
                                         (hkf_real_t)(i == 0 ? 0.0 : FRAME_US * 1e-6), NULL), HKF_OK);
        assert_int_equal(hkf_calibration_update(&calibration, &reference, yaw >= 25.0 ? z2 : z,
                                                (hkf_real_t)(i == 0 ? 0.0 : FRAME_US * 1e-6)), HKF_OK);
    }
    assert_int_equal(hkf_get_output(&node.filter, &ours), HKF_OK);
    assert_int_equal(hkf_get_output(&reference, &theirs), HKF_OK);
    for (a = 0; a < 3; ++a) {
        assert_float_equal(ours.angle[a], theirs.angle[a], 1e-4);
    }
    /* the second model's pitch, not a blend: the first's (2 deg) is set aside */
    assert_true(fabs(ours.angle[0] - (-1.0)) < 1.0);
    assert_int_equal(node.counts.paired, 60);
}

/* Another estimator with another model on the channel, its counter behind and
 * its frames a little older than the followed one's (the fault catalogue's two
 * estimators on one channel: WHENet started a second after the mesh): another
 * publisher, never taken for a late second measurement - its seq and utime
 * are no frame of the followed one. */
static void test_other_model_publisher_not_a_second(void **state)
{
    hkf_head_pose_measurement_t a, b;
    hkf_head_pose_t pose;
    int i, published = 0;
    (void)state;
    for (i = 0; i < 60; ++i) {
        a = measurement(T0 + i * FRAME_US, 1, 0, 10, 0);
        a.seq = 100 + i;
        published += filter_node_receive(&node, &a, a.utime + 2000, &pose);
        if (i >= 30) {
            b = measurement(T0 + i * FRAME_US - 20000, 1, 0, 40, 0); /* captured 20 ms before a */
            b.seq = i - 30;
            b.model = "hopenet";
            assert_int_equal(filter_node_receive(&node, &b, a.utime + 30000, &pose), 0);
        }
    }
    assert_int_equal(published, 60);
    assert_int_equal(node.counts.other_publisher, 30);
    assert_int_equal(node.counts.unpaired, 0);
    assert_int_equal(node.counts.paired, 0);
    assert_true(fabsf(pose.yaw - 10.0f) < 0.5f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_poses_match_libhkf, setup),
        cmocka_unit_test_setup(test_without_face, setup),
        cmocka_unit_test_setup(test_out_of_order_and_duplicates, setup),
        cmocka_unit_test_setup(test_bad_values_never_published, setup),
        cmocka_unit_test_setup(test_gap_restarts_track, setup),
        cmocka_unit_test_setup(test_model_table, setup),
        cmocka_unit_test_setup(test_commands, setup),
        cmocka_unit_test_setup(test_extrapolation, setup),
        cmocka_unit_test_setup(test_clock_corrupt_stamp, setup),
        cmocka_unit_test_setup(test_clock_jump_backward, setup),
        cmocka_unit_test_setup(test_clock_jump_forward, setup),
        cmocka_unit_test_setup(test_clock_corrupt_first_stamp, setup),
        cmocka_unit_test_setup(test_clock_not_a_jump, setup),
        cmocka_unit_test_setup(test_clock_steps_back_with_arrival, setup),
        cmocka_unit_test_setup(test_forged_stamp_ahead, setup),
        cmocka_unit_test_setup(test_position_filtered, setup),
        cmocka_unit_test_setup(test_second_model_position, setup),
        cmocka_unit_test_setup(test_position_follows_after_clock_step_back, setup),
        cmocka_unit_test_setup(test_position_gated_and_bounded, setup),
        cmocka_unit_test_setup(test_position_coast_bounded, setup),
        cmocka_unit_test_setup(test_reset_forgets_second_offset, setup),
        cmocka_unit_test_setup(test_two_publishers_not_mixed, setup),
        cmocka_unit_test_setup(test_publisher_restart_followed, setup),
        cmocka_unit_test_setup(test_rule_boundaries, setup),
        cmocka_unit_test_setup(test_second_model_after_recenter, setup),
        cmocka_unit_test_setup(test_silence_reported_lost, setup),
        cmocka_unit_test_setup(test_second_model_fused_into_its_frame, setup),
        cmocka_unit_test_setup(test_second_model_late_or_repeated_not_used, setup),
        cmocka_unit_test_setup(test_second_model_alone_starts_and_keeps_track, setup),
        cmocka_unit_test_setup(test_second_model_offset_aligned, setup),
        cmocka_unit_test_setup(test_second_model_offset_from_the_first_frames, setup),
        cmocka_unit_test_setup(test_second_model_offset_across_the_seam, setup),
        cmocka_unit_test_setup(test_second_model_alone_at_large_yaw, setup),
        cmocka_unit_test_setup(test_other_model_publisher_not_a_second, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

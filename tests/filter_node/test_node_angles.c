/*
 * test_node_angles.c - hkf-filter's node (filter_node/filter_node.c), the angles: what the node publishes for a measurement, a frame without a face, a gap, a model, a command, between measurements and in a silence.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "node_test_support.h"

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
 * face. Each second measurement is fused into its own frame (and the posterior
 * with it published at once), and in the end the node's filter is where libhkf gets stepping
 * frame by frame with hkf_update_pair (z NULL where the first found no face). */

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
        cmocka_unit_test_setup(test_silence_reported_lost, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

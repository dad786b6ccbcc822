/*
 * test_node_rest.c - hkf-filter's node (filter_node/node_rest.c), the player's rest: asked for when
 * tracking starts, measured on the first model's frames, its wander handed to the filter and its mean
 * made the centre; a move spoils it and it is asked for again; RECENTER asks again, RESET forgets it; a
 * model change and a second model's redone frames keep it; the status beside each pose says it all.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "node_test_support.h"


/* Frame i of a head resting at (pitch, yaw, roll) whose estimate wanders slowly (a 0.6 deg, 1.3 s sine on
 * pitch) with a little frame noise; valid, taken by the node. The status that goes with its pose. */
static hkf_tracker_status_t rest_frame(int i, double pitch, double yaw, double roll)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    hkf_tracker_status_t status;
    const double wander = 0.6 * sin(2.0 * M_PI * i / 40.0), noise = 0.05 * ((i * 7919) % 11 - 5) / 5.0;
    m = measurement(T0 + i * FRAME_US, 1, pitch + wander + noise, yaw - noise, roll + noise);
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    filter_node_status(&node, &pose, &status);
    assert_true(status.utime == pose.utime && status.pose_seq == pose.seq);
    return status;
}

/* Asked for at the start: RESTING with its progress counting up, then MEASURED after 2 s; the wander
 * the filter takes is the rest's (the sine's spread beyond the noise: about 0.18 deg^2), the centre its mean. */
static void test_rest_measured_at_start(void **state)
{
    hkf_tracker_status_t status;
    hkf_real_t wander, center[3];
    int i;
    (void)state;
    status = rest_frame(0, -5.0, 10.0, 2.0);
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_RESTING);
    assert_false(status.wander_measured);
    assert_true(fabsf(status.wander - (float)config.settings.still_wander) < 1e-6f); /* the built-in, until measured */
    for (i = 1; i < 60; ++i) {
        status = rest_frame(i, -5.0, 10.0, 2.0);
        assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_RESTING);
        assert_true(fabsf(status.rest_progress - (float)(i * FRAME_US * 1e-6 / 2.0)) < 0.01f);
    }
    status = rest_frame(60, -5.0, 10.0, 2.0);
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_MEASURED);
    assert_true(status.wander_measured && status.rest_progress == 1.0f && status.rests_spoiled == 0);
    assert_int_equal(node.rest.measured_count, 1);
    assert_int_equal(hkf_get_wander(&node.filter, &wander), HKF_OK);
    assert_true(fabsf(status.wander - (float)wander) < 1e-6f);
    assert_true(wander > 0.12f && wander < 0.22f); /* a sine of amplitude 0.6: variance 0.18 */
    assert_true(status.rest_spread[0] > 0.12f && status.rest_spread[1] < 0.02f);
    assert_int_equal(hkf_get_center(&node.filter, center), HKF_OK);
    assert_true(fabsf((float)center[0] + 5.0f) < 0.2f && fabsf((float)center[1] - 10.0f) < 0.05f);
    assert_true(fabsf(status.rest_center[1] - 10.0f) < 0.05f);
    status = rest_frame(61, -5.0, 10.0, 2.0); /* measured once: no more rest measured after it */
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_MEASURED);
    assert_int_equal(node.rest.measured_count, 1);
}

/* A glance during the rest spoils it: counted, the rest asked for again from there, and measured 2 s
 * after the glance; the filter keeps the built-in wander meanwhile. */
static void test_spoiled_rest_asked_again(void **state)
{
    hkf_tracker_status_t status;
    int i;
    (void)state;
    for (i = 0; i < 30; ++i) {
        status = rest_frame(i, 0.0, 0.0, 0.0);
    }
    status = rest_frame(30, 0.0, 15.0, 0.0); /* a glance: 15 deg of yaw; its first frame could be an outlier */
    assert_int_equal(status.rests_spoiled, 0);
    status = rest_frame(31, 0.0, 15.0, 0.0); /* its second: a move */
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_RESTING);
    assert_int_equal(status.rests_spoiled, 1);
    assert_int_equal(node.rest.spoiled_count, 1);
    assert_true(status.rest_progress == 0.0f && !status.wander_measured);
    for (i = 32; i < 91; ++i) {
        status = rest_frame(i, 0.0, 15.0, 0.0);
        assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_RESTING);
    }
    status = rest_frame(91, 0.0, 15.0, 0.0);
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_MEASURED);
    assert_true(fabsf(status.rest_center[1] - 15.0f) < 0.05f);
}

/* RECENTER asks for a new rest (the last one's wander stays meanwhile); RESET forgets it and asks again. */
static void test_recenter_and_reset_ask_again(void **state)
{
    hkf_tracker_command_t command = {0, HKF_TRACKER_COMMAND_T_RECENTER};
    hkf_tracker_status_t status;
    hkf_real_t measured, wander;
    int i;
    (void)state;
    for (i = 0; i <= 60; ++i) {
        status = rest_frame(i, 0.0, 0.0, 0.0);
    }
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_MEASURED);
    assert_int_equal(hkf_get_wander(&node.filter, &measured), HKF_OK);
    assert_int_equal(filter_node_command(&node, &command), 0);
    status = rest_frame(61, 3.0, 20.0, 0.0);
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_RESTING);
    assert_true(status.wander_measured && status.wander == (float)measured);
    for (i = 62; i <= 121; ++i) {
        status = rest_frame(i, 3.0, 20.0, 0.0);
    }
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_MEASURED);
    assert_true(fabsf(status.rest_center[1] - 20.0f) < 0.05f);
    command.command = HKF_TRACKER_COMMAND_T_RESET;
    assert_int_equal(filter_node_command(&node, &command), 0);
    status = rest_frame(122, 3.0, 20.0, 0.0);
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_RESTING);
    assert_false(status.wander_measured);
    assert_int_equal(hkf_get_wander(&node.filter, &wander), HKF_OK);
    assert_true(wander == config.settings.still_wander);
}

/* The measured wander stays through a change of model (the filter set up anew) and through a second
 * model's frame redone from before the rest was measured. */
static void test_wander_kept_by_set_up_and_redo(void **state)
{
    hkf_tracker_status_t status;
    hkf_head_pose_measurement_t second, m;
    hkf_head_pose_t pose;
    hkf_real_t measured, wander;
    int i;
    (void)state;
    for (i = 0; i < 60; ++i) {
        status = rest_frame(i, 0.0, 0.0, 0.0);
    }
    const int64_t seq59 = next_seq - 1;
    second = measurement(T0 + 59 * FRAME_US, 1, 0.0, 0.5, 0.0);
    second.seq = seq59; /* frame 59's second model, arriving after frame 60 */
    second.model = "hopenet";
    status = rest_frame(60, 0.0, 0.0, 0.0);
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_MEASURED);
    assert_int_equal(hkf_get_wander(&node.filter, &measured), HKF_OK);
    assert_true(measured != config.settings.still_wander);
    assert_int_equal(filter_node_receive(&node, &second, second.utime + 40000, &pose), 0); /* frame 60's is out */
    assert_int_equal(node.counts.paired, 1);
    assert_int_equal(hkf_get_wander(&node.filter, &wander), HKF_OK);
    assert_true(wander == measured); /* frames 59 and 60 redone from a filter before the rest's end */
    m = measurement(T0 + 61 * FRAME_US, 1, 0.0, 0.0, 0.0);
    m.model = "whenet"; /* another first model: the filter is set up with its curves */
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    assert_int_equal(hkf_get_wander(&node.filter, &wander), HKF_OK);
    assert_true(wander == measured);
}

/* rest_time 0: no rest is asked for; the status says so and the built-in wander holds. */
static void test_no_rest(void **state)
{
    hkf_tracker_status_t status;
    (void)state;
    config.rest.rest_time = 0;
    assert_int_equal(filter_node_init(&node, &config), 0);
    status = rest_frame(0, 0.0, 0.0, 0.0);
    assert_int_equal(status.rest, HKF_TRACKER_STATUS_T_NO_REST);
    assert_true(status.rest_time == 0.0f && !status.wander_measured);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_rest_measured_at_start, setup_with_rest),
        cmocka_unit_test_setup(test_spoiled_rest_asked_again, setup_with_rest),
        cmocka_unit_test_setup(test_recenter_and_reset_ask_again, setup_with_rest),
        cmocka_unit_test_setup(test_wander_kept_by_set_up_and_redo, setup_with_rest),
        cmocka_unit_test_setup(test_no_rest, setup_with_rest),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

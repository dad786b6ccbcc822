/*
 * test_node_admission.c - hkf-filter's node (filter_node/filter_node.c), admission at the node (stream_admission.h behind filter_node_receive): corrupt stamps, clock jumps, forged stamps, publishers, and what each rule counts.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "node_test_support.h"

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
    assert_int_equal(feed(10, 20, -3600000000LL), 20 - (STREAM_RESYNC_MESSAGES - 1));
    assert_int_equal(node.counts.clock_jumps, STREAM_RESYNC_MESSAGES - 1);
    assert_int_equal(node.counts.clock_resyncs, 1);
    assert_int_equal(node.counts.restarts, 1);
    assert_true(node.admission.last_utime == T0 + 29 * FRAME_US - 3600000000LL);
}

/* ... and forward an hour. */
static void test_clock_jump_forward(void **state)
{
    (void)state;
    assert_int_equal(feed(0, 10, 0), 10);
    assert_int_equal(feed(10, 20, 3600000000LL), 20 - (STREAM_RESYNC_MESSAGES - 1));
    assert_int_equal(node.counts.clock_jumps, STREAM_RESYNC_MESSAGES - 1);
    assert_int_equal(node.counts.clock_resyncs, 1);
    assert_int_equal(node.counts.out_of_order, 0);
}

/* A corrupt first stamp: one at the clock's end is refused outright (stream_admission.h), so the
 * good ones are taken from the first; one the clock rule cannot judge (the first, far from the good
 * ones) is left behind once three good ones agree. */
static void test_clock_corrupt_first_stamp(void **state)
{
    hkf_head_pose_measurement_t m = measurement(INT64_MAX, 1, 0, 10, 0);
    hkf_head_pose_t pose;
    (void)state;
    assert_int_equal(filter_node_receive(&node, &m, T0 - FRAME_US, &pose), 0);
    assert_int_equal(feed(0, 20, 0), 20);
    assert_int_equal(node.counts.clock_jumps, 1);
    assert_int_equal(node.counts.clock_resyncs, 0);
    assert_int_equal(filter_node_init(&node, &config), 0);
    m = measurement(T0 + 3600000000LL, 1, 0, 10, 0); /* 1 h ahead of the good stamps */
    assert_int_equal(filter_node_receive(&node, &m, T0 + 20 * FRAME_US, &pose), 1);
    assert_int_equal(feed(21, 20, 0), 20 - (STREAM_RESYNC_MESSAGES - 1));
    assert_int_equal(node.counts.clock_resyncs, 1);
    assert_true(node.admission.last_utime == T0 + 40 * FRAME_US);
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
    m = measurement(node.admission.last_utime - FRAME_US, 1, 0, 10, 0);
    assert_int_equal(filter_node_receive(&node, &m, T0 + 3000000, &pose), 0);
    assert_int_equal(node.counts.out_of_order, 1);
    assert_int_equal(node.counts.clock_jumps, 0);
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
    assert_int_equal(published, 20 - (STREAM_RESYNC_MESSAGES - 1));
    assert_int_equal(node.counts.out_of_order, STREAM_RESYNC_MESSAGES - 1);
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
    assert_int_equal(real_published, 120 - forged * (1 + STREAM_RESYNC_MESSAGES - 1));
    assert_true(longest_wait <= (1 + STREAM_RESYNC_MESSAGES) * FRAME_US);
    assert_true(longest_wait < coast_us);
    assert_int_equal(node.counts.clock_resyncs, forged);
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

/* The rules' boundaries, each stated: a clock step of 6 s is a jump (the
 * limit is 5 s) and of 4 s is not; rejected stamps must also be in order to
 * count as a new clock (three that go backwards are not followed); a seq step
 * of exactly STREAM_MAX_SEQ_STEP continues the followed counter, one more
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
    m.seq = 4 + STREAM_MAX_SEQ_STEP;
    assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1); /* frames dropped: still the same one */
    m = measurement(T0 + 6 * FRAME_US, 1, 0, 10, 0);
    m.seq = 4 + 2 * STREAM_MAX_SEQ_STEP + 1;
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

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup(test_clock_corrupt_stamp, setup),
        cmocka_unit_test_setup(test_clock_jump_backward, setup),
        cmocka_unit_test_setup(test_clock_jump_forward, setup),
        cmocka_unit_test_setup(test_clock_corrupt_first_stamp, setup),
        cmocka_unit_test_setup(test_clock_not_a_jump, setup),
        cmocka_unit_test_setup(test_clock_steps_back_with_arrival, setup),
        cmocka_unit_test_setup(test_forged_stamp_ahead, setup),
        cmocka_unit_test_setup(test_two_publishers_not_mixed, setup),
        cmocka_unit_test_setup(test_publisher_restart_followed, setup),
        cmocka_unit_test_setup(test_rule_boundaries, setup),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

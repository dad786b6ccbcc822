/*
 * test_node_schedule.c - what hkf-filter publishes between measurements, and when
 * (filter_node/node_schedule.c): --rate ticks on the capture grid, due on the arrival clock;
 * the silence's LOST pose; and the same poses whether the schedule is asked at its wake times (live)
 * or only when the next event comes (a log).
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "node_schedule.h"

#define T0 1700000000000000LL /* capture clock */
#define A0 5000000LL          /* arrival clock: another origin */
#define FRAME_US 33333LL
#define TICK_US 10000LL

static node_config_t config;

static hkf_head_pose_measurement_t measurement(int64_t seq, int64_t utime, double yaw)
{
    hkf_head_pose_measurement_t m;
    memset(&m, 0, sizeof m);
    m.seq = seq;
    m.utime = utime;
    m.model = "fsanet";
    m.valid = 1;
    m.yaw = (float)yaw;
    return m;
}

/* Ticks come on the grid of TICK_US in capture time after the measurement, each due as much
 * arrival time after the measurement's arrival, extrapolated from it; none before it is due. */
static void test_ticks_on_the_capture_grid(void **state)
{
    filter_node_t node;
    node_schedule_t s;
    hkf_head_pose_t pose, posterior;
    hkf_head_pose_measurement_t m;
    int64_t due, t;
    int i;
    (void)state;
    assert_int_equal(filter_node_init(&node, &config), 0);
    node_schedule_init(&s, TICK_US, 1);
    assert_true(node_schedule_wake(&s, &node) == 0); /* nothing taken: nothing due */
    for (i = 0; i < 5; ++i) {
        m = measurement(1 + i, T0 + 3000 + i * FRAME_US, 2.0 * i);
        assert_int_equal(filter_node_receive(&node, &m, A0 + i * FRAME_US, &posterior), 1);
        t = (m.utime / TICK_US + 1) * TICK_US; /* the grid's first point after the measurement */
        assert_true(node_schedule_wake(&s, &node) == A0 + i * FRAME_US + (t - m.utime));
        assert_int_equal(node_schedule_next(&s, &node, A0 + i * FRAME_US + (t - m.utime) - 1, &pose, &due), 0);
        for (; t < m.utime + FRAME_US - 1000; t += TICK_US) { /* each tick before the next frame */
            assert_int_equal(node_schedule_next(&s, &node, A0 + (i + 1) * FRAME_US - 1000, &pose, &due), 1);
            assert_true(pose.utime == t && pose.extrapolated && pose.measurement_utime == m.utime);
            assert_true(due == A0 + i * FRAME_US + (t - m.utime));
            assert_true(i < 2 || pose.yaw > posterior.yaw); /* moved on by the rate of the turn */
        }
        assert_int_equal(node_schedule_next(&s, &node, A0 + (i + 1) * FRAME_US - 1000, &pose, &due), 0);
    }
}

/* Ticks stop where extrapolation does (coast_time after the last measurement); the silence's LOST
 * pose follows, once in a log, again every FILTER_NODE_LOST_REPEAT_US live. */
static void test_ticks_stop_then_lost(void **state)
{
    filter_node_t node;
    node_schedule_t once, repeat;
    hkf_head_pose_t pose;
    hkf_head_pose_measurement_t m = measurement(1, T0, 0.0);
    const int64_t coast_us = (int64_t)ceil(1e6 * (double)config.settings.coast_time);
    int64_t due;
    int ticks = 0, lost = 0;
    (void)state;
    assert_int_equal(filter_node_init(&node, &config), 0);
    node_schedule_init(&once, TICK_US, 0);
    node_schedule_init(&repeat, 0, 1); /* LOST alone */
    assert_int_equal(filter_node_receive(&node, &m, A0, &pose), 1);
    while (node_schedule_next(&once, &node, A0 + 10 * FILTER_NODE_LOST_REPEAT_US, &pose, &due)) {
        if (pose.status == HKF_HEAD_POSE_T_LOST) {
            ++lost;
            assert_true(due == A0 + coast_us && pose.utime == T0 + coast_us && pose.yaw_rate == 0.0f);
        } else {
            ++ticks;
            assert_true(pose.utime - T0 <= coast_us);
        }
    }
    assert_int_equal(ticks, (int)(coast_us / TICK_US));
    assert_int_equal(lost, 1);
    assert_true(node_schedule_wake(&once, &node) == 0); /* once in a log; no tick after extrapolation stopped */
    assert_true(node_schedule_wake(&repeat, &node) == A0 + coast_us + FILTER_NODE_LOST_REPEAT_US);
    assert_int_equal(node_schedule_next(&repeat, &node, A0 + coast_us + FILTER_NODE_LOST_REPEAT_US, &pose, &due), 1);
    assert_true(pose.status == HKF_HEAD_POSE_T_LOST && due == A0 + coast_us + FILTER_NODE_LOST_REPEAT_US);
}

/* Hardening round 4, moderate item 4: a stream stamped 0.2 s before the clock's end, then 2.5 s of
 * silence. Before, its first stamp started a track that no LOST pose could follow (none could be
 * stamped), so the last pose stayed TRACKING. Now such stamps are corrupt (the clock's end rule,
 * stream_admission.h): no pose is published for them, nothing is due, and the live loop's wake time
 * is never in the past (it spun on a stamp at the clock's end once). */
static void test_nothing_held_at_the_clock_end(void **state)
{
    filter_node_t node;
    node_schedule_t s;
    hkf_head_pose_t pose;
    int64_t due, wake;
    const int64_t now = A0 + 30 * FRAME_US + 2500000;
    int i, published = 0;
    (void)state;
    assert_int_equal(filter_node_init(&node, &config), 0);
    node_schedule_init(&s, TICK_US, 1);
    for (i = 0; i < 30; ++i) {
        const hkf_head_pose_measurement_t m = measurement(1 + i, INT64_MAX - 200000 + i * 1000, 0.0);
        published += filter_node_receive(&node, &m, A0 + i * FRAME_US, &pose);
    }
    while (published < 100 && node_schedule_next(&s, &node, now, &pose, &due)) {
        ++published;
    }
    assert_int_equal(published, 0);
    assert_int_equal(node.counts.clock_jumps, 30);
    wake = node_schedule_wake(&s, &node);
    assert_true(wake == 0 || wake > now);
    /* the latest stamp taken, then a year of LOST repeats: the next LOST could not be stamped, so none is due
     * (the live loop spun on such a due time once) */
    {
        const hkf_head_pose_measurement_t m = measurement(100, STREAM_LATEST_UTIME, 0.0);
        assert_int_equal(filter_node_receive(&node, &m, A0 + 40 * FRAME_US, &pose), 1);
        assert_true(filter_node_silence_due(&node) != 0);
        node.lost_published = (STREAM_LATEST_UTIME - INT64_MAX) / -FILTER_NODE_LOST_REPEAT_US + 1;
        assert_true(filter_node_silence_due(&node) == 0);
        assert_int_equal(filter_node_silence(&node, INT64_MAX, &pose), 0);
    }
}

typedef struct {
    int64_t utime, due;
    int status;
    float yaw;
} published_t;

enum { STREAM = 60, MOST = 4000 };

/* The arrival time of measurement i of a stream with jitter, a gap of 2 s and a late frame. */
static int64_t arrival_of(int i)
{
    return A0 + i * FRAME_US + (i % 4) * 3000 + (i >= 30 ? 2000000 : 0);
}

/* The stream through a node and a schedule: asked only as each measurement arrives (a log), or also at
 * every wake time the schedule names (the live loop). The poses published, in order. */
static int run_stream(int live, published_t *out)
{
    filter_node_t node;
    node_schedule_t s;
    hkf_head_pose_t pose;
    int64_t due, now;
    int i, n = 0;
    assert_int_equal(filter_node_init(&node, &config), 0);
    node_schedule_init(&s, TICK_US, 0);
    for (i = 0; i <= STREAM; ++i) {
        const int64_t arrival = i < STREAM ? arrival_of(i) : INT64_MAX;
        while (live && (now = node_schedule_wake(&s, &node)) != 0 && now < arrival) {
            while (node_schedule_next(&s, &node, now, &pose, &due)) {
                assert_true(due <= now && n < MOST);
                out[n++] = (published_t){pose.utime, due, pose.status, pose.yaw};
            }
        }
        while (node_schedule_next(&s, &node, arrival, &pose, &due)) {
            assert_true(n < MOST);
            out[n++] = (published_t){pose.utime, due, pose.status, pose.yaw};
        }
        if (i < STREAM) {
            const hkf_head_pose_measurement_t m = measurement(1 + i, T0 + i * FRAME_US + (i >= 30 ? 2000000 : 0), 0.5 * i);
            if (filter_node_receive(&node, &m, arrival, &pose)) {
                assert_true(n < MOST);
                out[n++] = (published_t){pose.utime, arrival, pose.status, pose.yaw};
            }
        }
    }
    return n;
}

/* Live and a log agree: the same poses, with the same stamps and due times, whether the schedule is
 * served at its wake times or only when the next measurement comes. */
static void test_live_and_log_agree(void **state)
{
    static published_t live[MOST], log[MOST];
    int n_live, n_log, i, lost = 0, backwards = 0;
    (void)state;
    n_live = run_stream(1, live);
    n_log = run_stream(0, log);
    assert_int_equal(n_live, n_log);
    assert_true(n_live > STREAM * 3);
    for (i = 0; i < n_live; ++i) {
        assert_true(live[i].utime == log[i].utime && live[i].due == log[i].due);
        assert_int_equal(live[i].status, log[i].status);
        assert_true(live[i].yaw == log[i].yaw);
        lost += live[i].status == HKF_HEAD_POSE_T_LOST;
        assert_true(i == 0 || live[i].due >= live[i - 1].due);
        backwards += i > 0 && live[i].utime < live[i - 1].utime;
    }
    print_message("%d poses, %d of them stamped earlier than the pose before\n", n_live, backwards);
    assert_int_equal(backwards, 0); /* round 4: a late frame's pose after the ticks went ahead of it */
    assert_int_equal(lost, 2); /* the 2 s gap, and the end */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ticks_on_the_capture_grid),
        cmocka_unit_test(test_ticks_stop_then_lost),
        cmocka_unit_test(test_live_and_log_agree),
        cmocka_unit_test(test_nothing_held_at_the_clock_end),
    };
    node_config_defaults(&config);
    return cmocka_run_group_tests(tests, NULL, NULL);
}

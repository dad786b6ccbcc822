/*
 * test_track_monitor.c - hkf-track's status line fed hostile datagrams through LCM (memq://), as
 * the launcher's subscriptions receive them: a model string whose length is -1 or 100 kB, cut
 * payloads, another type's bytes. Each is counted as undecodable; none crashes the launcher or
 * grows it, and the real messages around them are still counted.
 */
#define _GNU_SOURCE /* mallinfo2 */
#include <malloc.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <lcm/lcm.h>

#include "hkf_head_pose_measurement_t.h"
#include "hkf_head_pose_t.h"
#include "track_monitor.h"

enum { MODEL_LENGTH_AT = 24 }; /* hash, utime, seq: then the model string's int32 length */

static track_monitor_t monitor;
static lcm_t *lcm;

static int setup(void **state)
{
    (void)state;
    lcm = lcm_create("memq://");
    assert_non_null(lcm);
    assert_int_equal(track_monitor_start(&monitor, lcm, 1), 0);
    return 0;
}

static int teardown(void **state)
{
    (void)state;
    lcm_destroy(lcm);
    return 0;
}

/* A real measurement's bytes (the face mesh's, seq `seq`) into buffer; their size. */
static int measurement_bytes(int64_t seq, uint8_t *buffer, int size)
{
    hkf_head_pose_measurement_t m;
    memset(&m, 0, sizeof m);
    m.utime = 1700000000000000LL + (seq % 1000) * 33333; /* seqs may be near the int64 ends */
    m.seq = seq;
    m.model = "mesh_pnp";
    m.valid = 1;
    m.yaw = 12.5f;
    m.z = 60.0f;
    const int length = hkf_head_pose_measurement_t_encoded_size(&m);
    assert_true(length <= size);
    assert_int_equal(hkf_head_pose_measurement_t_encode(buffer, 0, size, &m), length);
    return length;
}

static void set_model_length(uint8_t *bytes, uint32_t length)
{
    bytes[MODEL_LENGTH_AT] = (uint8_t)(length >> 24), bytes[MODEL_LENGTH_AT + 1] = (uint8_t)(length >> 16);
    bytes[MODEL_LENGTH_AT + 2] = (uint8_t)(length >> 8), bytes[MODEL_LENGTH_AT + 3] = (uint8_t)length;
}

/* Publishes one payload on channel and lets the monitor handle it. */
static void deliver(const char *channel, const void *data, int size)
{
    assert_int_equal(lcm_publish(lcm, channel, data, (unsigned)size), 0);
    assert_true(lcm_handle_timeout(lcm, 1000) > 0);
}

/* The review's datagram: a HEAD_POSE_RAW whose model length is -1 (LCM's generated decoder then
 * read and copied past the payload: SIGSEGV). Counted; the real frames before and after counted. */
static void test_model_length_minus_one(void **state)
{
    uint8_t bytes[256];
    (void)state;
    int size = measurement_bytes(1, bytes, sizeof bytes);
    deliver("HEAD_POSE_RAW", bytes, size);
    set_model_length(bytes, 0xffffffffu);
    deliver("HEAD_POSE_RAW", bytes, size);
    set_model_length(bytes, 0x80000000u); /* the most negative */
    deliver("HEAD_POSE_RAW", bytes, size);
    size = measurement_bytes(2, bytes, sizeof bytes);
    deliver("HEAD_POSE_RAW", bytes, size);
    assert_int_equal(monitor.decode_errors, 2);
    assert_int_equal(monitor.raw, 2);
    assert_int_equal(monitor.faces, 2);
}

/* 20,000 datagrams that each claim a 100 kB model id (whole, or cut after the claim): before, each
 * failed decode kept its allocation and hkf-track grew from 3.8 MB to 84 MB. Now nothing is
 * allocated for them: the heap in use grows by less than 1 MB (and LeakSanitizer sees no leak). */
static void test_long_model_claims_do_not_grow(void **state)
{
    const uint32_t claim = 100 * 1000;
    const int whole = MODEL_LENGTH_AT + 4 + (int)claim + 45;
    uint8_t *bytes = calloc(1, (size_t)whole);
    char line[512];
    (void)state;
    assert_non_null(bytes);
    (void)measurement_bytes(1, bytes, whole);
    set_model_length(bytes, claim);
    memset(bytes + MODEL_LENGTH_AT + 4, 'm', claim - 1); /* a NUL-terminated 100 kB id, then the fields */
    const size_t before = mallinfo2().uordblks;
    for (int i = 0; i < 20000; ++i) {
        deliver("HEAD_POSE_RAW", bytes, i % 2 ? whole : MODEL_LENGTH_AT + 4 + 64);
    }
    const size_t after = mallinfo2().uordblks;
    print_message("20,000 datagrams claiming a 100 kB model id: heap in use %zu -> %zu bytes\n", before, after);
    assert_int_equal(monitor.decode_errors, 20000);
    assert_int_equal(monitor.raw, 0);
    assert_true(after < before + 1024 * 1024);
    track_monitor_line(&monitor, 1.0, 1.0, line, sizeof line);
    assert_non_null(strstr(line, "camera   0.0 fps"));
    free(bytes);
}

/* Frame counters near the int64 ends (found by fuzz_node_messages: the second model's window
 * overflowed): a second model's measurement of a frame 5 before the last is told apart there too. */
static void test_seq_at_the_ends(void **state)
{
    uint8_t bytes[256];
    (void)state;
    deliver("HEAD_POSE_RAW", bytes, measurement_bytes(INT64_MIN + 10, bytes, sizeof bytes));
    deliver("HEAD_POSE_RAW", bytes, measurement_bytes(INT64_MIN + 5, bytes, sizeof bytes));
    deliver("HEAD_POSE_RAW", bytes, measurement_bytes(INT64_MAX, bytes, sizeof bytes));
    deliver("HEAD_POSE_RAW", bytes, measurement_bytes(INT64_MAX - 1, bytes, sizeof bytes));
    assert_int_equal(monitor.raw, 2);
    assert_int_equal(monitor.second, 2);
}

/* Poses: a real one is counted and shown; a cut one and a measurement on the pose channel are
 * counted as undecodable and leave the shown pose as it was. */
static void test_poses_checked(void **state)
{
    hkf_head_pose_t pose;
    uint8_t bytes[512], raw[256];
    char line[512];
    (void)state;
    memset(&pose, 0, sizeof pose);
    pose.status = HKF_HEAD_POSE_T_TRACKING;
    pose.yaw = 20.0f;
    pose.latency_us = 15000;
    const int size = hkf_head_pose_t_encode(bytes, 0, sizeof bytes, &pose);
    assert_true(size > 0);
    deliver("HEAD_POSE", bytes, size);
    deliver("HEAD_POSE", bytes, size - 1);
    deliver("HEAD_POSE", raw, measurement_bytes(3, raw, sizeof raw));
    assert_int_equal(monitor.poses, 1);
    assert_int_equal(monitor.decode_errors, 2);
    track_monitor_line(&monitor, 1.0, 1.0, line, sizeof line);
    print_message("%s\n", line);
    assert_non_null(strstr(line, "TRACKING pitch   +0.0 yaw  +20.0"));
    assert_non_null(strstr(line, "p50 15.0 ms"));
}

/* Hardening round 6, item 7: the faces are a rate beside the camera's: 15 frames with a face in the half
 * second a line covers read "camera 30.0 fps (30.0 with a face)", not "(15 with a face)". */
static void test_faces_a_rate(void **state)
{
    uint8_t raw[256];
    char line[512];
    int i;
    (void)state;
    for (i = 0; i < 15; ++i) {
        deliver("HEAD_POSE_RAW", raw, measurement_bytes(i + 1, raw, sizeof raw));
    }
    track_monitor_line(&monitor, 0.5, 0.5, line, sizeof line);
    print_message("%s\n", line);
    assert_non_null(strstr(line, "camera  30.0 fps (30.0 with a face)"));
}

/* A filter that stops (SIGSTOP) or hangs: its last pose is not shown as current; after
 * TRACK_SILENT_LINES silent seconds the line says so, and the pose returns when poses do. */
static void test_silent_filter_said(void **state)
{
    hkf_head_pose_t pose;
    uint8_t bytes[512];
    char line[512];
    int i;
    (void)state;
    memset(&pose, 0, sizeof pose);
    pose.status = HKF_HEAD_POSE_T_TRACKING;
    const int size = hkf_head_pose_t_encode(bytes, 0, sizeof bytes, &pose);
    deliver("HEAD_POSE", bytes, size);
    track_monitor_line(&monitor, 1.0, 1.0, line, sizeof line);
    assert_non_null(strstr(line, "TRACKING"));
    for (i = 1; i <= 3; ++i) {
        track_monitor_line(&monitor, 1.0 + i, 1.0, line, sizeof line);
        print_message("%s\n", line);
        assert_true(i < TRACK_SILENT_LINES ? strstr(line, "TRACKING") != NULL : strstr(line, "TRACKING") == NULL);
    }
    assert_non_null(strstr(line, "no filtered pose for 3 s"));
    deliver("HEAD_POSE", bytes, size);
    track_monitor_line(&monitor, 5.0, 1.0, line, sizeof line);
    assert_non_null(strstr(line, "TRACKING"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_model_length_minus_one, setup, teardown),
        cmocka_unit_test_setup_teardown(test_long_model_claims_do_not_grow, setup, teardown),
        cmocka_unit_test_setup_teardown(test_seq_at_the_ends, setup, teardown),
        cmocka_unit_test_setup_teardown(test_poses_checked, setup, teardown),
        cmocka_unit_test_setup_teardown(test_silent_filter_said, setup, teardown),
        cmocka_unit_test_setup_teardown(test_faces_a_rate, setup, teardown),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

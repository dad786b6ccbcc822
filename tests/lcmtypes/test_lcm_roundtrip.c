/*
 * test_lcm_roundtrip.c - every hkf message type published and received over
 * LCM's in-process memq:// provider, field for field.
 */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>
#include <lcm/lcm.h>

#include "hkf_head_pose_measurement_t.h"
#include "hkf_head_pose_t.h"
#include "hkf_tracker_command_t.h"

static hkf_head_pose_measurement_t received_measurement;
static char received_model[64];
static hkf_head_pose_t received_pose;
static hkf_tracker_command_t received_command;
static int received;

static void on_measurement(const lcm_recv_buf_t *rbuf, const char *channel, const hkf_head_pose_measurement_t *m,
                           void *user)
{
    (void)rbuf;
    (void)user;
    assert_string_equal(channel, "HEAD_POSE_RAW");
    received_measurement = *m;
    strncpy(received_model, m->model, sizeof received_model - 1);
    received_measurement.model = received_model; /* the message's string is freed after the handler */
    ++received;
}

static void on_pose(const lcm_recv_buf_t *rbuf, const char *channel, const hkf_head_pose_t *p, void *user)
{
    (void)rbuf;
    (void)user;
    assert_string_equal(channel, "HEAD_POSE");
    received_pose = *p;
    ++received;
}

static void on_command(const lcm_recv_buf_t *rbuf, const char *channel, const hkf_tracker_command_t *c, void *user)
{
    (void)rbuf;
    (void)user;
    assert_string_equal(channel, "HEAD_TRACKER_CMD");
    received_command = *c;
    ++received;
}

static void test_measurement_round_trip(void **state)
{
    lcm_t *lcm = lcm_create("memq://");
    hkf_head_pose_measurement_t m;
    (void)state;
    assert_non_null(lcm);
    memset(&m, 0, sizeof m);
    m.utime = 1700000000123456LL;
    m.seq = 42;
    m.model = "whenet";
    m.valid = 1;
    m.pitch = -12.5f;
    m.yaw = 179.75f;
    m.roll = 3.25f;
    m.face_box[0] = 10.0f;
    m.face_box[1] = 20.0f;
    m.face_box[2] = 110.0f;
    m.face_box[3] = 140.0f;
    m.detection_score = 0.875f;
    m.inference_us = 16700;
    received = 0;
    hkf_head_pose_measurement_t_subscription_t *sub =
        hkf_head_pose_measurement_t_subscribe(lcm, "HEAD_POSE_RAW", on_measurement, NULL);
    assert_int_equal(hkf_head_pose_measurement_t_publish(lcm, "HEAD_POSE_RAW", &m), 0);
    assert_int_equal(lcm_handle(lcm), 0);
    assert_int_equal(received, 1);
    assert_true(received_measurement.utime == m.utime);
    assert_true(received_measurement.seq == 42);
    assert_string_equal(received_measurement.model, "whenet");
    assert_int_equal(received_measurement.valid, 1);
    assert_true(received_measurement.pitch == -12.5f && received_measurement.yaw == 179.75f &&
                received_measurement.roll == 3.25f);
    assert_memory_equal(received_measurement.face_box, m.face_box, sizeof m.face_box);
    assert_true(received_measurement.detection_score == 0.875f);
    assert_true(received_measurement.inference_us == 16700);
    assert_int_equal(hkf_head_pose_measurement_t_unsubscribe(lcm, sub), 0);
    lcm_destroy(lcm);
}

static void test_pose_round_trip(void **state)
{
    lcm_t *lcm = lcm_create("memq://");
    hkf_head_pose_t p;
    (void)state;
    memset(&p, 0, sizeof p);
    p.utime = 1700000000200000LL;
    p.measurement_utime = 1700000000166667LL;
    p.seq = 7;
    p.status = HKF_HEAD_POSE_T_COASTING;
    p.pitch = 1.5f;
    p.yaw = -90.25f;
    p.roll = 0.125f;
    p.pitch_rate = 10.0f;
    p.yaw_rate = -200.0f;
    p.roll_rate = 0.5f;
    p.variance[1] = 2.5f;
    p.r[2] = 3.375f;
    p.loop_closure_active = 1;
    p.extrapolated = 1;
    p.latency_us = 250;
    received = 0;
    hkf_head_pose_t_subscription_t *sub = hkf_head_pose_t_subscribe(lcm, "HEAD_POSE", on_pose, NULL);
    assert_int_equal(hkf_head_pose_t_publish(lcm, "HEAD_POSE", &p), 0);
    assert_int_equal(lcm_handle(lcm), 0);
    assert_int_equal(received, 1);
    assert_memory_equal(&received_pose, &p, sizeof p); /* no pointers in this type */
    assert_int_equal(hkf_head_pose_t_unsubscribe(lcm, sub), 0);
    lcm_destroy(lcm);
}

static void test_command_round_trip(void **state)
{
    lcm_t *lcm = lcm_create("memq://");
    hkf_tracker_command_t c;
    (void)state;
    memset(&c, 0, sizeof c);
    c.utime = 5;
    c.command = HKF_TRACKER_COMMAND_T_RESET;
    received = 0;
    hkf_tracker_command_t_subscription_t *sub =
        hkf_tracker_command_t_subscribe(lcm, "HEAD_TRACKER_CMD", on_command, NULL);
    assert_int_equal(hkf_tracker_command_t_publish(lcm, "HEAD_TRACKER_CMD", &c), 0);
    assert_int_equal(lcm_handle(lcm), 0);
    assert_int_equal(received, 1);
    assert_int_equal(received_command.command, HKF_TRACKER_COMMAND_T_RESET);
    assert_true(received_command.utime == 5);
    assert_int_equal(hkf_tracker_command_t_unsubscribe(lcm, sub), 0);
    lcm_destroy(lcm);
}

/* A truncated message does not decode (what hkf-filter counts as undecodable). */
static void test_truncated_message_fails_to_decode(void **state)
{
    hkf_head_pose_t p, out;
    unsigned char buffer[256];
    int size;
    (void)state;
    memset(&p, 0, sizeof p);
    size = hkf_head_pose_t_encoded_size(&p);
    assert_true(size > 8 && size <= (int)sizeof buffer);
    assert_int_equal(hkf_head_pose_t_encode(buffer, 0, size, &p), size);
    assert_true(hkf_head_pose_t_decode(buffer, 0, size - 4, &out) < 0);
    buffer[0] ^= 0xFF; /* wrong type fingerprint */
    assert_true(hkf_head_pose_t_decode(buffer, 0, size, &out) < 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_measurement_round_trip),
        cmocka_unit_test(test_pose_round_trip),
        cmocka_unit_test(test_command_round_trip),
        cmocka_unit_test(test_truncated_message_fails_to_decode),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

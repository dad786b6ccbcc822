/* hkf-opentrack's packet: opentrack's byte layout and our angle mapping. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <string.h>

#include <cmocka.h>

#include "opentrack_packet.h"

static hkf_head_pose_t pose_at(float pitch, float yaw, float roll)
{
    hkf_head_pose_t pose;
    memset(&pose, 0, sizeof pose);
    pose.status = HKF_HEAD_POSE_T_TRACKING;
    pose.pitch = pitch;
    pose.yaw = yaw;
    pose.roll = roll;
    return pose;
}

/* Six little-endian doubles: 1.0 is 00 00 00 00 00 00 f0 3f, -2.0 is ... 00 c0. */
static void test_wire_layout(void **state)
{
    const double values[OPENTRACK_FIELDS] = {0.0, 0.0, 0.0, 1.0, -2.0, 0.5};
    static const unsigned char one[8] = {0, 0, 0, 0, 0, 0, 0xf0, 0x3f};
    static const unsigned char minus_two[8] = {0, 0, 0, 0, 0, 0, 0, 0xc0};
    static const unsigned char half[8] = {0, 0, 0, 0, 0, 0, 0xe0, 0x3f};
    static const unsigned char zero[24] = {0};
    unsigned char packet[OPENTRACK_PACKET_SIZE];
    (void)state;
    opentrack_encode(values, packet);
    assert_memory_equal(packet, zero, 24);           /* x, y, z */
    assert_memory_equal(packet + 24, one, 8);        /* yaw */
    assert_memory_equal(packet + 32, minus_two, 8);  /* pitch */
    assert_memory_equal(packet + 40, half, 8);       /* roll */
}

/* The convention mapping: yaw and pitch keep their sign, roll flips. */
static void test_convention(void **state)
{
    opentrack_mapping_t mapping = opentrack_default_mapping();
    hkf_head_pose_t pose = pose_at(10.0f, 20.0f, 30.0f);
    double v[OPENTRACK_FIELDS];
    (void)state;
    mapping.relative_to_center = 0;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_X] == 0.0 && v[OPENTRACK_Y] == 0.0 && v[OPENTRACK_Z] == 0.0);
    assert_true(v[OPENTRACK_YAW] == 20.0);
    assert_true(v[OPENTRACK_PITCH] == 10.0);
    assert_true(v[OPENTRACK_ROLL] == -30.0);
}

/* Relative to the centre, yaw the short way round the +-180 seam. */
static void test_relative_to_center(void **state)
{
    const opentrack_mapping_t mapping = opentrack_default_mapping();
    hkf_head_pose_t pose = pose_at(12.0f, 170.0f, -4.0f);
    double v[OPENTRACK_FIELDS];
    (void)state;
    pose.center[0] = 2.0f;
    pose.center[1] = -170.0f;
    pose.center[2] = 1.0f;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_PITCH] == 10.0);
    assert_true(fabs(v[OPENTRACK_YAW] - (-20.0)) < 1e-9);
    assert_true(v[OPENTRACK_ROLL] == 5.0);
    pose.yaw = -170.0f; /* at the centre: exactly zero */
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_YAW] == 0.0);
    pose.center[1] = 170.0f; /* the short way round the other way: -170 - 170 = -340, i.e. +20 */
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(fabs(v[OPENTRACK_YAW] - 20.0) < 1e-9);
}

/* The user's invert and scale come after the mapping, on opentrack's axes. */
static void test_invert_and_scale(void **state)
{
    opentrack_mapping_t mapping = opentrack_default_mapping();
    hkf_head_pose_t pose = pose_at(10.0f, 20.0f, 30.0f);
    double v[OPENTRACK_FIELDS];
    (void)state;
    mapping.relative_to_center = 0;
    mapping.invert[opentrack_axis_from_name("roll")] = 1;
    mapping.scale[opentrack_axis_from_name("yaw")] = 1.5;
    mapping.invert[opentrack_axis_from_name("pitch")] = 1;
    mapping.scale[opentrack_axis_from_name("pitch")] = 2.0;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_YAW] == 30.0);
    assert_true(v[OPENTRACK_PITCH] == -20.0);
    assert_true(v[OPENTRACK_ROLL] == 30.0);
    assert_int_equal(opentrack_axis_from_name("x"), OPENTRACK_AXIS_X);
    assert_int_equal(opentrack_axis_from_name("w"), -1);
    assert_int_equal(opentrack_axis_from_name(""), -1);
}

/* The position: hkf's x, y, z as opentrack's, minus the centre position unless
 * absolute, then --invert and --scale; beyond 1000 cm refused. */
static void test_position(void **state)
{
    opentrack_mapping_t mapping = opentrack_default_mapping();
    hkf_head_pose_t pose = pose_at(0.0f, 0.0f, 0.0f);
    double v[OPENTRACK_FIELDS];
    (void)state;
    pose.x = 3.0f, pose.y = -2.0f, pose.z = 55.0f;
    pose.position_center[0] = 1.0f, pose.position_center[1] = 1.0f, pose.position_center[2] = 60.0f;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_X] == 2.0 && v[OPENTRACK_Y] == -3.0 && v[OPENTRACK_Z] == -5.0);
    mapping.invert[OPENTRACK_AXIS_Z] = 1;
    mapping.scale[OPENTRACK_AXIS_X] = 2.0;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_X] == 4.0 && v[OPENTRACK_Y] == -3.0 && v[OPENTRACK_Z] == 5.0);
    mapping.relative_to_center = 0;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_X] == 6.0 && v[OPENTRACK_Z] == -55.0);
    pose.z = 1500.0f; /* beyond: the angles are given, the position left as it was */
    pose.yaw = 7.0f;
    v[OPENTRACK_X] = 11.0, v[OPENTRACK_Y] = 12.0, v[OPENTRACK_Z] = 13.0;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), -3);
    assert_true(v[OPENTRACK_YAW] == 7.0 && v[OPENTRACK_X] == 11.0 && v[OPENTRACK_Z] == 13.0);
    pose.z = NAN;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), -3);
    assert_true(v[OPENTRACK_YAW] == 7.0 && v[OPENTRACK_Y] == 12.0);
    /* a TX of 1000 cm scaled x100 is sent as the most opentrack takes, not 100,000 cm */
    pose.x = 1000.0f, pose.z = 55.0f;
    mapping.scale[OPENTRACK_AXIS_X] = 100.0;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_X] == OPENTRACK_MAX_ABS_POSITION);
}

/* Relative angles take the short way round on every axis: a pitch of 180 with the centre at -180
 * is 0, not 360 (36,000 x100); a scaled angle stays within +-180. */
static void test_relative_angles_wrapped(void **state)
{
    opentrack_mapping_t mapping = opentrack_default_mapping();
    hkf_head_pose_t pose = pose_at(180.0f, 170.0f, -170.0f);
    double v[OPENTRACK_FIELDS];
    (void)state;
    pose.center[0] = -180.0f, pose.center[1] = -170.0f, pose.center[2] = 170.0f;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(fabs(v[OPENTRACK_PITCH]) < 1e-9 && fabs(v[OPENTRACK_YAW] - (-20.0)) < 1e-9);
    assert_true(fabs(v[OPENTRACK_ROLL] - (-20.0)) < 1e-9); /* roll -170 - 170 = -340 = +20, then opentrack's sign */
    mapping.scale[OPENTRACK_AXIS_PITCH] = 100.0;
    pose.pitch = 90.0f, pose.center[0] = 0.0f;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
    assert_true(v[OPENTRACK_PITCH] == OPENTRACK_MAX_ABS_ANGLE);
}

/* --predict: a pose moved on by its rates (angles, and the position when measured), not when
 * LOST; the horizon is the pose's age plus the lead, and 0 for a stamp of another clock. */
static void test_predict(void **state)
{
    hkf_head_pose_t pose = pose_at(1.0f, 10.0f, -2.0f), moved;
    (void)state;
    pose.yaw_rate = 100.0f, pose.pitch_rate = -20.0f, pose.roll_rate = 0.0f;
    pose.z = 60.0f, pose.z_rate = -30.0f, pose.x_rate = 10.0f;
    pose.utime = 1000000;
    moved = opentrack_predict(&pose, 0.05);
    assert_true(fabsf(moved.yaw - 15.0f) < 1e-4f && fabsf(moved.pitch - 0.0f) < 1e-4f && moved.roll == -2.0f);
    assert_true(fabsf(moved.z - 58.5f) < 1e-4f && fabsf(moved.x - 0.5f) < 1e-4f);
    assert_true(moved.center[1] == pose.center[1] && moved.utime == pose.utime);
    pose.status = HKF_HEAD_POSE_T_LOST;
    moved = opentrack_predict(&pose, 0.05);
    assert_true(moved.yaw == pose.yaw && moved.z == pose.z);
    pose.status = HKF_HEAD_POSE_T_TRACKING;
    pose.z = 0.0f; /* no position measured: it stays 0 */
    moved = opentrack_predict(&pose, 0.05);
    assert_true(moved.z == 0.0f && moved.x == pose.x);
    moved = opentrack_predict(&pose, -0.01);
    assert_true(moved.yaw == pose.yaw);
    assert_true(fabs(opentrack_horizon(&pose, 1040000, 0.01) - 0.05) < 1e-9); /* 40 ms old, 10 ms lead */
    assert_true(opentrack_horizon(&pose, 990000, 0.01) == 0.0);               /* a stamp in the future */
    assert_true(opentrack_horizon(&pose, 1000000 + 300000, 0.0) == 0.0);      /* older than OPENTRACK_MAX_AGE */
    assert_true(fabs(opentrack_horizon(&pose, 1250000, 0.0) - OPENTRACK_MAX_AGE) < 1e-9);
}

/* Nothing non-finite is ever produced: a NaN or infinite angle or centre is refused. */
/* Round 4: --predict across the yaw seam is a turn (wrapped, then sent), not a corrupt pose; a
 * prediction toward the camera stops at OPENTRACK_MIN_Z (it sent TZ -155 cm with the centre at 60);
 * a status hkf-filter never publishes (7) is corrupt, not sent as tracked. */
static void test_predict_bounded(void **state)
{
    opentrack_mapping_t mapping = opentrack_default_mapping();
    hkf_head_pose_t pose = pose_at(0.0f, 178.0f, 0.0f), moved;
    double v[OPENTRACK_FIELDS];
    (void)state;
    pose.yaw_rate = 200.0f; /* 178 deg + 200 deg/s x 0.02 s = 182 deg: -178 */
    pose.z = 2.0f, pose.z_rate = -3000.0f;
    pose.position_center[2] = 60.0f;
    moved = opentrack_predict(&pose, 0.02);
    assert_true(fabs((double)moved.yaw + 178.0) < 1e-3);
    assert_true(moved.z == (float)OPENTRACK_MIN_Z);
    assert_int_equal(opentrack_pose_values(&mapping, &moved, v), 0);
    assert_true(fabs(v[OPENTRACK_YAW] + 178.0) < 1e-3 && v[OPENTRACK_Z] == OPENTRACK_MIN_Z - 60.0);
    pose = pose_at(1.0f, 2.0f, 3.0f);
    pose.status = 7;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), -4);
    pose.status = HKF_HEAD_POSE_T_COASTING;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
}

static void test_non_finite_refused(void **state)
{
    const opentrack_mapping_t mapping = opentrack_default_mapping();
    double v[OPENTRACK_FIELDS];
    hkf_head_pose_t pose = pose_at(NAN, 0.0f, 0.0f);
    (void)state;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), -1);
    pose = pose_at(0.0f, INFINITY, 0.0f);
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), -1);
    pose = pose_at(0.0f, 0.0f, 0.0f);
    pose.center[2] = -INFINITY;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), -1);
    pose.center[2] = 0.0f;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, v), 0);
}

/* A finite pose no head can make (a forged or corrupt HEAD_POSE: 6.8e37 deg,
 * or a centre of 1000 deg) is refused, not sent to the game camera. ±180 is
 * the limit: a pose at it is sent. */
static void test_beyond_a_head_refused(void **state)
{
    const opentrack_mapping_t mapping = opentrack_default_mapping();
    double values[OPENTRACK_FIELDS];
    hkf_head_pose_t pose = pose_at(0.0f, 6.8e37f, 0.0f);
    (void)state;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, values), -2);
    pose = pose_at(-181.0f, 0.0f, 0.0f);
    assert_int_equal(opentrack_pose_values(&mapping, &pose, values), -2);
    pose = pose_at(0.0f, 0.0f, 0.0f);
    pose.center[2] = 1000.0f;
    assert_int_equal(opentrack_pose_values(&mapping, &pose, values), -2);
    pose = pose_at(180.0f, -180.0f, 180.0f);
    assert_int_equal(opentrack_pose_values(&mapping, &pose, values), 0);
    assert_true(fabs(values[OPENTRACK_PITCH] - (-180.0)) < 1e-9); /* +180 and -180 are one angle: [-180, 180) */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_wire_layout),
        cmocka_unit_test(test_convention),
        cmocka_unit_test(test_relative_to_center),
        cmocka_unit_test(test_invert_and_scale),
        cmocka_unit_test(test_position),
        cmocka_unit_test(test_relative_angles_wrapped),
        cmocka_unit_test(test_predict),
        cmocka_unit_test(test_predict_bounded),
        cmocka_unit_test(test_non_finite_refused),
        cmocka_unit_test(test_beyond_a_head_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

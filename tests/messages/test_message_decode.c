/*
 * test_message_decode.c - hkf's messages decoded (messages/message_decode.c): the measurement's
 * layout checked before LCM's decoder allocates, and hkf 0.1's messages read as 0.2's.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "hkf_head_pose_measurement_v1_t.h"
#include "hkf_head_pose_v1_t.h"
#include "hkf_head_pose_v2_t.h"
#include "hkf_tracker_command_t.h"
#include "message_decode.h"

#define T0 1700000000000000LL

static hkf_head_pose_measurement_t measurement(int64_t utime, int valid, double pitch, double yaw, double roll)
{
    hkf_head_pose_measurement_t m;
    memset(&m, 0, sizeof m);
    m.seq = 1;
    m.utime = utime;
    m.model = "fsanet";
    m.valid = valid;
    m.pitch = (float)pitch;
    m.yaw = (float)yaw;
    m.roll = (float)roll;
    return m;
}

/* message_decode_measurement checks the layout before LCM's decoder allocates: a
 * claimed 2 GB string, a string without its NUL, a short message and another
 * type are refused with nothing allocated (LeakSanitizer watches in the
 * sanitizer build); a good message decodes whole. */
static void test_decode_checks_layout(void **state)
{
    hkf_head_pose_measurement_t m = measurement(T0, 1, 1, 2, 3), back;
    unsigned char buffer[256], spoiled[256];
    const int size = hkf_head_pose_measurement_t_encoded_size(&m);
    const int length_at = 24; /* hash, utime, seq */
    (void)state;
    assert_true(size > 0 && size <= (int)sizeof buffer);
    assert_int_equal(hkf_head_pose_measurement_t_encode(buffer, 0, size, &m), size);
    assert_int_equal(message_decode_measurement(buffer, size, &back), 0);
    assert_string_equal(back.model, "fsanet");
    assert_true(back.utime == T0 && back.yaw == 2.0f);
    hkf_head_pose_measurement_t_decode_cleanup(&back);

    memcpy(spoiled, buffer, (size_t)size);
    spoiled[length_at] = 0x7f, spoiled[length_at + 1] = spoiled[length_at + 2] = spoiled[length_at + 3] = 0xff;
    assert_int_equal(message_decode_measurement(spoiled, size, &back), -1);
    memcpy(spoiled, buffer, (size_t)size);
    spoiled[length_at + 4 + 6] = 'x'; /* "fsanet" loses its NUL */
    assert_int_equal(message_decode_measurement(spoiled, size, &back), -1);
    assert_int_equal(message_decode_measurement(buffer, size - 1, &back), -1);
    memcpy(spoiled, buffer, (size_t)size);
    spoiled[0] ^= 0x5a; /* another type's hash */
    assert_int_equal(message_decode_measurement(spoiled, size, &back), -1);
    assert_int_equal(message_decode_measurement(buffer, 3, &back), -1);
}

/* A live setting (hkf 0.4) decodes whole; a claimed 2 GB or negative string, a key without its NUL, one longer than
 * TEXT_MAX, a byte too many or too few, and a tracker_command_t on the same channel are refused unallocated. */
static void test_setting_layout_checked(void **state)
{
    hkf_tracker_setting_t setting = {T0, (char *)"stillness", (char *)"2.5"}, back;
    hkf_tracker_command_t command = {T0, HKF_TRACKER_COMMAND_T_RECENTER};
    char long_key[HKF_TRACKER_SETTING_T_TEXT_MAX + 2];
    unsigned char buffer[256], spoiled[256];
    const int size = hkf_tracker_setting_t_encoded_size(&setting);
    (void)state;
    assert_int_equal(hkf_tracker_setting_t_encode(buffer, 0, size, &setting), size);
    assert_int_equal(message_decode_setting(buffer, size, &back), 0);
    assert_string_equal(back.key, "stillness");
    assert_string_equal(back.value, "2.5");
    hkf_tracker_setting_t_decode_cleanup(&back);
    memcpy(spoiled, buffer, (size_t)size);
    spoiled[16] = 0x7f; /* the key's length: 2 GB */
    assert_int_equal(message_decode_setting(spoiled, size, &back), -1);
    spoiled[16] = 0xff; /* negative */
    assert_int_equal(message_decode_setting(spoiled, size, &back), -1);
    memcpy(spoiled, buffer, (size_t)size);
    spoiled[16 + 4 + 9] = 'x'; /* "stillness" loses its NUL */
    assert_int_equal(message_decode_setting(spoiled, size, &back), -1);
    assert_int_equal(message_decode_setting(buffer, size - 1, &back), -1);
    assert_int_equal(message_decode_setting(buffer, size + 1, &back), -1);
    assert_int_equal(message_decode_setting(buffer, 10, &back), -1);
    memset(long_key, 'k', sizeof long_key - 1);
    long_key[sizeof long_key - 1] = '\0';
    setting.key = long_key;
    assert_int_equal(hkf_tracker_setting_t_encode(spoiled, 0, (int)sizeof spoiled, &setting),
                     hkf_tracker_setting_t_encoded_size(&setting));
    assert_int_equal(message_decode_setting(spoiled, hkf_tracker_setting_t_encoded_size(&setting), &back), -1);
    assert_int_equal(hkf_tracker_command_t_encode(spoiled, 0, (int)sizeof spoiled, &command),
                     hkf_tracker_command_t_encoded_size(&command));
    assert_int_equal(message_decode_setting(spoiled, hkf_tracker_command_t_encoded_size(&command), &back), -1);
}

/* A camera picture decodes whole; a jpeg_size that is negative, beyond MAX_JPEG_SIZE or not the bytes that follow
 * is refused unallocated. */
static void test_picture_layout_checked(void **state)
{
    uint8_t jpeg[100];
    hkf_camera_picture_t picture = {T0, 7, 320, 240, (int32_t)sizeof jpeg, jpeg}, back;
    unsigned char buffer[256], spoiled[256];
    const int size = hkf_camera_picture_t_encoded_size(&picture);
    (void)state;
    memset(jpeg, 0xd8, sizeof jpeg);
    assert_int_equal(hkf_camera_picture_t_encode(buffer, 0, size, &picture), size);
    assert_int_equal(message_decode_picture(buffer, size, &back), 0);
    assert_true(back.seq == 7 && back.jpeg_size == 100 && back.jpeg[99] == 0xd8);
    hkf_camera_picture_t_decode_cleanup(&back);
    memcpy(spoiled, buffer, (size_t)size);
    spoiled[28] = 0xff; /* negative */
    assert_int_equal(message_decode_picture(spoiled, size, &back), -1);
    spoiled[28] = 0x00, spoiled[29] = 0x10; /* 1 MiB: beyond MAX_JPEG_SIZE */
    assert_int_equal(message_decode_picture(spoiled, size, &back), -1);
    assert_int_equal(message_decode_picture(buffer, size - 1, &back), -1);
    assert_int_equal(message_decode_picture(buffer, 20, &back), -1);
}

/* hkf 0.1's message (head_pose_measurement_v1_t, no position) decodes as a 0.2 one with z = 0. */
static void test_decode_reads_v1(void **state)
{
    hkf_head_pose_measurement_v1_t old;
    hkf_head_pose_measurement_t back;
    unsigned char buffer[256];
    int size;
    (void)state;
    memset(&old, 0, sizeof old);
    old.utime = T0;
    old.seq = 7;
    old.model = "mesh_pnp";
    old.valid = 1;
    old.pitch = 1.0f, old.yaw = -2.0f, old.roll = 3.0f;
    old.face_box[2] = 100.0f;
    size = hkf_head_pose_measurement_v1_t_encoded_size(&old);
    assert_true(size > 0 && size <= (int)sizeof buffer);
    assert_int_equal(hkf_head_pose_measurement_v1_t_encode(buffer, 0, size, &old), size);
    assert_int_equal(message_decode_measurement(buffer, size, &back), 0);
    assert_string_equal(back.model, "mesh_pnp");
    assert_true(back.utime == T0 && back.seq == 7 && back.valid && back.yaw == -2.0f && back.face_box[2] == 100.0f);
    assert_true(back.x == 0.0f && back.y == 0.0f && back.z == 0.0f);
    hkf_head_pose_measurement_t_decode_cleanup(&back);
    assert_int_equal(message_decode_measurement(buffer, size + 12, &back), -1); /* neither layout */
}

/* hkf 0.1's pose (head_pose_v1_t) still decodes, its position 0; hkf 0.2's (head_pose_v2_t) with
 * its position, a measured one's status TRACKING; hkf 0.3's as it is. */
static void test_decode_every_version(void **state)
{
    hkf_head_pose_v1_t old;
    hkf_head_pose_v2_t older_position;
    hkf_head_pose_t pose, back;
    unsigned char buffer[512];
    int size;
    (void)state;
    memset(&old, 0, sizeof old);
    old.status = HKF_HEAD_POSE_T_TRACKING;
    old.yaw = 12.0f;
    old.center[1] = 2.0f;
    size = hkf_head_pose_v1_t_encoded_size(&old);
    assert_true(size > 0 && size <= (int)sizeof buffer);
    assert_int_equal(hkf_head_pose_v1_t_encode(buffer, 0, size, &old), size);
    assert_int_equal(message_decode_pose(buffer, size, &back), 0);
    assert_true(back.yaw == 12.0f && back.center[1] == 2.0f && back.z == 0.0f && back.status == HKF_HEAD_POSE_T_TRACKING);
    assert_int_equal(back.position_status, 0);
    memset(&older_position, 0, sizeof older_position);
    older_position.status = HKF_HEAD_POSE_T_COASTING;
    older_position.yaw = 3.0f;
    older_position.z = 61.0f;
    older_position.position_center[2] = 60.0f;
    older_position.latency_us = 7;
    size = hkf_head_pose_v2_t_encoded_size(&older_position);
    assert_int_equal(hkf_head_pose_v2_t_encode(buffer, 0, size, &older_position), size);
    assert_int_equal(message_decode_pose(buffer, size, &back), 0);
    assert_true(back.yaw == 3.0f && back.z == 61.0f && back.position_center[2] == 60.0f && back.latency_us == 7);
    assert_true(back.status == HKF_HEAD_POSE_T_COASTING && back.position_status == HKF_HEAD_POSE_T_TRACKING);
    memset(&pose, 0, sizeof pose);
    pose.yaw = 2.0f;
    pose.z = 55.0f;
    pose.position_status = HKF_HEAD_POSE_T_LOST;
    size = hkf_head_pose_t_encoded_size(&pose);
    assert_int_equal(hkf_head_pose_t_encode(buffer, 0, size, &pose), size);
    assert_int_equal(message_decode_pose(buffer, size, &back), 0);
    assert_true(back.z == 55.0f && back.yaw == 2.0f && back.position_status == HKF_HEAD_POSE_T_LOST);
    buffer[0] ^= 0x5a; /* neither type's hash */
    assert_int_equal(message_decode_pose(buffer, size, &back), -1);
}

/* A model id over MODEL_NAME_MAX is told apart from other damage, so the programs can say it. */
static void test_long_model_id_named(void **state)
{
    hkf_head_pose_measurement_t m = measurement(T0, 1, 1, 2, 3), back;
    unsigned char buffer[256];
    int size;
    (void)state;
    m.model = "a_model_id_of_thirty_two_letter";
    assert_int_equal((int)strlen(m.model), 31);
    size = hkf_head_pose_measurement_t_encoded_size(&m);
    assert_int_equal(hkf_head_pose_measurement_t_encode(buffer, 0, size, &m), size);
    assert_int_equal(message_decode_measurement(buffer, size, &back), 0); /* 31: the longest allowed */
    hkf_head_pose_measurement_t_decode_cleanup(&back);
    assert_int_equal(message_model_id_too_long(buffer, size), 0);
    m.model = "a_model_id_of_thirty_three_lette";
    size = hkf_head_pose_measurement_t_encoded_size(&m);
    assert_int_equal(hkf_head_pose_measurement_t_encode(buffer, 0, size, &m), size);
    assert_int_equal(message_decode_measurement(buffer, size, &back), -1);
    assert_int_equal(message_model_id_too_long(buffer, size), 1);
    assert_int_equal(message_model_id_too_long(buffer, 20), 0); /* too short to say */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_decode_checks_layout),
        cmocka_unit_test(test_decode_reads_v1),
        cmocka_unit_test(test_decode_every_version),
        cmocka_unit_test(test_long_model_id_named),
        cmocka_unit_test(test_setting_layout_checked),
        cmocka_unit_test(test_picture_layout_checked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

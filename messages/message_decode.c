/* message_decode.c - see message_decode.h. */
#include "message_decode.h"

#include <string.h>

#include "hkf_head_pose_measurement_v1_t.h"
#include "hkf_head_pose_v1_t.h"
#include "hkf_head_pose_v2_t.h"

/* The wire layout of a measurement: hash, utime, seq (8 bytes each), the model string as a
 * big-endian int32 length with its NUL and the bytes, then valid (1), pitch, yaw, roll (4 each),
 * face_box (16), detection_score (4), inference_us (8), and since hkf 0.2 x, y, z (4 each). */
enum { MODEL_AT = 24, TAIL_V1 = 1 + 12 + 16 + 4 + 8, TAIL = TAIL_V1 + 12 };
enum { MODEL_BYTES_MAX = HKF_HEAD_POSE_MEASUREMENT_T_MODEL_NAME_MAX + 1 }; /* with the NUL */

/* The model string's claimed length (with its NUL); the payload has at least MODEL_AT + 4 bytes. */
static long model_length(const unsigned char *bytes)
{
    return ((long)bytes[MODEL_AT] << 24) | ((long)bytes[MODEL_AT + 1] << 16) | ((long)bytes[MODEL_AT + 2] << 8) |
           bytes[MODEL_AT + 3];
}

/* hkf 0.1's measurement as a 0.2 one, z = 0. */
static int decode_measurement_v1(const void *data, int size, hkf_head_pose_measurement_t *m)
{
    hkf_head_pose_measurement_v1_t old;
    memset(&old, 0, sizeof old);
    if (hkf_head_pose_measurement_v1_t_decode(data, 0, size, &old) != size) {
        hkf_head_pose_measurement_v1_t_decode_cleanup(&old);
        return -1;
    }
    m->utime = old.utime;
    m->seq = old.seq;
    m->model = old.model; /* taken over: freed by hkf_head_pose_measurement_t_decode_cleanup */
    m->valid = old.valid;
    m->pitch = old.pitch;
    m->yaw = old.yaw;
    m->roll = old.roll;
    memcpy(m->face_box, old.face_box, sizeof m->face_box);
    m->detection_score = old.detection_score;
    m->inference_us = old.inference_us;
    m->x = m->y = m->z = 0.f;
    return 0;
}

int message_decode_measurement(const void *data, int size, hkf_head_pose_measurement_t *m)
{
    const unsigned char *bytes = data;
    long length;
    int v1;
    if (data == NULL || size < MODEL_AT + 4 + 1 + TAIL_V1) {
        return -1;
    }
    length = model_length(bytes);
    if (length < 1 || length > MODEL_BYTES_MAX || bytes[MODEL_AT + 4 + length - 1] != '\0') {
        return -1;
    }
    if (MODEL_AT + 4 + length + TAIL == size) {
        v1 = 0;
    } else if (MODEL_AT + 4 + length + TAIL_V1 == size) {
        v1 = 1;
    } else {
        return -1;
    }
    memset(m, 0, sizeof *m); /* so that a cleanup after a failed decode frees nothing it did not allocate */
    if (v1) {
        return decode_measurement_v1(data, size, m);
    }
    if (hkf_head_pose_measurement_t_decode(data, 0, size, m) != size) { /* e.g. another type's hash */
        hkf_head_pose_measurement_t_decode_cleanup(m);
        return -1;
    }
    return 0;
}

int message_model_id_too_long(const void *data, int size)
{
    long length;
    if (data == NULL || size < MODEL_AT + 4) {
        return 0;
    }
    length = model_length(data);
    return length > MODEL_BYTES_MAX && length <= size - (MODEL_AT + 4);
}

/* The fields every version of the pose has (hkf 0.1's), from old into pose. */
#define COPY_ANGLE_FIELDS(pose, old)                                                                              \
    do {                                                                                                          \
        (pose)->utime = (old).utime, (pose)->measurement_utime = (old).measurement_utime, (pose)->seq = (old).seq; \
        (pose)->status = (old).status;                                                                            \
        (pose)->pitch = (old).pitch, (pose)->yaw = (old).yaw, (pose)->roll = (old).roll;                          \
        (pose)->pitch_rate = (old).pitch_rate, (pose)->yaw_rate = (old).yaw_rate;                                 \
        (pose)->roll_rate = (old).roll_rate;                                                                      \
        memcpy((pose)->variance, (old).variance, sizeof (pose)->variance);                                        \
        memcpy((pose)->r, (old).r, sizeof (pose)->r);                                                             \
        memcpy((pose)->center, (old).center, sizeof (pose)->center);                                              \
        (pose)->loop_closure_active = (old).loop_closure_active, (pose)->extrapolated = (old).extrapolated;       \
        (pose)->latency_us = (old).latency_us;                                                                    \
    } while (0)

/* hkf 0.2's pose as a 0.3 one: the position without its status (measured when z > 0: TRACKING). */
static int decode_pose_v2(const void *data, int size, hkf_head_pose_t *pose)
{
    hkf_head_pose_v2_t old;
    if (hkf_head_pose_v2_t_decode(data, 0, size, &old) < 0) {
        return -1;
    }
    memset(pose, 0, sizeof *pose);
    COPY_ANGLE_FIELDS(pose, old);
    pose->x = old.x, pose->y = old.y, pose->z = old.z;
    pose->x_rate = old.x_rate, pose->y_rate = old.y_rate, pose->z_rate = old.z_rate;
    memcpy(pose->position_variance, old.position_variance, sizeof pose->position_variance);
    memcpy(pose->position_center, old.position_center, sizeof pose->position_center);
    pose->position_status = old.z > 0.f ? HKF_HEAD_POSE_T_TRACKING : 0; /* 0.2 did not say: as a measured one */
    return 0;
}

int message_decode_pose(const void *data, int size, hkf_head_pose_t *pose)
{
    hkf_head_pose_v1_t old;
    if (hkf_head_pose_t_decode(data, 0, size, pose) >= 0) {
        return 0;
    }
    if (decode_pose_v2(data, size, pose) == 0) {
        return 0;
    }
    if (hkf_head_pose_v1_t_decode(data, 0, size, &old) < 0) {
        return -1;
    }
    memset(pose, 0, sizeof *pose);
    COPY_ANGLE_FIELDS(pose, old);
    return 0;
}

/* A big-endian int32 field as LCM writes it, read as a non-negative length; -1 when it is negative. */
static long length_at(const unsigned char *bytes)
{
    const unsigned long value = ((unsigned long)bytes[0] << 24) | ((unsigned long)bytes[1] << 16) |
                                ((unsigned long)bytes[2] << 8) | bytes[3];
    return value > 0x7fffffffUL ? -1 : (long)value;
}

int message_decode_setting(const void *data, int size, hkf_tracker_setting_t *s)
{
    const unsigned char *bytes = data;
    long at = 16; /* hash, utime */
    int i;
    for (i = 0; i < 2 && data != NULL; ++i) { /* the key, then the value: a length with its NUL, the bytes */
        long length;
        if (at + 4 > size) return -1;
        length = length_at(bytes + at);
        if (length < 2 || length > HKF_TRACKER_SETTING_T_TEXT_MAX + 1 || at + 4 + length > size ||
            bytes[at + 4 + length - 1] != '\0') {
            return -1;
        }
        at += 4 + length;
    }
    if (data == NULL || at != size) return -1;
    memset(s, 0, sizeof *s);
    if (hkf_tracker_setting_t_decode(data, 0, size, s) != size) { /* another type's hash */
        hkf_tracker_setting_t_decode_cleanup(s);
        return -1;
    }
    return 0;
}

int message_decode_picture(const void *data, int size, hkf_camera_picture_t *p)
{
    enum { JPEG_SIZE_AT = 28, JPEG_AT = 32 }; /* hash, utime, seq (8 each), width, height (2 each), jpeg_size (4) */
    long length;
    if (data == NULL || size < JPEG_AT) return -1;
    length = length_at((const unsigned char *)data + JPEG_SIZE_AT);
    if (length < 0 || length > HKF_CAMERA_PICTURE_T_MAX_JPEG_SIZE || JPEG_AT + length != size) return -1;
    memset(p, 0, sizeof *p);
    if (hkf_camera_picture_t_decode(data, 0, size, p) != size) {
        hkf_camera_picture_t_decode_cleanup(p);
        return -1;
    }
    return 0;
}

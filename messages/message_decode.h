/*
 * message_decode.h - hkf's messages decoded from LCM payloads, checked, and with older versions
 * read as today's (written once here for hkf-filter, hkf-opentrack, hkf-annotate and hkf-track).
 *
 * hkf 0.1's messages are head_pose_measurement_v1_t and head_pose_v1_t: the same fields but no
 * position. Read as today's, their position is 0 (z = 0: not measured). hkf 0.2's pose is
 * head_pose_v2_t: no position_status.
 */
#ifndef MESSAGE_DECODE_H
#define MESSAGE_DECODE_H

#include "hkf_camera_picture_t.h"
#include "hkf_head_pose_measurement_t.h"
#include "hkf_head_pose_t.h"
#include "hkf_tracker_setting_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A HEAD_POSE_RAW payload, hkf 0.2's or 0.1's, its layout checked before LCM's generated decoder
 * runs: LCM 1.3.1's decoder mallocs a string of whatever length the message claims (up to 2 GB),
 * leaks it when a later field is short, and does not require the terminating NUL. The payload
 * must be exactly one message. Returns 0 with *m decoded (free with
 * hkf_head_pose_measurement_t_decode_cleanup), or -1 with nothing allocated. */
int message_decode_measurement(const void *data, int size, hkf_head_pose_measurement_t *m);

/* 1 when a HEAD_POSE_RAW payload that did not decode carries a model id longer than
 * MODEL_NAME_MAX: the one mistake a user makes, so the programs say it. */
int message_model_id_too_long(const void *data, int size);

/* A HEAD_POSE payload, hkf 0.3's, 0.2's (which carries no position_status: TRACKING where z > 0,
 * else 0) or 0.1's (which carries no position: x, y, z and their rates, variances, centre and
 * status are 0). Returns 0 with *pose decoded, or -1. */
int message_decode_pose(const void *data, int size, hkf_head_pose_t *pose);

/* A live setting on the command channel (hkf 0.4), its layout checked first: the key and the value each
 * 1 to TEXT_MAX bytes and their NUL, and nothing after. Returns 0 with *s decoded (free with
 * hkf_tracker_setting_t_decode_cleanup), or -1 with nothing allocated (e.g. a tracker_command_t). */
int message_decode_setting(const void *data, int size, hkf_tracker_setting_t *s);

/* A camera picture (hkf 0.4), its layout checked first: jpeg_size from 0 to MAX_JPEG_SIZE and exactly that
 * many bytes after it. Returns 0 with *p decoded (free with hkf_camera_picture_t_decode_cleanup), or -1 with
 * nothing allocated. */
int message_decode_picture(const void *data, int size, hkf_camera_picture_t *p);

#ifdef __cplusplus
}
#endif

#endif /* MESSAGE_DECODE_H */

/*
 * view_events.h - the live view's events, one line of JSON each, from the tracker's messages: a model's raw
 * measurement (HEAD_POSE_RAW), the filtered pose (HEAD_POSE), hkf-filter's rest status (HEAD_POSE_STATUS),
 * hkf-track's status line, and a new camera picture. A number that is not finite is written null.
 * Each returns the characters written (< size), or 0 when it did not fit.
 */
#ifndef VIEW_EVENTS_H
#define VIEW_EVENTS_H

#include <stddef.h>
#include <stdint.h>

#include "hkf_head_pose_measurement_t.h"
#include "hkf_head_pose_t.h"
#include "hkf_tracker_status_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* {"t":"raw","model":..,"utime":..,"seq":..,"valid":..,"pitch":..,"yaw":..,"roll":..,"box":[4],"z":..} */
size_t view_event_raw(const hkf_head_pose_measurement_t *m, char *out, size_t size);

/* {"t":"pose","utime":..,"seq":..,"status":"TRACKING"..,"pitch":..,..,"x":..,"y":..,"z":..,"latency_ms":..,
 *  "center":[3],"from_center":[3],"position_from_center":[3],"extrapolated":..}: from_center as hkf-track's line
 *  and opentrack take the pose (pose_angles.h) */
size_t view_event_pose(const hkf_head_pose_t *p, char *out, size_t size);

/* {"t":"status","rest":"NO_REST|RESTING|MEASURED","progress":..,"rest_time":..,"spoiled":..,
 *  "wander_measured":..,"stillness":..,"wander":..,"rest_spread":[3],"rest_noise":[3],"commands":..,"settings_saved":..,"settings_unsaved":..} */
size_t view_event_status(const hkf_tracker_status_t *s, char *out, size_t size);

/* {"t":"line","text":".."}: hkf-track's status line, as its terminal shows it */
size_t view_event_line(const char *text, char *out, size_t size);

/* {"t":"picture","n":..,"utime":..,"seq":..}: picture n (GET /picture.jpg) of the frame captured at utime */
size_t view_event_picture(uint64_t n, int64_t utime, int64_t seq, char *out, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* VIEW_EVENTS_H */

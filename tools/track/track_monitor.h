/*
 * track_monitor.h - hkf-track's status line: listens to HEAD_POSE_RAW,
 * HEAD_POSE and HEAD_POSE_STATUS and says, once a second, the camera and filter
 * rates, the capture-to-pose latency and the latest pose from the centre; and,
 * while hkf-filter measures the player's rest, asks the player to keep still and
 * counts down (twice a second), says a rest spoiled by a move is asked again, and
 * says when the rest is measured.
 */
#ifndef TRACK_MONITOR_H
#define TRACK_MONITOR_H

#include <stddef.h>
#include <stdint.h>

#include <lcm/lcm.h>

#include "hkf_head_pose_t.h"
#include "hkf_tracker_status_t.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TRACK_MAX_LATENCIES 8192 /* per status line; more poses than that in a second are not timed */

typedef struct {
    int clock_is_real;  /* a camera, or a file at its frame rate: the stamps are the wall clock's */
    long raw, faces, poses, second; /* since the last status line */
    long total_poses;
    double latency_ms[TRACK_MAX_LATENCIES];
    int latencies;
    int64_t last_seq;
    int have_seq;
    hkf_head_pose_t last;
    int have_last;
    int silent_lines;   /* status lines in a row without a pose */
    long decode_errors;
    hkf_tracker_status_t status; /* hkf-filter's last status (the player's rest) */
    int have_status;
    int32_t said_spoiled;        /* rests spoiled, as the last line said */
    int said_measured;           /* the last line said the rest was measured */
} track_monitor_t;

/* Subscribes m to the three channels on lcm. 0, or -1 (said on stderr). */
int track_monitor_start(track_monitor_t *m, lcm_t *lcm, int clock_is_real);

/* One HEAD_POSE_RAW / HEAD_POSE payload, as the subscriptions hand it over: decoded by messages/
 * (message_decode.h: the layout checked before anything is allocated, so no payload can crash the
 * launcher or grow it) and counted; one that does not decode is counted in decode_errors. */
void track_monitor_take_raw(track_monitor_t *m, const void *data, int size);
void track_monitor_take_pose(track_monitor_t *m, const void *data, int size);
/* One HEAD_POSE_STATUS payload (tracker_status_t: fixed size, nothing allocated); one that does not
 * decode, or whose rest is out of range, is counted in decode_errors. */
void track_monitor_take_status(track_monitor_t *m, const void *data, int size);

/* 1 while hkf-filter measures the player's rest: the line is then due twice a second (the countdown). */
int track_monitor_resting(const track_monitor_t *m);

/* The status line for the `interval` seconds since the last one, `elapsed` s
 * after the start, into out; the counts start again. The latest pose is shown
 * while poses come; after TRACK_SILENT_LINES lines without one (hkf-filter
 * publishes at least a LOST pose a second), the line says the filter is silent
 * instead of showing its last pose as if it were current. */
#define TRACK_SILENT_LINES 2
void track_monitor_line(track_monitor_t *m, double elapsed, double interval, char *out, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* TRACK_MONITOR_H */

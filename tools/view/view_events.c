/* view_events.c - see view_events.h. */
#define _POSIX_C_SOURCE 200809L

#include "view_events.h"

#include "pose_angles.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>

typedef struct {
    char *out;
    size_t size, used;
    int full;
} json_t;

static void put(json_t *j, const char *format, ...)
{
    va_list args;
    int n;
    if (j->full) {
        return;
    }
    va_start(args, format);
    n = vsnprintf(j->out + j->used, j->size - j->used, format, args);
    va_end(args);
    if (n < 0 || (size_t)n >= j->size - j->used) {
        j->full = 1;
        return;
    }
    j->used += (size_t)n;
}

/* "key":number, or null when it is not finite; a comma before unless first */
static void number(json_t *j, const char *key, double value)
{
    if (isfinite(value)) {
        put(j, ",\"%s\":%.4g", key, value);
    } else {
        put(j, ",\"%s\":null", key);
    }
}

static void numbers(json_t *j, const char *key, const float *values, int count)
{
    int i;
    put(j, ",\"%s\":[", key);
    for (i = 0; i < count; ++i) {
        if (isfinite(values[i])) {
            put(j, "%s%.4g", i ? "," : "", (double)values[i]);
        } else {
            put(j, "%snull", i ? "," : "");
        }
    }
    put(j, "]");
}

/* "key":"text" with JSON's escapes; control characters as \u00XX */
static void text(json_t *j, const char *key, const char *value)
{
    put(j, ",\"%s\":\"", key);
    for (; *value != '\0'; ++value) {
        const unsigned char c = (unsigned char)*value;
        if (c == '"' || c == '\\') {
            put(j, "\\%c", c);
        } else if (c < 0x20) {
            put(j, "\\u%04x", c);
        } else {
            put(j, "%c", c);
        }
    }
    put(j, "\"");
}

static size_t finish(json_t *j)
{
    put(j, "}");
    return j->full ? 0 : j->used;
}

size_t view_event_raw(const hkf_head_pose_measurement_t *m, char *out, size_t size)
{
    json_t j = {out, size, 0, 0};
    put(&j, "{\"t\":\"raw\"");
    text(&j, "model", m->model != NULL ? m->model : "");
    put(&j, ",\"utime\":%lld,\"seq\":%lld,\"valid\":%s", (long long)m->utime, (long long)m->seq,
        m->valid ? "true" : "false");
    number(&j, "pitch", m->pitch);
    number(&j, "yaw", m->yaw);
    number(&j, "roll", m->roll);
    numbers(&j, "box", m->face_box, 4);
    number(&j, "z", m->z);
    return finish(&j);
}

static const char *pose_status(int8_t status)
{
    return status == HKF_HEAD_POSE_T_TRACKING ? "TRACKING"
           : status == HKF_HEAD_POSE_T_COASTING ? "COASTING"
           : status == HKF_HEAD_POSE_T_LOST     ? "LOST"
                                                : "?";
}

size_t view_event_pose(const hkf_head_pose_t *p, char *out, size_t size)
{
    json_t j = {out, size, 0, 0};
    double from_center[3], position[3];
    float angles[3], offsets[3];
    int a;
    put(&j, "{\"t\":\"pose\",\"utime\":%lld,\"seq\":%lld", (long long)p->utime, (long long)p->seq);
    text(&j, "status", pose_status(p->status));
    number(&j, "pitch", p->pitch);
    number(&j, "yaw", p->yaw);
    number(&j, "roll", p->roll);
    number(&j, "x", p->x);
    number(&j, "y", p->y);
    number(&j, "z", p->z);
    number(&j, "latency_ms", (double)p->latency_us / 1000.0);
    numbers(&j, "center", p->center, 3);
    pose_from_center(p, from_center, position);
    for (a = 0; a < 3; ++a) {
        angles[a] = (float)from_center[a];
        offsets[a] = (float)position[a];
    }
    numbers(&j, "from_center", angles, 3); /* as hkf-track's line and opentrack take it (pose_angles.h) */
    numbers(&j, "position_from_center", offsets, 3);
    put(&j, ",\"extrapolated\":%s", p->extrapolated ? "true" : "false");
    return finish(&j);
}

static const char *rest_name(int8_t rest)
{
    return rest == HKF_TRACKER_STATUS_T_RESTING ? "RESTING" : rest == HKF_TRACKER_STATUS_T_MEASURED ? "MEASURED" : "NO_REST";
}

size_t view_event_status(const hkf_tracker_status_t *s, char *out, size_t size)
{
    json_t j = {out, size, 0, 0};
    put(&j, "{\"t\":\"status\"");
    text(&j, "rest", rest_name(s->rest));
    number(&j, "progress", s->rest_progress);
    number(&j, "rest_time", s->rest_time);
    put(&j, ",\"spoiled\":%ld,\"wander_measured\":%s", (long)s->rests_spoiled, s->wander_measured ? "true" : "false");
    number(&j, "stillness", s->stillness);
    number(&j, "wander", s->wander);
    numbers(&j, "rest_spread", s->rest_spread, 3);
    numbers(&j, "rest_noise", s->rest_noise, 3);
    put(&j, ",\"commands\":%ld,\"settings_saved\":%ld,\"settings_unsaved\":%ld", (long)s->commands,
        (long)s->settings_saved, (long)s->settings_unsaved);
    return finish(&j);
}

size_t view_event_line(const char *line, char *out, size_t size)
{
    json_t j = {out, size, 0, 0};
    put(&j, "{\"t\":\"line\"");
    text(&j, "text", line);
    return finish(&j);
}

size_t view_event_picture(uint64_t n, int64_t utime, int64_t seq, char *out, size_t size)
{
    json_t j = {out, size, 0, 0};
    put(&j, "{\"t\":\"picture\",\"n\":%llu,\"utime\":%lld,\"seq\":%lld", (unsigned long long)n, (long long)utime,
        (long long)seq);
    return finish(&j);
}

/* track_monitor.c - see track_monitor.h. */
#include "track_monitor.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lcm_wait.h"
#include "message_decode.h"
#include "pose_angles.h"

/* A second model's measurement of a frame already counted carries that frame's seq (it may come late). */
#define TRACK_SECOND_MODEL_WINDOW 300

void track_monitor_take_raw(track_monitor_t *m, const void *data, int size)
{
    hkf_head_pose_measurement_t raw;
    if (message_decode_measurement(data, size, &raw) != 0) { /* checked before anything is allocated */
        ++m->decode_errors;
        return;
    }
    /* seqs may be anything: the window in double (last_seq - 300 overflowed near INT64_MIN: fuzz_node_messages) */
    if (m->have_seq && raw.seq <= m->last_seq && (double)m->last_seq - (double)raw.seq < TRACK_SECOND_MODEL_WINDOW) {
        ++m->second;
    } else {
        m->last_seq = raw.seq, m->have_seq = 1;
        ++m->raw;
        m->faces += raw.valid != 0;
    }
    hkf_head_pose_measurement_t_decode_cleanup(&raw);
}

void track_monitor_take_pose(track_monitor_t *m, const void *data, int size)
{
    hkf_head_pose_t pose;
    if (message_decode_pose(data, size, &pose) != 0) {
        ++m->decode_errors;
        return;
    }
    ++m->poses, ++m->total_poses;
    if (!pose.extrapolated && m->latencies < TRACK_MAX_LATENCIES) {
        m->latency_ms[m->latencies++] = (double)pose.latency_us / 1000.0;
    }
    m->last = pose, m->have_last = 1;
}

void track_monitor_take_status(track_monitor_t *m, const void *data, int size)
{
    hkf_tracker_status_t status;
    if (hkf_tracker_status_t_decode(data, 0, size, &status) != size || status.rest < HKF_TRACKER_STATUS_T_NO_REST ||
        status.rest > HKF_TRACKER_STATUS_T_MEASURED || !isfinite(status.rest_progress) || !isfinite(status.rest_time) ||
        !isfinite(status.wander)) {
        ++m->decode_errors;
        return;
    }
    m->status = status, m->have_status = 1;
}

int track_monitor_resting(const track_monitor_t *m)
{
    return m->have_status && m->status.rest == HKF_TRACKER_STATUS_T_RESTING;
}

static void on_status(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    track_monitor_take_status(user, rbuf->data, (int)rbuf->data_size);
}

static void on_raw(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    track_monitor_take_raw(user, rbuf->data, (int)rbuf->data_size);
}

static void on_pose(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    (void)channel;
    track_monitor_take_pose(user, rbuf->data, (int)rbuf->data_size);
}

int track_monitor_start(track_monitor_t *m, lcm_t *lcm, int clock_is_real)
{
    memset(m, 0, sizeof *m);
    m->clock_is_real = clock_is_real;
    if (lcm_wait_subscribe(lcm, "HEAD_POSE_RAW", on_raw, m, "hkf-track") == NULL ||
        lcm_wait_subscribe(lcm, "HEAD_POSE", on_pose, m, "hkf-track") == NULL ||
        lcm_wait_subscribe(lcm, "HEAD_POSE_STATUS", on_status, m, "hkf-track") == NULL) {
        return -1;
    }
    return 0;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Appends printf-style text to out, never beyond size. */
#define APPEND(...) (used += (size_t)snprintf(out + used, used < size ? size - used : 0, __VA_ARGS__), \
                     used = used < size ? used : size)

static const char *status_name(int status)
{
    return status == HKF_HEAD_POSE_T_TRACKING ? "TRACKING"
           : status == HKF_HEAD_POSE_T_COASTING ? "COASTING"
           : status == HKF_HEAD_POSE_T_LOST     ? "LOST"
                                                : "?";
}

/* The pose from the centre (pose_from_center): pitch, yaw, roll and, when measured, x, y, z. */
static size_t pose_text(const hkf_head_pose_t *p, char *out, size_t size)
{
    size_t used = 0;
    double angles[3], position[3];
    pose_from_center(p, angles, position);
    APPEND(", %s pitch %+6.1f yaw %+6.1f roll %+6.1f deg", status_name(p->status), angles[0], angles[1], angles[2]);
    if (p->z > 0.0f) {
        APPEND(", x %+5.1f y %+5.1f z %+5.1f cm", position[0], position[1], position[2]);
    }
    APPEND(" from centre");
    return used;
}

/* The player's rest, as hkf-filter's status says: the request to keep still with the countdown while it
 * is measured (a move spoiled it: asked again), and once that it was measured. */
static size_t rest_text(track_monitor_t *m, char *out, size_t size)
{
    const hkf_tracker_status_t *s = &m->status;
    size_t used = 0;
    if (s->rest == HKF_TRACKER_STATUS_T_RESTING) {
        const double left = (1.0 - (double)s->rest_progress) * (double)s->rest_time;
        APPEND(" | look at the screen's centre and keep still: %.1f s", left > 0.0 ? left : 0.0);
        if (s->rests_spoiled > m->said_spoiled) APPEND(" (you moved: again)");
    } else if (s->rest == HKF_TRACKER_STATUS_T_MEASURED && !m->said_measured) {
        APPEND(" | rest measured: the view holds still by %.2f deg^2 (--stillness %.2g)", (double)s->wander,
               (double)s->stillness);
    }
    m->said_spoiled = s->rests_spoiled;
    m->said_measured = s->rest == HKF_TRACKER_STATUS_T_MEASURED;
    return used;
}

void track_monitor_line(track_monitor_t *m, double elapsed, double interval, char *out, size_t size)
{
    size_t used = 0;
    APPEND("[%6.1f s] camera %5.1f fps (%.1f with a face), filter %5.1f poses/s", elapsed, m->raw / interval, m->faces / interval,
           m->poses / interval);
    if (m->second) APPEND(", second model %4.1f/s", m->second / interval);
    if (m->latencies > 0 && m->clock_is_real) {
        qsort(m->latency_ms, (size_t)m->latencies, sizeof m->latency_ms[0], by_value);
        APPEND(", capture->pose p50 %.1f ms max %.1f ms", m->latency_ms[m->latencies / 2],
               m->latency_ms[m->latencies - 1]);
    } else if (m->latencies > 0) { /* a file read as fast as it goes: its stamps are the file's time */
        APPEND(", no latency (a file faster than real time: --realtime measures it)");
    }
    m->silent_lines = m->poses == 0 ? m->silent_lines + 1 : 0;
    if (m->have_last && m->silent_lines >= TRACK_SILENT_LINES) {
        APPEND(", no filtered pose for %d s: is hkf-filter stopped or hung?", m->silent_lines);
    } else if (m->have_last && used < size) {
        used += pose_text(&m->last, out + used, size - used);
        used = used < size ? used : size;
    }
    if (m->have_status && used < size) {
        rest_text(m, out + used, size - used);
    }
    m->raw = m->faces = m->poses = m->second = 0;
    m->latencies = 0;
}

/* node_schedule.c - see node_schedule.h. */
#include "node_schedule.h"

#include <string.h>

void node_schedule_init(node_schedule_t *s, int64_t tick_us, int repeat_lost)
{
    memset(s, 0, sizeof *s);
    s->tick_us = tick_us > 0 ? tick_us : 0;
    s->repeat_lost = repeat_lost;
    s->ticks_over = 1; /* until a measurement is taken */
}

/* A new measurement taken since the last call: the ticks follow it. */
static void follow_measurement(node_schedule_t *s, const filter_node_t *node)
{
    const stream_admission_t *a = &node->admission;
    if (!a->have_time || (a->last_utime == s->ticks_from && a->last_arrival_utime == s->ticks_from_arrival)) {
        return;
    }
    s->ticks_from = a->last_utime;
    s->ticks_from_arrival = a->last_arrival_utime;
    s->ticks_after = a->last_utime;
    s->ticks_over = 0;
}

/* The next tick's capture time *t and the arrival time it is due at, or 0: no tick is due. */
static int64_t tick_due(const node_schedule_t *s, const filter_node_t *node, int64_t *t)
{
    const stream_admission_t *a = &node->admission;
    double ahead_us;
    if (s->tick_us == 0 || s->ticks_over || s->ticks_after > INT64_MAX - s->tick_us) {
        return 0;
    }
    *t = (s->ticks_after / s->tick_us + 1) * s->tick_us; /* the grid's next point after ticks_after */
    ahead_us = (double)*t - (double)a->last_utime;
    if (ahead_us > 1e12 || (double)a->last_arrival_utime + ahead_us >= 9.2e18) {
        return 0; /* far beyond any coast_time, or beyond the clock's end: no extrapolation */
    }
    return a->last_arrival_utime + (*t - a->last_utime);
}

/* When the silence's LOST pose is due (filter_node_silence_due), or 0. */
static int64_t lost_due(const node_schedule_t *s, const filter_node_t *node)
{
    return s->repeat_lost || node->lost_published == 0 ? filter_node_silence_due(node) : 0;
}

static int64_t earlier(int64_t a, int64_t b)
{
    return a == 0 ? b : b == 0 || a <= b ? a : b;
}

int64_t node_schedule_wake(node_schedule_t *s, const filter_node_t *node)
{
    int64_t t;
    follow_measurement(s, node);
    return earlier(filter_node_await_due(node), earlier(tick_due(s, node, &t), lost_due(s, node)));
}

int node_schedule_next(node_schedule_t *s, filter_node_t *node, int64_t now, hkf_head_pose_t *pose, int64_t *due)
{
    int64_t t, tick, lost;
    if (filter_node_await_next(node, now, pose, due)) {
        return 1; /* a waiting frame's pose first: the oldest frame */
    }
    follow_measurement(s, node);
    /* ticks first: they end where extrapolation does, at coast_time, and LOST is due no earlier */
    while ((tick = tick_due(s, node, &t)) != 0 && tick <= now) {
        s->ticks_after = t;
        if (t <= node->published_utime) {
            continue; /* a late frame's pose was published at or after it */
        }
        if (filter_node_extrapolate(node, t, pose)) {
            *due = tick;
            return 1;
        }
        s->ticks_over = 1; /* coast_time passed, or no track: no tick until a new measurement */
    }
    lost = lost_due(s, node);
    if (lost != 0 && lost <= now && filter_node_silence(node, now, pose)) {
        *due = lost;
        return 1;
    }
    return 0;
}

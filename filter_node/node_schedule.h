/*
 * node_schedule.h - what hkf-filter publishes between measurements, and when: the LOST pose of a
 * silence (filter_node_silence) and the --rate ticks (filter_node_extrapolate). One call for the
 * live loop and for --offline, so that a replayed log gives the poses the live node gave.
 *
 * Both are due on the arrival clock (a monotonic clock live, the log's event timestamps offline):
 * - a tick every tick_us of *capture* time, on the grid of its multiples after the last
 *   measurement taken, due when as much arrival time has passed since that measurement arrived;
 *   ticks stop where extrapolation does (coast_time after the measurement, or no track) until
 *   the next measurement is taken;
 * - first, a frame that waited for the second model's answer, at its deadline or queued by a later frame, a
 *   command or a restart (filter_node_await_next: one pose per frame);
 * - a LOST pose when the followed estimator has been silent for coast_time (filter_node.h); live,
 *   again every FILTER_NODE_LOST_REPEAT_US for late subscribers; in a log, once per silence.
 */
#ifndef NODE_SCHEDULE_H
#define NODE_SCHEDULE_H

#include <stdint.h>

#include "filter_node.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    int64_t tick_us;      /* > 0: --rate ticks every tick_us of capture time; 0: none */
    int repeat_lost;      /* 1: LOST again every FILTER_NODE_LOST_REPEAT_US while silent; 0: once */
    int64_t ticks_after;  /* capture time: ticks are due after it (the last tick, or the measurement) */
    int64_t ticks_from, ticks_from_arrival; /* capture and arrival time of the measurement the ticks follow */
    int ticks_over;       /* extrapolation refused: no tick until a new measurement is taken */
} node_schedule_t;

void node_schedule_init(node_schedule_t *s, int64_t tick_us, int repeat_lost);

/* The arrival time at which the next pose is due, or 0 when none will be without a new
 * measurement: the live loop's wake time. */
int64_t node_schedule_wake(node_schedule_t *s, const filter_node_t *node);

/* The next pose due by arrival time `now`, if any: 1 with *pose to publish and *due the arrival
 * time it was due at; 0 when none is. Called until it returns 0. */
int node_schedule_next(node_schedule_t *s, filter_node_t *node, int64_t now, hkf_head_pose_t *pose, int64_t *due);

#ifdef __cplusplus
}
#endif

#endif /* NODE_SCHEDULE_H */

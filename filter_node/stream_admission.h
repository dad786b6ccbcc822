/*
 * stream_admission.h - which measurements hkf-filter takes from its channel, by their
 * publisher, capture time and arrival time alone. Pure: no filter, no transport; the node
 * (filter_node.h) asks it and acts on the answer.
 *
 * The rules, in the order they are asked:
 * - a second model's measurement: one with the seq and capture time of one of the followed
 *   publisher's last STREAM_FRAME_IDS frames (one that passed the rules below), but not of the model
 *   the node follows, is that frame's measurement by a second model (filter_node.h): no other rule
 *   is asked of it, and it changes nothing here;
 * - one publisher: the node follows one estimator's frame counter. A measurement whose seq does
 *   not continue it (1 to STREAM_MAX_SEQ_STEP frames on) is from another publisher on the same
 *   channel and is refused, unless the followed one has been silent for STREAM_TIMEOUT_US (it
 *   stopped or restarted): then the new one is followed. Two estimators are never mixed;
 * - clock rule: a measurement whose capture-time step disagrees with its arrival-time step by more
 *   than STREAM_CLOCK_JUMP_US is a corrupt stamp or a clock jump, and is refused, so one bad stamp
 *   (e.g. INT64_MAX) cannot freeze the node. STREAM_RESYNC_MESSAGES such measurements in a row
 *   that agree with each other mean the capture clock really moved (either way): the last of them
 *   is taken on the new clock;
 * - stale rule: STREAM_RESYNC_MESSAGES measurements in a row older than the last one taken, that
 *   agree with each other, mean the last one taken was the odd one out (a forged stamp ahead of
 *   time, or the capture and receive clocks stepped back together, e.g. NTP): they are followed
 *   as after a clock jump. One message can hold tracking up for two frames at most;
 * - clock's end rule: a capture time later than STREAM_LATEST_UTIME (within a year of the int64
 *   clock's end, the year 294,246) is a corrupt stamp and refused as a clock jump, even as the first
 *   or as one of a run that agree: a track on such a clock could not stamp the LOST poses of a
 *   silence (filter_node_silence), and would be held as TRACKING;
 * - order: a capture time older than the last one taken is out of order, an equal one a duplicate.
 *
 * The arrival clock is the receive clock: a monotonic clock live, the log's event timestamps
 * offline. Stamps may be anything: differences are taken in double.
 */
#ifndef STREAM_ADMISSION_H
#define STREAM_ADMISSION_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define STREAM_CLOCK_JUMP_US 5000000LL /* 5 s: more than any gap a replay's pacing hides */
#define STREAM_RESYNC_MESSAGES 3
#define STREAM_MAX_SEQ_STEP 300            /* frames: 10 s at 30 fps of dropped frames */
#define STREAM_TIMEOUT_US 1000000LL        /* 1 s without the followed publisher */
#define STREAM_LATEST_UTIME (INT64_MAX - 31557600000000LL) /* us: a Julian year before the clock's end */
#define STREAM_FRAME_IDS 512               /* the followed publisher's last frames known by (seq, utime) */

typedef struct {
    int have_time;                    /* a measurement has been taken: */
    int64_t last_utime;               /* its capture time */
    int64_t last_arrival_utime;       /* its arrival time (stream_admission_took_arrival) */
    int have_stream;                  /* a publisher is followed: */
    int64_t stream_seq;               /* its last seq */
    int64_t stream_arrival_utime;     /* when that arrived */
    int jump_count;                   /* clock and stale rules: consistent refused stamps in a row */
    int64_t jump_utime, jump_arrival_utime; /* the last of them */
    struct {
        int known;
        int64_t seq, utime;
    } frames[STREAM_FRAME_IDS];       /* the followed publisher's frames, by seq modulo STREAM_FRAME_IDS */
} stream_admission_t;

typedef enum {
    STREAM_GO_ON,          /* publisher, clock and stale rules passed: the order rule is next */
    STREAM_NEW_CLOCK,      /* passed on a new capture clock: no time reference now; the track restarts */
    STREAM_OTHER_PUBLISHER,
    STREAM_CLOCK_JUMP,
    STREAM_STALE,          /* older than the last one taken */
    STREAM_SECOND_MODEL    /* a second model's measurement of one of the followed publisher's frames */
} stream_verdict_t;

typedef enum { STREAM_IN_ORDER, STREAM_OUT_OF_ORDER, STREAM_DUPLICATE } stream_order_t;

/* What became of one measurement (stream_admission_admit, stream_admission_admit_time). */
typedef struct {
    stream_verdict_t verdict; /* the publisher, clock and stale rules (STREAM_GO_ON from admit_time) */
    stream_order_t order;     /* the order rule, asked when they passed (verdict STREAM_GO_ON or STREAM_NEW_CLOCK) */
    int taken;                /* 1: in order and its values good, so the time reference now */
    double dt;                /* when taken: its step from the last one taken, s (0 for the first) */
} stream_admission_result_t;

void stream_admission_init(stream_admission_t *a);

/* One measurement as the node describes it to admission. */
typedef struct {
    int64_t seq, utime;    /* its publisher's frame counter, its capture time */
    int64_t arrival_utime; /* when it arrived (the receive clock) */
    int other_model;       /* 1: its model is not the one the node follows */
    int values_ok;         /* its angles are finite and in range, or it has none */
} stream_measurement_t;

/* The node's one call per measurement: the second model's rule, the publisher, clock and stale rules,
 * then, when they pass, the order rule, and a measurement in order with good values taken with its
 * arrival. */
stream_admission_result_t stream_admission_admit(stream_admission_t *a, const stream_measurement_t *m);

/* The same by capture time alone (no publisher, no arrival): the order rule, then taken when in order
 * with good values. */
stream_admission_result_t stream_admission_admit_time(stream_admission_t *a, int64_t utime, int values_ok);

/* The rules one by one (what stream_admission_admit asks, in its order): */

/* The publisher, clock and stale rules for a measurement (seq, capture time utime) that arrived at
 * arrival_utime. Following a new publisher, or counting refused stamps towards a resync, is noted
 * whatever the verdict. */
stream_verdict_t stream_admission_check(stream_admission_t *a, int64_t seq, int64_t utime, int64_t arrival_utime);

/* The order rule for capture time utime. */
stream_order_t stream_admission_order(const stream_admission_t *a, int64_t utime);

/* Takes capture time utime (in order) as the time reference; returns its step from the last one
 * taken in seconds (0 for the first). */
double stream_admission_take(stream_admission_t *a, int64_t utime);

/* The measurement taken last arrived at arrival_utime: the clock rule's reference, and the end of
 * any run of refused stamps. */
void stream_admission_took_arrival(stream_admission_t *a, int64_t arrival_utime);

/* 1 when a publisher is followed. */
static inline int stream_admission_following(const stream_admission_t *a)
{
    return a->have_stream;
}

#ifdef __cplusplus
}
#endif

#endif /* STREAM_ADMISSION_H */

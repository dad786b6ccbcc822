/* stream_admission.c - see stream_admission.h. */
#include "stream_admission.h"

#include <math.h>
#include <string.h>

void stream_admission_init(stream_admission_t *a)
{
    memset(a, 0, sizeof *a);
}

/* Capture-clock step minus arrival-clock step, in double: stamps may be anything. */
static double clock_skew_us(int64_t utime, int64_t arrival, int64_t ref_utime, int64_t ref_arrival)
{
    return ((double)utime - (double)ref_utime) - ((double)arrival - (double)ref_arrival);
}

/* One publisher: 1 when seq continues the followed estimator's frame counter, or when that one has
 * gone silent (then seq's publisher is followed); else 0. */
static int from_followed_publisher(stream_admission_t *a, int64_t seq, int64_t arrival_utime)
{
    if (a->have_stream) {
        const double step = (double)seq - (double)a->stream_seq;
        const int continues = step >= 1 && step <= (double)STREAM_MAX_SEQ_STEP;
        const int silent = (double)arrival_utime - (double)a->stream_arrival_utime > (double)STREAM_TIMEOUT_US;
        if (!continues && !silent) {
            return 0;
        }
    }
    a->have_stream = 1;
    a->stream_seq = seq;
    a->stream_arrival_utime = arrival_utime;
    return 1;
}

/* A stamp the time reference refuses (clock rule, or older than the last one taken).
 * STREAM_RESYNC_MESSAGES such in a row that agree with each other - each later than the one
 * before, with a capture step that matches the arrival step - mean the reference is what was
 * wrong: on the last of them the reference is dropped and 1 returned; before, 0. */
static int follows_refused_stamps(stream_admission_t *a, int64_t utime, int64_t arrival_utime)
{
    const int consistent = a->jump_count > 0 && utime > a->jump_utime &&
                           fabs(clock_skew_us(utime, arrival_utime, a->jump_utime, a->jump_arrival_utime)) <=
                               (double)STREAM_CLOCK_JUMP_US;
    a->jump_count = consistent ? a->jump_count + 1 : 1;
    a->jump_utime = utime;
    a->jump_arrival_utime = arrival_utime;
    if (a->jump_count < STREAM_RESYNC_MESSAGES) {
        return 0;
    }
    a->have_time = 0;
    return 1;
}

stream_verdict_t stream_admission_check(stream_admission_t *a, int64_t seq, int64_t utime, int64_t arrival_utime)
{
    int new_clock = 0;
    if (!from_followed_publisher(a, seq, arrival_utime)) {
        return STREAM_OTHER_PUBLISHER;
    }
    if (utime > STREAM_LATEST_UTIME) { /* the clock's end rule: a corrupt stamp, never a time reference */
        return STREAM_CLOCK_JUMP;
    }
    if (a->have_time && fabs(clock_skew_us(utime, arrival_utime, a->last_utime, a->last_arrival_utime)) >
                            (double)STREAM_CLOCK_JUMP_US) { /* the clock rule */
        if (!follows_refused_stamps(a, utime, arrival_utime)) {
            return STREAM_CLOCK_JUMP;
        }
        new_clock = 1;
    }
    if (a->have_time && utime < a->last_utime) { /* the stale rule */
        if (!follows_refused_stamps(a, utime, arrival_utime)) {
            return STREAM_STALE;
        }
        new_clock = 1;
    }
    return new_clock ? STREAM_NEW_CLOCK : STREAM_GO_ON;
}

stream_order_t stream_admission_order(const stream_admission_t *a, int64_t utime)
{
    if (a->have_time && utime < a->last_utime) {
        return STREAM_OUT_OF_ORDER;
    }
    if (a->have_time && utime == a->last_utime) {
        return STREAM_DUPLICATE;
    }
    return STREAM_IN_ORDER;
}

double stream_admission_take(stream_admission_t *a, int64_t utime)
{
    const double dt = a->have_time ? ((double)utime - (double)a->last_utime) * 1e-6 : 0.0;
    a->have_time = 1;
    a->last_utime = utime;
    return dt;
}

void stream_admission_took_arrival(stream_admission_t *a, int64_t arrival_utime)
{
    a->last_arrival_utime = arrival_utime;
    a->jump_count = 0;
}

stream_admission_result_t stream_admission_admit_time(stream_admission_t *a, int64_t utime, int values_ok)
{
    stream_admission_result_t r;
    r.verdict = STREAM_GO_ON;
    r.order = stream_admission_order(a, utime);
    r.taken = r.order == STREAM_IN_ORDER && values_ok;
    r.dt = r.taken ? stream_admission_take(a, utime) : 0.0;
    return r;
}

static int frame_slot(int64_t seq)
{
    return (int)((uint64_t)seq % STREAM_FRAME_IDS);
}

/* 1 when (seq, utime) is one of the followed publisher's last frames. */
static int known_frame(const stream_admission_t *a, int64_t seq, int64_t utime)
{
    const int i = frame_slot(seq);
    return a->frames[i].known && a->frames[i].seq == seq && a->frames[i].utime == utime;
}

static void note_frame(stream_admission_t *a, int64_t seq, int64_t utime)
{
    const int i = frame_slot(seq);
    a->frames[i].known = 1;
    a->frames[i].seq = seq;
    a->frames[i].utime = utime;
}

stream_admission_result_t stream_admission_admit(stream_admission_t *a, const stream_measurement_t *m)
{
    stream_admission_result_t r;
    const stream_verdict_t verdict = m->other_model && known_frame(a, m->seq, m->utime)
                                         ? STREAM_SECOND_MODEL
                                         : stream_admission_check(a, m->seq, m->utime, m->arrival_utime);
    memset(&r, 0, sizeof r);
    r.verdict = verdict;
    if (verdict != STREAM_GO_ON && verdict != STREAM_NEW_CLOCK) {
        return r;
    }
    note_frame(a, m->seq, m->utime); /* a frame of the followed publisher, taken or not */
    r = stream_admission_admit_time(a, m->utime, m->values_ok);
    r.verdict = verdict;
    if (r.taken) {
        stream_admission_took_arrival(a, m->arrival_utime);
    }
    return r;
}

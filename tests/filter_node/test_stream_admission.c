/*
 * test_stream_admission.c - which measurements the node takes (filter_node/stream_admission.c),
 * by publisher, capture time and arrival time alone: rule by rule, with no filter behind it.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "stream_admission.h"

#define T0 1700000000000000LL
#define FRAME_US 33333LL

/* One measurement as the node describes it: of the followed model unless other_model. */
static stream_admission_result_t admit(stream_admission_t *a, int64_t seq, int64_t utime, int64_t arrival,
                                       int other_model, int values_ok)
{
    const stream_measurement_t m = {seq, utime, arrival, other_model, values_ok};
    return stream_admission_admit(a, &m);
}

/* A measurement with good values as the node offers it (stream_admission_admit). Returns the verdict;
 * *dt the step taken (-1 when not taken). */
static stream_verdict_t offer(stream_admission_t *a, int64_t seq, int64_t utime, int64_t arrival, double *dt)
{
    const stream_admission_result_t r = admit(a, seq, utime, arrival, 0, 1);
    *dt = r.taken ? r.dt : -1.0;
    return r.verdict;
}

/* The node's one call: bad values are refused after the other rules (the reference and the clock rule's
 * arrival stay); by capture time alone, the order rule and the values decide. */
static void test_admit_in_one_call(void **state)
{
    stream_admission_t a;
    stream_admission_result_t r;
    (void)state;
    stream_admission_init(&a);
    r = admit(&a, 1, T0, 1000, 0, 1);
    assert_true(r.verdict == STREAM_GO_ON && r.order == STREAM_IN_ORDER && r.taken && r.dt == 0.0);
    r = admit(&a, 2, T0 + FRAME_US, 1000 + FRAME_US, 0, 0); /* bad values */
    assert_true(r.verdict == STREAM_GO_ON && r.order == STREAM_IN_ORDER && !r.taken);
    assert_true(a.last_utime == T0 && a.last_arrival_utime == 1000);
    r = admit(&a, 3, T0 + 2 * FRAME_US, 1000 + 2 * FRAME_US, 0, 1);
    assert_true(r.taken && r.dt > 0.0666 && r.dt < 0.0667);
    r = admit(&a, 4, T0 + 2 * FRAME_US, 1000 + 3 * FRAME_US, 0, 1);
    assert_true(r.verdict == STREAM_GO_ON && r.order == STREAM_DUPLICATE && !r.taken);
    r = admit(&a, 5000, T0 + 3 * FRAME_US, 1000 + 3 * FRAME_US, 0, 1); /* another publisher */
    assert_true(r.verdict == STREAM_OTHER_PUBLISHER && !r.taken);
    assert_true(a.last_utime == T0 + 2 * FRAME_US);
    stream_admission_init(&a);
    r = stream_admission_admit_time(&a, T0, 1);
    assert_true(r.verdict == STREAM_GO_ON && r.taken && r.dt == 0.0);
    r = stream_admission_admit_time(&a, T0 - 1, 1);
    assert_true(r.order == STREAM_OUT_OF_ORDER && !r.taken);
    r = stream_admission_admit_time(&a, T0 + FRAME_US, 0);
    assert_true(r.order == STREAM_IN_ORDER && !r.taken && a.last_utime == T0);
}

/* A second model's measurement is one of another model with the seq and capture time of a frame of the
 * followed publisher that passed the rules (taken or not): told apart before any other rule, it changes
 * nothing; the same frame of the followed model is a duplicate, a frame refused is not the publisher's. */
static void test_second_model_told_apart(void **state)
{
    stream_admission_t a;
    stream_admission_result_t r;
    (void)state;
    stream_admission_init(&a);
    assert_true(admit(&a, 0, 0, 1000, 1, 1).verdict == STREAM_GO_ON); /* nothing known, not even seq 0 at 0 */
    stream_admission_init(&a);
    assert_true(admit(&a, 1, T0, 1000, 1, 1).taken); /* nothing known: any model's first measurement */
    assert_true(admit(&a, 2, T0 + FRAME_US, 1000 + FRAME_US, 0, 1).taken);
    assert_true(admit(&a, 3, T0 + 2 * FRAME_US, 1000 + 2 * FRAME_US, 0, 0).verdict == STREAM_GO_ON); /* bad values */
    r = admit(&a, 2, T0 + FRAME_US, 1000 + 3 * FRAME_US, 1, 1);
    assert_true(r.verdict == STREAM_SECOND_MODEL && !r.taken);
    assert_true(admit(&a, 3, T0 + 2 * FRAME_US, 1000 + 3 * FRAME_US, 1, 1).verdict == STREAM_SECOND_MODEL);
    assert_true(a.stream_seq == 3 && a.last_utime == T0 + FRAME_US && a.last_arrival_utime == 1000 + FRAME_US);
    assert_true(admit(&a, 2, T0 + FRAME_US, 1000 + 3 * FRAME_US, 0, 1).verdict == STREAM_OTHER_PUBLISHER); /* seq again */
    assert_true(admit(&a, 2, T0 + 1, 1000 + 3 * FRAME_US, 1, 1).verdict == STREAM_OTHER_PUBLISHER); /* another stamp */
    assert_true(admit(&a, 5000, T0 + 3 * FRAME_US, 1000 + 3 * FRAME_US, 0, 1).verdict == STREAM_OTHER_PUBLISHER);
    assert_true(admit(&a, 5000, T0 + 3 * FRAME_US, 1000 + 3 * FRAME_US, 1, 1).verdict == STREAM_OTHER_PUBLISHER);
    assert_true(admit(&a, 4, T0 + 3 * FRAME_US, 1000 + 3 * FRAME_US, 0, 1).taken);
    assert_true(admit(&a, 4 + STREAM_FRAME_IDS, T0 + 3 * FRAME_US, 1000 + 3 * FRAME_US, 1, 1).verdict !=
                STREAM_SECOND_MODEL); /* its slot holds frame 4 */
}

/* A steady stream is taken frame by frame, its steps in seconds; the first step is 0. */
static void test_steady_stream_taken(void **state)
{
    stream_admission_t a;
    double dt;
    int i;
    (void)state;
    stream_admission_init(&a);
    assert_false(stream_admission_following(&a));
    assert_int_equal(offer(&a, 1, T0, 500, &dt), STREAM_GO_ON);
    assert_true(dt == 0.0);
    assert_true(stream_admission_following(&a));
    for (i = 1; i < 30; ++i) {
        assert_int_equal(offer(&a, 1 + i, T0 + i * FRAME_US, 500 + i * FRAME_US + (i % 3) * 2000, &dt), STREAM_GO_ON);
        assert_true(dt > 0.0333 && dt < 0.0334);
    }
    assert_true(a.have_time && a.last_utime == T0 + 29 * FRAME_US);
}

/* The order rule: an older capture time is out of order, an equal one a duplicate; neither moves the reference. */
static void test_order_rule(void **state)
{
    stream_admission_t a;
    double dt;
    (void)state;
    stream_admission_init(&a);
    assert_int_equal(stream_admission_order(&a, T0), STREAM_IN_ORDER); /* nothing taken: anything goes */
    (void)offer(&a, 1, T0, 0, &dt);
    assert_int_equal(stream_admission_order(&a, T0), STREAM_DUPLICATE);
    assert_int_equal(stream_admission_order(&a, T0 - 1), STREAM_OUT_OF_ORDER);
    assert_int_equal(stream_admission_order(&a, T0 + 1), STREAM_IN_ORDER);
    assert_true(a.last_utime == T0);
}

/* One publisher: a seq that does not continue the followed counter (a step of 1 to
 * STREAM_MAX_SEQ_STEP) is another publisher's, until the followed one has been silent for
 * STREAM_TIMEOUT_US; then the new one is followed. */
static void test_one_publisher(void **state)
{
    stream_admission_t a;
    double dt;
    (void)state;
    stream_admission_init(&a);
    (void)offer(&a, 10, T0, 0, &dt);
    assert_int_equal(offer(&a, 10, T0 + FRAME_US, FRAME_US, &dt), STREAM_OTHER_PUBLISHER);       /* a step of 0 */
    assert_int_equal(offer(&a, 9000, T0 + FRAME_US, FRAME_US, &dt), STREAM_OTHER_PUBLISHER);     /* far ahead */
    assert_int_equal(offer(&a, 10 + STREAM_MAX_SEQ_STEP, T0 + FRAME_US, FRAME_US, &dt), STREAM_GO_ON); /* the longest step */
    assert_int_equal(offer(&a, 11 + 2 * STREAM_MAX_SEQ_STEP, T0 + 2 * FRAME_US, 2 * FRAME_US, &dt),
                     STREAM_OTHER_PUBLISHER); /* one more */
    /* the followed publisher silent for just over STREAM_TIMEOUT_US: the other one is followed */
    assert_int_equal(offer(&a, 5, T0 + FRAME_US + STREAM_TIMEOUT_US + 1, FRAME_US + STREAM_TIMEOUT_US + 1, &dt),
                     STREAM_GO_ON);
    assert_true(a.stream_seq == 5 && dt > 1.0);
    assert_int_equal(offer(&a, 6, T0 + 2 * FRAME_US + STREAM_TIMEOUT_US, 2 * FRAME_US + STREAM_TIMEOUT_US, &dt),
                     STREAM_GO_ON);
}

/* The clock rule: one stamp whose capture step disagrees with its arrival step by more than
 * STREAM_CLOCK_JUMP_US is refused and leaves the reference alone, however far off it is. */
static void test_one_bad_stamp_refused(void **state)
{
    stream_admission_t a;
    double dt;
    int i;
    (void)state;
    stream_admission_init(&a);
    for (i = 0; i < 5; ++i) {
        (void)offer(&a, 1 + i, T0 + i * FRAME_US, i * FRAME_US, &dt);
    }
    assert_int_equal(offer(&a, 6, INT64_MAX, 5 * FRAME_US, &dt), STREAM_CLOCK_JUMP);
    assert_true(dt == -1.0 && a.last_utime == T0 + 4 * FRAME_US);
    /* a step just within the rule is taken */
    assert_int_equal(offer(&a, 7, T0 + 6 * FRAME_US + STREAM_CLOCK_JUMP_US, 6 * FRAME_US, &dt), STREAM_GO_ON);
}

/* The clock's end rule: stamps later than STREAM_LATEST_UTIME are refused as the first of a stream
 * and as a run that agrees; the latest allowed one is taken. */
static void test_clock_end_refused(void **state)
{
    stream_admission_t a;
    double dt;
    int i;
    (void)state;
    stream_admission_init(&a);
    for (i = 0; i < 2 * STREAM_RESYNC_MESSAGES; ++i) {
        assert_int_equal(offer(&a, 1 + i, INT64_MAX - 200000 + i * FRAME_US, i * FRAME_US, &dt), STREAM_CLOCK_JUMP);
        assert_int_equal(a.have_time, 0);
    }
    assert_int_equal(offer(&a, 20, STREAM_LATEST_UTIME, 20 * FRAME_US, &dt), STREAM_GO_ON);
    assert_true(a.last_utime == STREAM_LATEST_UTIME);
    assert_int_equal(offer(&a, 21, STREAM_LATEST_UTIME + 1, 21 * FRAME_US, &dt), STREAM_CLOCK_JUMP);
}

/* STREAM_RESYNC_MESSAGES jumped stamps in a row that agree with each other mean the clock moved: the
 * last of them comes with STREAM_NEW_CLOCK and no reference, and is taken with a step of 0. */
static void test_clock_jump_followed(void **state)
{
    stream_admission_t a;
    double dt;
    int i;
    (void)state;
    stream_admission_init(&a);
    (void)offer(&a, 1, T0, 0, &dt);
    for (i = 1; i < STREAM_RESYNC_MESSAGES; ++i) {
        assert_int_equal(offer(&a, 1 + i, T0 + 3600000000LL + i * FRAME_US, i * FRAME_US, &dt), STREAM_CLOCK_JUMP);
    }
    assert_int_equal(offer(&a, 1 + i, T0 + 3600000000LL + i * FRAME_US, i * FRAME_US, &dt), STREAM_NEW_CLOCK);
    assert_true(dt == 0.0 && a.last_utime == T0 + 3600000000LL + i * FRAME_US);
    assert_int_equal(offer(&a, 2 + i, T0 + 3600000000LL + (i + 1) * FRAME_US, (i + 1) * FRAME_US, &dt), STREAM_GO_ON);
}

/* Jumped stamps that disagree with each other (noise, not a clock) never move the reference; a
 * measurement taken between them starts the count again. */
static void test_inconsistent_stamps_never_followed(void **state)
{
    stream_admission_t a;
    double dt;
    int i;
    (void)state;
    stream_admission_init(&a);
    (void)offer(&a, 1, T0, 0, &dt);
    for (i = 1; i <= 20; ++i) { /* each 1 h off, alternately ahead and behind: the clock rule either way */
        const int64_t off = (i % 2 ? 1 : -1) * 3600000000LL;
        assert_int_equal(offer(&a, 2 * i, T0 + off + i * FRAME_US, i * FRAME_US, &dt), STREAM_CLOCK_JUMP);
        assert_int_equal(offer(&a, 2 * i + 1, T0 + i * FRAME_US, i * FRAME_US, &dt), STREAM_GO_ON);
    }
    assert_true(a.last_utime == T0 + 20 * FRAME_US);
    for (i = 0; i < STREAM_RESYNC_MESSAGES - 1; ++i) { /* two consistent jumps, a good one, two more */
        assert_int_equal(offer(&a, 100 + i, T0 + 7200000000LL + i * FRAME_US, 21 * FRAME_US + i * FRAME_US, &dt),
                         STREAM_CLOCK_JUMP);
    }
    assert_int_equal(offer(&a, 110, T0 + 23 * FRAME_US, 23 * FRAME_US, &dt), STREAM_GO_ON);
    for (i = 0; i < STREAM_RESYNC_MESSAGES - 1; ++i) {
        assert_int_equal(offer(&a, 111 + i, T0 + 7200000000LL + (24 + i) * FRAME_US, (24 + i) * FRAME_US, &dt),
                         STREAM_CLOCK_JUMP);
    }
}

/* The stale rule: one stamp older than the reference is refused; STREAM_RESYNC_MESSAGES such in a
 * row that agree mean the reference was the odd one out (a forged stamp ahead): followed. */
static void test_stale_rule(void **state)
{
    stream_admission_t a;
    double dt;
    int i;
    (void)state;
    stream_admission_init(&a);
    (void)offer(&a, 1, T0, 0, &dt);
    (void)offer(&a, 2, T0 + 4000000, FRAME_US, &dt); /* 4 s ahead: within the clock rule */
    for (i = 2; i < 1 + STREAM_RESYNC_MESSAGES; ++i) {
        assert_int_equal(offer(&a, 1 + i, T0 + i * FRAME_US, i * FRAME_US, &dt), STREAM_STALE);
    }
    assert_int_equal(offer(&a, 1 + i, T0 + i * FRAME_US, i * FRAME_US, &dt), STREAM_NEW_CLOCK);
    assert_true(dt == 0.0 && a.last_utime == T0 + i * FRAME_US);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_admit_in_one_call),
        cmocka_unit_test(test_second_model_told_apart),
        cmocka_unit_test(test_steady_stream_taken),
        cmocka_unit_test(test_order_rule),
        cmocka_unit_test(test_one_publisher),
        cmocka_unit_test(test_one_bad_stamp_refused),
        cmocka_unit_test(test_clock_end_refused),
        cmocka_unit_test(test_clock_jump_followed),
        cmocka_unit_test(test_inconsistent_stamps_never_followed),
        cmocka_unit_test(test_stale_rule),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

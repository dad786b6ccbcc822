/* second_model.c - see second_model.h. */
#include "second_model.h"

#include <math.h>
#include <string.h>

#include "pose_angles.h"

void second_model_init(second_model_t *s)
{
    memset(s, 0, sizeof *s);
    s->align_frames = FILTER_NODE_ALIGN_FRAMES;
    model_alignment_init(&s->alignment);
}

void second_model_forget_frames(second_model_t *s)
{
    s->frame_count = 0;
}

void second_model_forget_alignment(second_model_t *s)
{
    model_alignment_init(&s->alignment);
}

/* The kept frame i frames before the newest. */
static const second_model_frame_t *kept_back(const second_model_t *s, int i)
{
    return &s->frames[(s->frame_newest + FILTER_NODE_PAIR_FRAMES - i) % FILTER_NODE_PAIR_FRAMES];
}

/* The newest kept frame from the last prompt_us before utime with a second model's answer, or NULL. */
static const second_model_frame_t *newest_answered(const second_model_t *s, int64_t utime, int64_t prompt_us)
{
    int i;
    for (i = 0; i < s->frame_count; ++i) {
        const second_model_frame_t *frame = kept_back(s, i);
        if (utime - frame->utime > prompt_us) {
            return NULL;
        }
        if (frame->paired) {
            return frame;
        }
    }
    return NULL;
}

int second_model_answers(const second_model_t *s, int64_t utime, int64_t prompt_us)
{
    return newest_answered(s, utime, prompt_us) != NULL;
}

/* The largest difference between two readings over the axes (yaw's wrapped). */
static double largest_difference(const hkf_real_t a[3], const hkf_real_t b[3])
{
    double largest = 0.0;
    int axis;
    for (axis = 0; axis < 3; ++axis) {
        double d = (double)a[axis] - (double)b[axis];
        d = fabs(axis == HKF_AXIS_YAW ? pose_angle_wrap(d) : d);
        largest = d > largest ? d : largest;
    }
    return largest;
}

int second_model_prediction(const hkf_filter_t *f, hkf_real_t dt, hkf_real_t predicted[3])
{
    hkf_output_t out;
    int a;
    if (hkf_get_output(f, &out) != HKF_OK || (out.status != HKF_STATUS_TRACKING && out.status != HKF_STATUS_COASTING)) {
        return 0;
    }
    for (a = 0; a < 3; ++a) {
        predicted[a] = out.angle[a] + out.rate[a] * dt;
    }
    return 1;
}

int second_model_awaits(const second_model_t *s, const resolved_models_t *models, const hkf_real_t z[3],
                        const hkf_filter_t *track, hkf_real_t dt, int64_t utime, int64_t prompt_us)
{
    const int awaiting = s->frame_count > 0 && s->frames[s->frame_newest].awaited;
    const double from_yaw = (double)models->second_alone_from_yaw - (awaiting ? FILTER_NODE_AWAIT_HYSTERESIS : 0.0);
    hkf_real_t predicted[3];
    if (newest_answered(s, utime, prompt_us) == NULL) {
        return 0;
    }
    return fabs((double)z[HKF_AXIS_YAW]) >= from_yaw ||
           (second_model_prediction(track, dt, predicted) && largest_difference(z, predicted) >= FILTER_NODE_GROSS_DEG);
}

/* The index of the oldest kept frame waiting for the second's answer, or -1. */
static int oldest_waiting(const second_model_t *s)
{
    int i;
    for (i = s->frame_count - 1; i >= 0; --i) {
        const second_model_frame_t *frame = kept_back(s, i);
        if (frame->awaited && !frame->paired) {
            return (int)(frame - s->frames);
        }
    }
    return -1;
}

const second_model_frame_t *second_model_waiting(const second_model_t *s)
{
    const int index = oldest_waiting(s);
    return index < 0 ? NULL : &s->frames[index];
}

int64_t second_model_deadline(const second_model_t *s)
{
    const second_model_frame_t *frame = second_model_waiting(s);
    return frame == NULL ? 0 : frame->arrival + frame->wait_us;
}

void second_model_keep_frame(second_model_t *s, const hkf_head_pose_measurement_t *m, const second_model_step_t *step,
                             const hkf_filter_t *before, const hkf_calibration_t *calibration_before)
{
    const hkf_real_t *z = step->z;
    const double period_us = 1e6 * (double)step->dt, late_us = s->lateness_us + (double)FILTER_NODE_AWAIT_MARGIN_US;
    double wait_us = late_us > period_us ? late_us : period_us;
    second_model_frame_t *frame;
    s->frame_newest = (s->frame_newest + 1) % FILTER_NODE_PAIR_FRAMES;
    if (s->frame_count < FILTER_NODE_PAIR_FRAMES) {
        ++s->frame_count;
    }
    frame = &s->frames[s->frame_newest];
    memset(frame, 0, sizeof *frame);
    frame->seq = m->seq;
    frame->utime = m->utime;
    strncpy(frame->model, m->model ? m->model : "", sizeof frame->model - 1);
    frame->valid = z != NULL;
    frame->awaited = step->awaited;
    if (z != NULL) {
        memcpy(frame->z, z, sizeof frame->z);
    }
    frame->dt = step->dt;
    frame->arrival = step->arrival;
    wait_us = wait_us < (double)step->prompt_us ? wait_us : (double)step->prompt_us;
    frame->wait_us = wait_us > (double)FILTER_NODE_AWAIT_MIN_US ? (int64_t)(wait_us + 0.5) : FILTER_NODE_AWAIT_MIN_US;
    frame->xyz[0] = m->x;
    frame->xyz[1] = m->y;
    frame->xyz[2] = m->z;
    frame->before = *before;
    frame->calibration_before = *calibration_before;
}

/* The kept frame that m, another model's measurement, is of (the same seq and utime), or NULL. */
static second_model_frame_t *frame_of(second_model_t *s, const hkf_head_pose_measurement_t *m)
{
    int i;
    for (i = 0; i < s->frame_count; ++i) {
        second_model_frame_t *frame = &s->frames[(s->frame_newest + FILTER_NODE_PAIR_FRAMES - i) % FILTER_NODE_PAIR_FRAMES];
        if (frame->seq == m->seq && frame->utime == m->utime) {
            return strncmp(frame->model, m->model ? m->model : "", sizeof frame->model) != 0 ? frame : NULL;
        }
    }
    return NULL;
}

/* Where the first model measures a large turn, the second's measurement is taken alone. */
static int first_set_aside(const resolved_models_t *models, const second_model_frame_t *frame)
{
    return frame->valid && fabs((double)frame->z[HKF_AXIS_YAW]) >= (double)models->second_alone_from_yaw;
}

/* One kept frame's filter step on f, as the node made it, with the frame's second measurement if it
 * has one (and is not a gross error); *taken is the measurement the step took first (NULL: none), for the
 * calibration. A first measurement that waited is taken once the answer came as a gross error. */
static int redo_filter_step(const resolved_models_t *models, hkf_filter_t *f, const second_model_frame_t *frame,
                            const hkf_real_t **taken)
{
    *taken = frame->valid && (!frame->awaited || frame->paired) ? frame->z : NULL;
    if (frame->paired && frame->gross != SECOND_MODEL_GROSS_SECOND) {
        const resolved_model_t *second = resolved_models_find(models, frame->second_model);
        const int first = frame->valid && frame->gross != SECOND_MODEL_GROSS_FIRST && !first_set_aside(models, frame);
        *taken = first ? frame->z : frame->z2;
        return hkf_update_pair_prepared(f, first ? frame->z : NULL, frame->z2, &second->noise, frame->dt, NULL);
    }
    if (*taken != NULL) {
        return hkf_update(f, frame->z, frame->dt, NULL);
    }
    return hkf_predict(f, frame->dt, NULL); /* no face, or z awaiting the second's measurement */
}

/* One kept frame's step on f and its calibration c, as the node made it. */
static int redo_step(const resolved_models_t *models, hkf_filter_t *f, hkf_calibration_t *c,
                     const second_model_frame_t *frame)
{
    const hkf_real_t *taken;
    const int result = redo_filter_step(models, f, frame, &taken);
    if (result == HKF_ERROR_NOT_INITIALIZED) {
        return HKF_OK; /* no track yet, as the node found */
    }
    return result != HKF_OK ? result : hkf_calibration_update(c, f, taken, frame->dt);
}

/* Which of a paired frame's readings (z, and z2 on the first model's frame) is a gross error
 * (FILTER_NODE_GROSS_DEG), against the track's prediction for the frame from the filter before its step. */
static int gross_reading(const second_model_frame_t *frame)
{
    hkf_real_t predicted[3];
    int first_far, second_far;
    if (!frame->valid || !second_model_prediction(&frame->before, frame->dt, predicted) ||
        largest_difference(frame->z, frame->z2) < FILTER_NODE_GROSS_DEG) {
        return SECOND_MODEL_GROSS_NONE;
    }
    first_far = largest_difference(frame->z, predicted) >= FILTER_NODE_GROSS_DEG;
    second_far = largest_difference(frame->z2, predicted) >= FILTER_NODE_GROSS_DEG;
    return first_far == second_far ? SECOND_MODEL_GROSS_NONE
           : second_far           ? SECOND_MODEL_GROSS_SECOND
                                  : SECOND_MODEL_GROSS_FIRST;
}

/* A second model's angles moved onto the first model's frame by the curve (model_alignment.h), into z2. */
static void aligned_by_curve(const second_model_t *s, const double second[3], hkf_real_t z2[3])
{
    int a;
    for (a = 0; a < 3; ++a) {
        double v = second[a] + model_alignment_correction(&s->alignment, a, second[a]);
        if (a == HKF_AXIS_YAW) {
            v = pose_angle_wrap(v);
        }
        z2[a] = (hkf_real_t)(v < HKF_MAX_ABS_ANGLE ? (v > -HKF_MAX_ABS_ANGLE ? v : -HKF_MAX_ABS_ANGLE) : HKF_MAX_ABS_ANGLE);
    }
}

/* The frame's second measurement (frame->z2) moved onto the first model's frame (model_alignment.h): judged
 * for a gross error on the curve so far (frame->gross); where neither reading is one, the curve learns from
 * this frame's difference wherever the first measured, at a large turn too (the pose is in the first model's
 * frame, and the curve carries it across the first's reach without a step); then moved by the curve. */
static void align_second(second_model_t *s, second_model_frame_t *frame)
{
    double difference[3], second[3];
    int a;
    for (a = 0; a < 3; ++a) {
        second[a] = (double)frame->z2[a];
        difference[a] = (double)frame->z[a] - second[a];
    }
    difference[HKF_AXIS_YAW] = pose_angle_wrap(difference[HKF_AXIS_YAW]);
    model_alignment_learn(&s->alignment, frame->second_model, second, NULL, s->align_frames); /* its model */
    aligned_by_curve(s, second, frame->z2);
    frame->gross = gross_reading(frame);
    if (frame->valid && frame->gross == SECOND_MODEL_GROSS_NONE) {
        model_alignment_learn(&s->alignment, frame->second_model, second, difference, s->align_frames);
    }
    aligned_by_curve(s, second, frame->z2);
}

/* The kept frames' steps made again from `frame` on (its own step first) into `track`, with what each holds
 * now; the later frames keep the filter before their step. 0 when a step failed (cannot happen: each was
 * made before): then nothing changes. */
static int replay_from(second_model_t *s, const resolved_models_t *models, second_model_frame_t *frame,
                       second_model_track_t *track)
{
    hkf_filter_t f, before[FILTER_NODE_PAIR_FRAMES];
    hkf_calibration_t c, calibration_before[FILTER_NODE_PAIR_FRAMES];
    const int index = (int)(frame - s->frames);
    const int count = (s->frame_newest - index + FILTER_NODE_PAIR_FRAMES) % FILTER_NODE_PAIR_FRAMES + 1;
    int i;
    f = frame->before;
    c = frame->calibration_before;
    for (i = 0; i < count; ++i) {
        before[i] = f;
        calibration_before[i] = c;
        if (redo_step(models, &f, &c, &s->frames[(index + i) % FILTER_NODE_PAIR_FRAMES]) != HKF_OK) {
            return 0;
        }
    }
    for (i = 1; i < count; ++i) {
        s->frames[(index + i) % FILTER_NODE_PAIR_FRAMES].before = before[i];
        s->frames[(index + i) % FILTER_NODE_PAIR_FRAMES].calibration_before = calibration_before[i];
    }
    (void)hkf_get_output(count > 1 ? &before[1] : &f, &track->posterior); /* the frame's own step, before the later ones */
    *track->filter = f;
    *track->calibration = c;
    return 1;
}

/* An answer's lateness behind its frame's first measurement into the running quantile: up by q steps when
 * above it, down by 1 - q steps when below (the quantile where the two balance); the first sets it. */
static void learn_lateness(second_model_t *s, double late_us)
{
    const double q = FILTER_NODE_LATENESS_QUANTILE, step = FILTER_NODE_LATENESS_STEP_US;
    if (!(late_us >= 0.0)) {
        return; /* an answer "before" its frame: a clock step; nothing to learn */
    }
    if (s->lateness_us <= 0.0) {
        s->lateness_us = late_us;
    } else {
        s->lateness_us += late_us > s->lateness_us ? q * step : -(1.0 - q) * step;
    }
    if (s->lateness_us < 0.0) {
        s->lateness_us = 0.0;
    }
}

/* m, arrived at `arrival`, fused into its kept frame `frame` (second_model_take). */
static int fuse(second_model_t *s, const resolved_models_t *models, second_model_frame_t *frame,
                const hkf_head_pose_measurement_t *m, int64_t arrival, second_model_track_t *track)
{
    if (frame->paired) { /* one second measurement per frame */
        return 0;
    }
    frame->paired = 1;
    learn_lateness(s, (double)(arrival - frame->arrival));
    strncpy(frame->second_model, m->model ? m->model : "", sizeof frame->second_model - 1);
    frame->z2[0] = m->pitch;
    frame->z2[1] = m->yaw;
    frame->z2[2] = m->roll;
    align_second(s, frame);
    if (!replay_from(s, models, frame, track)) {
        frame->paired = 0; /* cannot happen (the steps were made before, z2 is checked): nothing changes */
        return 0;
    }
    return 1;
}

int second_model_take(second_model_t *s, const resolved_models_t *models, const hkf_head_pose_measurement_t *m,
                      int64_t arrival, second_model_track_t *track, const second_model_frame_t **frame)
{
    second_model_frame_t *kept = frame_of(s, m);
    *frame = kept;
    return kept != NULL && track->filter != NULL && fuse(s, models, kept, m, arrival, track);
}

int second_model_settle(second_model_t *s, const resolved_models_t *models, second_model_track_t *track,
                        const second_model_frame_t **frame)
{
    const int index = oldest_waiting(s);
    second_model_frame_t *waiting = index < 0 ? NULL : &s->frames[index];
    *frame = waiting;
    if (waiting == NULL) {
        return 0;
    }
    waiting->awaited = 0; /* its own measurement makes its step */
    if (!replay_from(s, models, waiting, track)) {
        waiting->awaited = 1; /* cannot happen: nothing changes */
        return 0;
    }
    return 1;
}

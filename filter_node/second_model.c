/* second_model.c - see second_model.h. */
#include "second_model.h"

#include <math.h>
#include <string.h>

#include "pose_angles.h"

void second_model_init(second_model_t *s)
{
    memset(s, 0, sizeof *s);
    s->align_frames = FILTER_NODE_ALIGN_FRAMES;
}

void second_model_forget_frames(second_model_t *s)
{
    s->frame_count = 0;
}

void second_model_keep_frame(second_model_t *s, const hkf_head_pose_measurement_t *m, const hkf_real_t z[3],
                             hkf_real_t dt, const hkf_filter_t *before, const hkf_calibration_t *calibration_before)
{
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
    if (z != NULL) {
        memcpy(frame->z, z, sizeof frame->z);
    }
    frame->dt = dt;
    frame->before = *before;
    frame->calibration_before = *calibration_before;
    second_model_note_frame(s, m->seq, m->utime);
}

static int frame_id_slot(int64_t seq)
{
    return (int)((uint64_t)seq % FILTER_NODE_FRAME_IDS);
}

void second_model_note_frame(second_model_t *s, int64_t seq, int64_t utime)
{
    const int slot = frame_id_slot(seq);
    s->frame_ids[slot].seq = seq;
    s->frame_ids[slot].utime = utime;
}

/* The index of the kept frame whose second measurement m is (same seq and utime, another model), or -1. */
static int frame_of(const second_model_t *s, const hkf_head_pose_measurement_t *m)
{
    int i;
    for (i = 0; i < s->frame_count; ++i) {
        const int index = (s->frame_newest + FILTER_NODE_PAIR_FRAMES - i) % FILTER_NODE_PAIR_FRAMES;
        const second_model_frame_t *frame = &s->frames[index];
        if (frame->seq == m->seq && frame->utime == m->utime) {
            return strncmp(frame->model, m->model ? m->model : "", sizeof frame->model) != 0 ? index : -1;
        }
    }
    return -1;
}

/* Its seq and utime are those of one of the followed publisher's last frames,
 * its model another. (Another publisher's seq and utime are not.) */
static int too_late(const second_model_t *s, const hkf_head_pose_measurement_t *m, const char *first_model)
{
    const int slot = frame_id_slot(m->seq);
    return s->frame_ids[slot].seq == m->seq && s->frame_ids[slot].utime == m->utime && m->utime != 0 &&
           strncmp(first_model, m->model ? m->model : "", NODE_MODEL_NAME_MAX) != 0;
}

int second_model_route(const second_model_t *s, const hkf_head_pose_measurement_t *m, const char *first_model,
                       int following)
{
    const int index = frame_of(s, m);
    if (index >= 0) {
        return index;
    }
    return following && too_late(s, m, first_model) ? SECOND_MODEL_TOO_LATE : SECOND_MODEL_NOT_SECOND;
}

/* Where the first model measures a large turn, the second's measurement is taken alone. */
static int first_set_aside(const resolved_models_t *models, const second_model_frame_t *frame)
{
    return frame->valid && fabs((double)frame->z[HKF_AXIS_YAW]) >= (double)models->second_alone_from_yaw;
}

/* One kept frame's filter step on f, as the node made it, with the frame's second measurement if it
 * has one; *taken is the measurement the step took first (NULL: none), for the calibration. */
static int redo_filter_step(const resolved_models_t *models, hkf_filter_t *f, const second_model_frame_t *frame,
                            const hkf_real_t **taken)
{
    *taken = frame->valid ? frame->z : NULL;
    if (frame->paired) {
        int known;
        const resolved_model_t *second = resolved_models_find(models, frame->second_model, &known);
        const int first = frame->valid && !first_set_aside(models, frame);
        *taken = first ? frame->z : frame->z2;
        return hkf_update_pair_prepared(f, first ? frame->z : NULL, frame->z2, &second->noise, frame->dt, NULL);
    }
    if (frame->valid) {
        return hkf_update(f, frame->z, frame->dt, NULL);
    }
    return hkf_predict(f, frame->dt, NULL);
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

/* The frame's second measurement (frame->z2) moved onto the first model's
 * frame: plus the running mean of (first - second) over the frames both
 * measured, updated with this frame's difference when the first measured it too. */
static void align_second(second_model_t *s, const resolved_models_t *models, second_model_frame_t *frame)
{
    int a;
    if (strncmp(s->model, frame->second_model, sizeof s->model) != 0) {
        /* another second model: start over */
        strncpy(s->model, frame->second_model, sizeof s->model - 1);
        s->offset_frames = 0;
        memset(s->offset, 0, sizeof s->offset);
    }
    /* learnt only where the first model is trusted (where the two are fused): at a large turn the
     * mesh's own error is what the second model is there to avoid */
    if (frame->valid && s->align_frames > 0 && !first_set_aside(models, frame)) {
        const long n = s->offset_frames < s->align_frames ? s->offset_frames + 1 : s->align_frames;
        for (a = 0; a < 3; ++a) {
            double difference = (double)frame->z[a] - (double)frame->z2[a];
            if (a == HKF_AXIS_YAW) {
                difference = pose_angle_wrap(difference);
            }
            s->offset[a] += (hkf_real_t)((difference - (double)s->offset[a]) / (double)n);
        }
        s->offset_frames = n;
    }
    for (a = 0; a < 3; ++a) {
        double v = (double)frame->z2[a] + (double)s->offset[a];
        if (a == HKF_AXIS_YAW) {
            v = pose_angle_wrap(v);
        }
        frame->z2[a] =
            (hkf_real_t)(v < HKF_MAX_ABS_ANGLE ? (v > -HKF_MAX_ABS_ANGLE ? v : -HKF_MAX_ABS_ANGLE) : HKF_MAX_ABS_ANGLE);
    }
}

int second_model_fuse(second_model_t *s, const resolved_models_t *models, int index, const hkf_head_pose_measurement_t *m,
                      hkf_filter_t *filter, hkf_calibration_t *calibration)
{
    hkf_filter_t f, before[FILTER_NODE_PAIR_FRAMES];
    hkf_calibration_t c, calibration_before[FILTER_NODE_PAIR_FRAMES];
    second_model_frame_t *frame = &s->frames[index];
    const int count = (s->frame_newest - index + FILTER_NODE_PAIR_FRAMES) % FILTER_NODE_PAIR_FRAMES + 1;
    int i;
    if (frame->paired) { /* one second measurement per frame */
        return 0;
    }
    frame->paired = 1;
    strncpy(frame->second_model, m->model ? m->model : "", sizeof frame->second_model - 1);
    frame->z2[0] = m->pitch;
    frame->z2[1] = m->yaw;
    frame->z2[2] = m->roll;
    align_second(s, models, frame);
    f = frame->before;
    c = frame->calibration_before;
    for (i = 0; i < count; ++i) {
        before[i] = f;
        calibration_before[i] = c;
        if (redo_step(models, &f, &c, &s->frames[(index + i) % FILTER_NODE_PAIR_FRAMES]) != HKF_OK) {
            frame->paired = 0; /* cannot happen (the steps were made before, z2 is checked): nothing changes */
            return 0;
        }
    }
    for (i = 1; i < count; ++i) {
        s->frames[(index + i) % FILTER_NODE_PAIR_FRAMES].before = before[i];
        s->frames[(index + i) % FILTER_NODE_PAIR_FRAMES].calibration_before = calibration_before[i];
    }
    *filter = f;
    *calibration = c;
    return 1;
}

/*
 * second_model.h - two models on one channel, the node's side (filter_node.h
 * states the rules): the last frames' filter steps kept in a ring, a second
 * model's measurement of one of them fused there (hkf_update_pair_prepared) and the
 * frames after it redone, and the second model moved onto the first's frame
 * by the running mean of their difference.
 */
#ifndef SECOND_MODEL_H
#define SECOND_MODEL_H

#include <stdint.h>

#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"
#include "hkf_head_pose_measurement_t.h"
#include "node_config.h"
#include "resolved_models.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FILTER_NODE_PAIR_FRAMES 32 /* frames kept for a late second measurement: 0.53 s at 60 fps */
#define FILTER_NODE_ALIGN_FRAMES 60 /* frames both models measured that the second's offset averages */
#define FILTER_NODE_FRAME_IDS 512   /* (seq, utime) of the followed publisher's last frames: a second measurement
                                       too late to fuse is told from another publisher's by them */

/* One frame's filter step, kept so that a second model's measurement of it can
 * be fused afterwards. */
typedef struct {
    int64_t seq, utime;                      /* the frame */
    char model[NODE_MODEL_NAME_MAX];         /* the first model (the filter's) */
    int valid;                               /* the first model measured z */
    hkf_real_t z[3], dt;
    int paired;                              /* a second model measured z2: */
    char second_model[NODE_MODEL_NAME_MAX];
    hkf_real_t z2[3];
    hkf_filter_t before;                     /* the filter before this frame's step */
    hkf_calibration_t calibration_before;    /* and the noise calibration beside it */
} second_model_frame_t;

typedef struct {
    second_model_frame_t frames[FILTER_NODE_PAIR_FRAMES]; /* the last frames' steps, a ring */
    int frame_count, frame_newest;
    struct {
        int64_t seq, utime;
    } frame_ids[FILTER_NODE_FRAME_IDS];     /* by seq modulo FILTER_NODE_FRAME_IDS */
    long align_frames;                      /* FILTER_NODE_ALIGN_FRAMES (0: no alignment) */
    char model[NODE_MODEL_NAME_MAX];        /* the second model the offset is for */
    hkf_real_t offset[3];                   /* first minus second, deg, running mean */
    long offset_frames;                     /* frames it has averaged */
} second_model_t;

/* Empty, aligning over FILTER_NODE_ALIGN_FRAMES. */
void second_model_init(second_model_t *s);

/* Forgets the kept frames (a restart, a command, a new clock); the offset stays. */
void second_model_forget_frames(second_model_t *s);

/* Keeps the step made from `before` (and its calibration) for frame m: z (NULL: no face), dt; the frame
 * is noted as second_model_note_frame notes one. */
void second_model_keep_frame(second_model_t *s, const hkf_head_pose_measurement_t *m, const hkf_real_t z[3],
                             hkf_real_t dt, const hkf_filter_t *before, const hkf_calibration_t *calibration_before);

/* Notes a frame of the followed publisher that was not stepped (to tell a too-late second measurement). */
void second_model_note_frame(second_model_t *s, int64_t seq, int64_t utime);

#define SECOND_MODEL_TOO_LATE (-1)   /* a second measurement of a followed frame no longer kept */
#define SECOND_MODEL_NOT_SECOND (-2) /* the first model's measurement (or another publisher's) */

/* Which frame m is a second model's measurement of: the index of the kept frame with its seq and utime
 * and another model; SECOND_MODEL_TOO_LATE when, following a publisher (`following`), m's seq and utime
 * are one of its last frames' and its model is not first_model (the filter's); else
 * SECOND_MODEL_NOT_SECOND. */
int second_model_route(const second_model_t *s, const hkf_head_pose_measurement_t *m, const char *first_model,
                       int following);

/* Fuses m, the second measurement of kept frame `index`, into *filter (and
 * its *calibration): that frame's step again with both (the second model's R
 * and the pair's rule from `models`), then the steps of the frames after it. Returns 1 when fused,
 * 0 when not (the frame already has one). */
int second_model_fuse(second_model_t *s, const resolved_models_t *models, int index, const hkf_head_pose_measurement_t *m,
                      hkf_filter_t *filter, hkf_calibration_t *calibration);

#ifdef __cplusplus
}
#endif

#endif /* SECOND_MODEL_H */

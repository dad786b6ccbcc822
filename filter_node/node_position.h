/*
 * node_position.h - the head's position at the node (filter_node.h states the rules): the followed
 * model's positions through libhkf's position filter (hkf/hkf_position.h) with R scaled by the
 * model's position_r_scale and the noise calibration beside it (hkf/hkf_calibration.h), a second
 * model's standing in where the first measured none in a kept frame (second_model.h), moved onto the
 * first's by the running mean of their difference over the last FILTER_NODE_POSITION_ALIGN frames both
 * measured (model_offset.h: a face box's distance differs from the mesh's by a steady few per cent, 2-4
 * cm at 60 cm, which would otherwise read as a lean each time the mesh drops out), and the filtered
 * position at a pose's time.
 */
#ifndef NODE_POSITION_H
#define NODE_POSITION_H

#include <stdint.h>

#include "hkf/hkf_calibration.h"
#include "hkf/hkf_position.h"
#include "hkf_head_pose_measurement_t.h"
#include "hkf_head_pose_t.h"
#include "model_offset.h"
#include "second_model.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FILTER_NODE_MIN_Z 1.0f /* cm: the nearest position taken and published (z = 0: not measured) */
#define FILTER_NODE_POSITION_ALIGN 60    /* frames both measured that the second's offset averages */
#define FILTER_NODE_POSITION_MIN_ALIGN 5 /* frames both measured before the second's positions are used */

typedef struct {
    hkf_position_filter_t filter; /* the followed model's measurements (z > 0) */
    hkf_calibration_t calibration; /* its noise level n, measured from the positions it took */
    int64_t utime;                /* capture time of the last position taken */
    model_offset_t offset;        /* the second model's, cm (model_offset.h) */
} node_position_t;

/* What a measurement's position became (node_position_take_first, _take_second). */
typedef enum {
    NODE_POSITION_NONE = 0,  /* it carried none (no face, z = 0), or not one to use now */
    NODE_POSITION_TAKEN = 1, /* into the filter */
    NODE_POSITION_GATED = 2, /* refused by the filter's outlier gate */
    NODE_POSITION_BAD = 3    /* non-finite, z < FILTER_NODE_MIN_Z (but not 0), beyond the range */
} node_position_result_t;

/* Empty, with the position filter's and its calibration's settings: HKF_OK or hkf_position_init's or
 * hkf_calibration_init_position's error. */
int node_position_init(node_position_t *p, const hkf_position_settings_t *settings,
                       const hkf_calibration_settings_t *calibration);

/* The first model's frame m: its position (R times r_scale) into the filter. */
node_position_result_t node_position_take_first(node_position_t *p, const hkf_head_pose_measurement_t *m,
                                                float r_scale);

/* A second model's measurement m of kept frame `frame` (NULL: a frame no longer kept): where the first
 * model measured a position there, the offset learns from the pair; where it measured none, m's
 * position (R times r_scale) stands in once the offset has averaged FILTER_NODE_POSITION_MIN_ALIGN frames. */
node_position_result_t node_position_take_second(node_position_t *p, const hkf_head_pose_measurement_t *m,
                                                 const second_model_frame_t *frame, float r_scale);

/* The filtered position at capture time utime into pose (hkf_position_extrapolate): the last one
 * taken moved on by its rate for up to the position's max_dt, then held with rate 0 while its
 * variance grows; within the range the node accepts. Untouched (0) before the first. */
void node_position_fill(const node_position_t *p, int64_t utime, hkf_head_pose_t *pose);

/* The track starts again with the next position; the offset and the measured noise stay. */
void node_position_restart(node_position_t *p);

/* RECENTER: the centre set on the position published at utime, so that it reads 0 after. */
void node_position_recenter(node_position_t *p, int64_t utime);

/* RESET: nothing of before stays (the models' offset too). */
void node_position_reset(node_position_t *p);

#ifdef __cplusplus
}
#endif

#endif /* NODE_POSITION_H */

/*
 * model_offset.h - a second model moved onto the first's frame (filter_node.h states the rule): two
 * models disagree by a steady few degrees, and a face box's distance differs from the mesh's by a
 * steady few per cent, so the second's measurements take the running mean of first minus second over
 * the last frames both measured. The mean starts again when the second model changes. One rule for
 * the angles (second_model.h) and the position (node_position.h).
 */
#ifndef MODEL_OFFSET_H
#define MODEL_OFFSET_H

#include "hkf/hkf_real.h"
#include "node_config.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    char model[NODE_MODEL_NAME_MAX]; /* the second model the mean is for */
    hkf_real_t offset[3];            /* first minus second, the running mean */
    long frames;                     /* the frames it averages (at most the `most` it learnt with) */
} model_offset_t;

/* No second model yet: no offset. */
void model_offset_init(model_offset_t *o);

/* Second model `model`'s measurement of a frame (another model than before: the mean starts again);
 * difference is first minus second there, or NULL when the first did not measure the frame or is not
 * trusted there. The difference joins the running mean over the last `most` frames (0: never). */
void model_offset_learn(model_offset_t *o, const char *model, const double difference[3], long most);

#ifdef __cplusplus
}
#endif

#endif /* MODEL_OFFSET_H */

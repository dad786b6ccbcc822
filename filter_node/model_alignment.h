/*
 * model_alignment.h - a second model's angles moved onto the first's frame (filter_node.h states the
 * rule). Two models disagree by an amount that changes with the turn: on the yaw truth renders the face
 * mesh reads 0.87 of a turn and WHENet 1.31, and the mesh's reading flattens towards its reach
 * (docs/evaluation.md), so neither a constant offset nor a line aligns them. Per axis, the difference
 * d(x) = first - second, as a function of the second's own angle x on that axis, is learnt as a
 * piecewise-linear curve on knots every MODEL_ALIGNMENT_KNOT_STEP deg: each frame both models measured
 * teaches the two knots around its x, in proportion to its nearness (linear interpolation weights), a
 * running mean over about the last `most` frames each knot learnt from (docs/programs.md derives it).
 * The curve is read by the same interpolation; a knot nothing taught takes the nearest taught knot's
 * value, so beyond the first model's reach the second keeps the disagreement last seen at its edge: the
 * hand-over across the reach has no step. The mapped angle is x + d(x).
 */
#ifndef MODEL_ALIGNMENT_H
#define MODEL_ALIGNMENT_H

#include "node_config.h"

#ifdef __cplusplus
extern "C" {
#endif

#define MODEL_ALIGNMENT_KNOT_STEP 10.0 /* deg between knots */
#define MODEL_ALIGNMENT_REACH 90.0     /* deg: knots from -this to +this; x beyond counts as at the end */
#define MODEL_ALIGNMENT_KNOTS 19       /* 2 * REACH / KNOT_STEP + 1 */

typedef struct {
    char model[NODE_MODEL_NAME_MAX];              /* the second model the curve is for */
    double d[3][MODEL_ALIGNMENT_KNOTS];           /* first minus second at each knot, deg */
    double weight[3][MODEL_ALIGNMENT_KNOTS];      /* the weight each knot averages (at most `most`) */
    long frames;                                  /* frames learnt from */
} model_alignment_t;

/* No second model yet: no correction. */
void model_alignment_init(model_alignment_t *a);

/* Second model `model`'s angles `second` of a frame (another model than before: the curve starts again),
 * and first minus second there (NULL when the first did not measure the frame; the yaw's wrapped into
 * +-180). Each axis teaches its two knots around its x, over about the last `most` frames (0: never). */
void model_alignment_learn(model_alignment_t *a, const char *model, const double second[3],
                           const double difference[3], long most);

/* The correction d(x) on `axis` for the second's angle x (deg): what to add to move it onto the first's. */
double model_alignment_correction(const model_alignment_t *a, int axis, double x);

#ifdef __cplusplus
}
#endif

#endif /* MODEL_ALIGNMENT_H */

/*
 * model_alignment.h - a second model's angles moved onto the first's frame (filter_node.h states the
 * rule). Two models disagree by an amount that changes with the turn: on the yaw truth renders the face
 * mesh reads 0.87 of a turn and WHENet 1.31, and the mesh's reading flattens towards its reach
 * (docs/evaluation.md), so neither a constant offset nor a line aligns them. Per axis, the difference
 * d(x) = first - second, as a function of the second's own angle x on that axis, is learnt as a
 * piecewise-linear curve on knots every MODEL_ALIGNMENT_KNOT_STEP deg, fitted by least squares: each
 * frame both models measured is one residual d - ((1 - s) d_k + s d_k+1), x being the share s of the way
 * from knot k to k+1, its weight forgotten over about the last `most` such frames; the knots minimise the
 * weighted squares plus MODEL_ALIGNMENT_SMOOTHING times the squared steps between neighbours (tridiagonal
 * normal equations, solved after each frame; docs/programs.md derives it). The fit goes through a held
 * turn's own disagreement, where a mean per knot would mix in the frames either side of it. A knot
 * nothing taught follows its taught neighbours (flat beyond the last, linear between two), so beyond the
 * first model's reach the second keeps the disagreement last seen at its edge: the hand-over across the
 * reach has no step. The mapped angle is x + d(x).
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
#define MODEL_ALIGNMENT_SMOOTHING 0.1 /* weight of a squared step between knots, against a frame's 1: it
                                       * settles the knots the frames leave open, and damps those few frames
                                       * taught (chosen on the tuning heads over 1e-4 to 1: docs/programs.md) */

/* The most the curve moves a second model's angle x: MODEL_ALIGNMENT_MOST_AT_0 + MODEL_ALIGNMENT_MOST_SLOPE |x|
 * deg, the models' plausible disagreement. On the yaw truth renders the mesh reads 0.87 of a turn and WHENet
 * 1.31: first - second = -0.34 x (30 deg at x = 90); at the centre the two agree within their AFLW2000
 * errors (3-4 deg each in pitch, up to 6 at 30-60 deg of yaw: docs/estimator.md), twice that is the 10 deg. A curve learnt from a forged or broken second model moves the view by no more. */
#define MODEL_ALIGNMENT_MOST_AT_0 10.0
#define MODEL_ALIGNMENT_MOST_SLOPE 0.4

typedef struct {
    char model[NODE_MODEL_NAME_MAX];              /* the second model the curve is for */
    double d[3][MODEL_ALIGNMENT_KNOTS];           /* first minus second at each knot, deg (the fit) */
    double diagonal[3][MODEL_ALIGNMENT_KNOTS];    /* the normal equations: sum of w_k^2 over the frames, */
    double beside[3][MODEL_ALIGNMENT_KNOTS - 1];  /* of w_k w_k+1, */
    double moment[3][MODEL_ALIGNMENT_KNOTS];      /* of w_k d; each forgotten by 1 - 1/most a frame */
    long frames;                                  /* frames learnt from */
} model_alignment_t;

/* No second model yet: no correction. */
void model_alignment_init(model_alignment_t *a);

/* Second model `model`'s angles `second` of a frame (another model than before: the curve starts again),
 * and first minus second there (NULL when the first did not measure the frame; the yaw's wrapped into
 * +-180). Each axis's fit takes the frame at its x, over about the last `most` frames (0: never). */
void model_alignment_learn(model_alignment_t *a, const char *model, const double second[3],
                           const double difference[3], long most);

/* The correction d(x) on `axis` for the second's angle x (deg): what to add to move it onto the first's,
 * within +-(MODEL_ALIGNMENT_MOST_AT_0 + MODEL_ALIGNMENT_MOST_SLOPE |x|), x taken within +-MODEL_ALIGNMENT_REACH. */
double model_alignment_correction(const model_alignment_t *a, int axis, double x);

#ifdef __cplusplus
}
#endif

#endif /* MODEL_ALIGNMENT_H */

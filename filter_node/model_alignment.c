/* model_alignment.c - see model_alignment.h. */
#include "model_alignment.h"

#include <math.h>
#include <string.h>

void model_alignment_init(model_alignment_t *a)
{
    memset(a, 0, sizeof *a);
}

/* x's place among the knots: the knot below it (*k) and x's share of the way to the next (*share). */
static void place(double x, int *k, double *share)
{
    double u = (x + MODEL_ALIGNMENT_REACH) / MODEL_ALIGNMENT_KNOT_STEP;
    u = u > 0.0 ? (u < MODEL_ALIGNMENT_KNOTS - 1 ? u : MODEL_ALIGNMENT_KNOTS - 1) : 0.0;
    *k = (int)floor(u);
    if (*k >= MODEL_ALIGNMENT_KNOTS - 1) {
        *k = MODEL_ALIGNMENT_KNOTS - 2;
    }
    *share = u - (double)*k;
}

/* The knots' values that minimise the forgotten squared residuals plus MODEL_ALIGNMENT_SMOOTHING times
 * the squared steps between neighbouring knots: the tridiagonal normal equations (A + eps L) d = b,
 * solved by elimination from the first knot down (Thomas; A + eps L is positive definite once eps > 0). */
static void solve(const double diagonal[MODEL_ALIGNMENT_KNOTS], const double beside[MODEL_ALIGNMENT_KNOTS - 1],
                  const double moment[MODEL_ALIGNMENT_KNOTS], double d[MODEL_ALIGNMENT_KNOTS])
{
    const double eps = MODEL_ALIGNMENT_SMOOTHING;
    double upper[MODEL_ALIGNMENT_KNOTS], right[MODEL_ALIGNMENT_KNOTS];
    int k;
    for (k = 0; k < MODEL_ALIGNMENT_KNOTS; ++k) {
        const double steps = (k > 0) + (k < MODEL_ALIGNMENT_KNOTS - 1); /* L's diagonal: 1 at the ends, else 2 */
        const double off_below = k > 0 ? beside[k - 1] - eps : 0.0;
        const double pivot = diagonal[k] + eps * steps - (k > 0 ? off_below * upper[k - 1] : 0.0);
        upper[k] = k < MODEL_ALIGNMENT_KNOTS - 1 ? (beside[k] - eps) / pivot : 0.0;
        right[k] = (moment[k] - (k > 0 ? off_below * right[k - 1] : 0.0)) / pivot;
    }
    d[MODEL_ALIGNMENT_KNOTS - 1] = right[MODEL_ALIGNMENT_KNOTS - 1];
    for (k = MODEL_ALIGNMENT_KNOTS - 2; k >= 0; --k) {
        d[k] = right[k] - upper[k] * d[k + 1];
    }
}

void model_alignment_learn(model_alignment_t *a, const char *model, const double second[3],
                           const double difference[3], long most)
{
    int axis, j, k;
    if (strncmp(a->model, model, sizeof a->model) != 0) { /* another second model: start over */
        model_alignment_init(a);
        strncpy(a->model, model, sizeof a->model - 1);
    }
    if (difference == NULL || most <= 0) {
        return;
    }
    ++a->frames;
    for (axis = 0; axis < 3; ++axis) {
        const double keep = 1.0 - 1.0 / (double)most; /* the older frames' weight: forgotten over `most` */
        double share, w[2];
        place(second[axis], &k, &share);
        w[0] = 1.0 - share;
        w[1] = share;
        for (j = 0; j < MODEL_ALIGNMENT_KNOTS; ++j) {
            a->diagonal[axis][j] *= keep;
            a->moment[axis][j] *= keep;
            if (j < MODEL_ALIGNMENT_KNOTS - 1) {
                a->beside[axis][j] *= keep;
            }
        }
        /* the frame's residual d - (w0 d_k + w1 d_k+1), squared: its row of the normal equations */
        a->diagonal[axis][k] += w[0] * w[0];
        a->diagonal[axis][k + 1] += w[1] * w[1];
        a->beside[axis][k] += w[0] * w[1];
        a->moment[axis][k] += w[0] * difference[axis];
        a->moment[axis][k + 1] += w[1] * difference[axis];
        solve(a->diagonal[axis], a->beside[axis], a->moment[axis], a->d[axis]);
    }
}

double model_alignment_correction(const model_alignment_t *a, int axis, double x)
{
    int k;
    double share, d, most;
    place(x, &k, &share);
    d = (1.0 - share) * a->d[axis][k] + share * a->d[axis][k + 1];
    most = MODEL_ALIGNMENT_MOST_AT_0 + MODEL_ALIGNMENT_MOST_SLOPE * fmin(fabs(x), MODEL_ALIGNMENT_REACH);
    return d > most ? most : d < -most ? -most : d; /* the models' plausible disagreement, no more */
}

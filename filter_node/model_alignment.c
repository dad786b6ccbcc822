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

/* One knot learns value v with weight w (0-1): a running mean over about `most` weight. */
static void teach(double *d, double *weight, double v, double w, long most)
{
    if (w <= 0.0) {
        return;
    }
    *weight = *weight + w < (double)most ? *weight + w : (double)most;
    *d += w * (v - *d) / *weight;
}

void model_alignment_learn(model_alignment_t *a, const char *model, const double second[3],
                           const double difference[3], long most)
{
    int axis;
    if (strncmp(a->model, model, sizeof a->model) != 0) { /* another second model: start over */
        model_alignment_init(a);
        strncpy(a->model, model, sizeof a->model - 1);
    }
    if (difference == NULL || most <= 0) {
        return;
    }
    ++a->frames;
    for (axis = 0; axis < 3; ++axis) {
        int k;
        double share;
        place(second[axis], &k, &share);
        teach(&a->d[axis][k], &a->weight[axis][k], difference[axis], 1.0 - share, most);
        teach(&a->d[axis][k + 1], &a->weight[axis][k + 1], difference[axis], share, most);
    }
}

/* Knot k's value, or the nearest taught knot's (the lower one on a tie); 0 when none is taught. */
static double knot(const model_alignment_t *a, int axis, int k)
{
    int step;
    for (step = 0; step < MODEL_ALIGNMENT_KNOTS; ++step) {
        if (k - step >= 0 && a->weight[axis][k - step] > 0.0) {
            return a->d[axis][k - step];
        }
        if (k + step < MODEL_ALIGNMENT_KNOTS && a->weight[axis][k + step] > 0.0) {
            return a->d[axis][k + step];
        }
    }
    return 0.0;
}

double model_alignment_correction(const model_alignment_t *a, int axis, double x)
{
    int k;
    double share;
    place(x, &k, &share);
    return (1.0 - share) * knot(a, axis, k) + share * knot(a, axis, k + 1);
}

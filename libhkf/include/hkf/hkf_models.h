/*
 * hkf_models.h - the one table of the estimator models hkf knows, by the name a
 * measurement carries (head_pose_measurement_t.model): each one's Eq. 8 curves
 * and what else the filter should know of it. hkf-filter's built-in models and
 * hkf-estimator's one-frame fusion read it; adding an estimator model means a row
 * here (and its description, estimator/models/NAME.model). A source of its own
 * (hkf_models.c): firmware that never looks a model up by name links none of it.
 */
#ifndef HKF_MODELS_H
#define HKF_MODELS_H

#include "hkf/hkf.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const char *name;               /* the measurement's model id */
    const hkf_noise_curve_t *noise; /* its Eq. 8 curves, [3]: pitch, yaw, roll */
    /* deg^2: the still_wander its resting estimate needs, where it differs from the settings' (0: none of
     * its own). WHENet's resting estimate wanders further than the face mesh's: 1 deg^2 brings its still
     * jitter level with the mesh's (docs/evaluation.md). */
    hkf_real_t still_wander;
    /* its position R as a multiple of the position filter's r_const (0: none of its own, the
     * user's default; 1: the face mesh fit's own, which r_const is). */
    hkf_real_t position_r_scale;
} hkf_model_info_t;

extern const hkf_model_info_t hkf_models[];
extern const int hkf_model_count;

/* The row of the model `name`, or NULL (an unknown model, or name NULL). */
const hkf_model_info_t *hkf_find_model(const char *name);

#ifdef __cplusplus
}
#endif

#endif /* HKF_MODELS_H */

/* hkf_models.c - see hkf_models.h. */
#include "hkf/hkf_models.h"

#include <string.h>

const hkf_model_info_t hkf_models[] = {
    {"fsanet", hkf_noise_fsanet, HKF_REAL(0.0), HKF_REAL(0.0)},    /* the paper's Table I */
    {"hopenet", hkf_noise_hopenet, HKF_REAL(0.0), HKF_REAL(0.0)},  /* the paper's Table I */
    {"mesh_pnp", hkf_noise_mesh_pnp, HKF_REAL(0.0), HKF_REAL(1.0)}, /* hkf-estimator's face mesh; its position is the fit's own */
    {"whenet", hkf_noise_whenet, HKF_REAL(1.0), HKF_REAL(0.0)},     /* hkf-estimator's second model, at large turns */
};
const int hkf_model_count = (int)(sizeof hkf_models / sizeof hkf_models[0]);

const hkf_model_info_t *hkf_find_model(const char *name)
{
    int i;
    for (i = 0; name != NULL && i < hkf_model_count; ++i) {
        if (strcmp(hkf_models[i].name, name) == 0) {
            return &hkf_models[i];
        }
    }
    return NULL;
}

/*
 * resolved_models.h - the config's models resolved once, when the node starts (libhkf's
 * prepare-once: hkf_model_noise_init): each model's angle settings, and its noise prepared for
 * hkf_update_pair_prepared, and its position's R scale, found by the measurement's model id; and the rule
 * that pairs two models. A model not in the table has the
 * base settings (node_config_for_model's rule). The config must have passed node_config_check.
 */
#ifndef RESOLVED_MODELS_H
#define RESOLVED_MODELS_H

#include "hkf/hkf.h"
#include "node_config.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    hkf_settings_t settings;      /* node_config_for_model's */
    hkf_model_prepared_t noise;   /* its R (mode, Eq. 8 curves, constant, clamp) as a second model */
    float position_r_scale;       /* its position R over the position filter's (node_config_model_settings') */
    int in_table;                 /* 1: a model of the config's table; 0: the base, for any other id */
} resolved_model_t;

typedef struct {
    int count;
    char names[NODE_MAX_MODELS][NODE_MODEL_NAME_MAX];
    resolved_model_t models[NODE_MAX_MODELS];
    resolved_model_t base;        /* for a model id not in the table */
    hkf_real_t second_alone_from_yaw; /* the pair's rule (node_config_t's): where the first model measures
                                         |yaw| >= this, a paired frame takes the second's measurement alone */
} resolved_models_t;

/* 0, or the hkf_result_t of a settings set that hkf_model_noise_init refuses (not after node_config_check). */
int resolved_models_init(resolved_models_t *r, const node_config_t *config);

/* The model for an id (NULL: ""): its entry, or the base (in_table 0). */
const resolved_model_t *resolved_models_find(const resolved_models_t *r, const char *model);

#ifdef __cplusplus
}
#endif

#endif /* RESOLVED_MODELS_H */

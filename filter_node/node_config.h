/*
 * node_config.h - hkf-filter's settings: every hkf_settings_t field, plus a
 * table mapping an estimator model's id to its noise curves. Read from a
 * config file (format: filter_node/hkf-filter.conf) and overridden by
 * "key = value" strings from the command line.
 */
#ifndef NODE_CONFIG_H
#define NODE_CONFIG_H

#include <stdio.h>

#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"
#include "hkf/hkf_position.h"
#include "hkf/hkf_rest.h"
#include "hkf_head_pose_measurement_t.h"
#include "model_pairing.h"
#include "setting_text.h"

#ifdef __cplusplus
extern "C" {
#endif

#define NODE_MAX_MODELS 16
/* a model id and its NUL: the limit stated in head_pose_measurement_t.lcm */
#define NODE_MODEL_NAME_MAX (HKF_HEAD_POSE_MEASUREMENT_T_MODEL_NAME_MAX + 1)
#define NODE_ORIGIN_MAX 96 /* "FILE:LINE" or "--set", where a setting was last given */
#define NODE_KEY_SLOTS 48  /* keys: libhkf's settings tables and the node's own, with room to grow */

/* What the node knows of a model beyond its angles' settings; a model's own, or the base's for a model that
 * does not set it. */
typedef struct {
    /* key "position_r_scale": the model's position R as a multiple of position_r_const (the face
     * mesh fit's): a position from the face box is 25 x (head_position.hpp: its z is within ~4 % of the
     * mesh's, median, against the mesh's ~0.5 %, so 5 x the standard deviation) */
    hkf_real_t position_r_scale;
} node_model_settings_t;

#define NODE_BOX_POSITION_R_SCALE 25.0 /* the base's position_r_scale: a position measured from the face box */

#define NODE_MODEL_MAX_SETS NODE_KEY_SLOTS /* a model sets each key once at most */

/* One value a model gives itself over the base: key `key` (node_keys.h) := value, given at origin
 * ("FILE:LINE" or "--set"; "": built in, from libhkf's table of models). */
typedef struct {
    int key;
    setting_value_t value;
    char origin[NODE_ORIGIN_MAX];
} node_model_setting_t;

/* A model: the assignments its [model NAME] section makes (and, for a built-in model, libhkf's table of
 * models: its Eq. 8 curves, r_const = each curve's minimum, ...), each key once (a later value replaces
 * an earlier one), replayed in order over the base settings (node_config_for_model). */
typedef struct {
    char name[NODE_MODEL_NAME_MAX];  /* the measurement's `model` field */
    node_model_setting_t sets[NODE_MODEL_MAX_SETS];
    int set_count;
} node_model_t;

typedef struct {
    hkf_settings_t settings;         /* for a model not in the table */
    node_model_settings_t model_settings; /* the same: for a model not in the table or that does not own them */
    node_model_t models[NODE_MAX_MODELS];
    int model_count;
    /* Two models on one channel (filter_node.h): where the first model
     * measures |yaw| >= this (deg), a frame the second also measured takes
     * the second's measurement alone; below it, both are fused by their Eq. 8
     * R. Key "pair_second_alone_from_yaw"; default NODE_SECOND_ALONE_FROM_YAW. */
    hkf_real_t second_alone_from_yaw;
    /* The head's position filter (hkf/hkf_position.h): keys "position_process_noise" (q per axis
     * x y z, cm^2/s^3), "position_r_const" (R per axis, cm^2, of the face mesh's), ... */
    hkf_position_settings_t position;
    /* The noise calibration beside the position filter: keys "position_noise_time", "position_noise_rise". */
    hkf_calibration_settings_t position_calibration;
    /* The noise calibration beside the angle filter (hkf/hkf_calibration.h): keys "noise_time", "noise_rise". */
    hkf_calibration_settings_t calibration;
    /* The player's rest (hkf/hkf_rest.h; node_rest.h): keys "rest_time", "rest_reach", "stillness". */
    hkf_rest_settings_t rest;
    char origin[NODE_KEY_SLOTS][NODE_ORIGIN_MAX]; /* where each base key was set ("": the default) */
} node_config_t;

#define NODE_SECOND_ALONE_FROM_YAW HKF_SECOND_ALONE_FROM_YAW /* deg: the estimator's too (model_pairing.h) */

/* libhkf's defaults, and the models "fsanet" and "hopenet" with the paper's Table I curves (r_const =
 * each curve's minimum), "mesh_pnp" and "whenet" with theirs; mesh_pnp's position_r_scale is 1 (the
 * position filter's r_const is its), the others' the base's NODE_BOX_POSITION_R_SCALE. */
void node_config_defaults(node_config_t *config);

/* Reads a config file (a regular file: a named pipe is refused, not waited
 * on) into config, on top of what it holds. On error writes "FILE:LINE: what"
 * into error and returns -1. */
int node_config_read_file(node_config_t *config, const char *path, char *error, size_t error_size);

/* Applies one "key = value" line; a key may name a model ("model.NAME.noise.yaw").
 * Returns -1 with a message in error when the key or value is bad. */
int node_config_set(node_config_t *config, const char *assignment, char *error, size_t error_size);

/* Every settings set (the base and each model's) passes hkf_init: 0, or -1
 * with "FILE:LINE: key = value: what is wrong" in error, naming where the
 * offending settings were given. */
int node_config_check(const node_config_t *config, char *error, size_t error_size);

/* The settings for a model id: its assignments (node_model_t) replayed over the base settings. */
hkf_settings_t node_config_for_model(const node_config_t *config, const char *model, int *known);

/* The node's per-model settings for a model id (NULL: none): its own keys over the base's. */
node_model_settings_t node_config_model_settings(const node_config_t *config, const char *model);

/* Writes the configuration in the config-file format (reads back the same). */
void node_config_print(const node_config_t *config, FILE *out);

/* The same, with where each value was set at the start of its comment: "FILE:LINE", "--set",
 * "default" or (a model's built-in curves) "built in" (hkf-filter --print-config). */
void node_config_print_origins(const node_config_t *config, FILE *out);

#ifdef __cplusplus
}
#endif

#endif /* NODE_CONFIG_H */

/*
 * node_keys.h - the keys of hkf-filter's configuration: every setting of libhkf's tables
 * (hkf/hkf_settings_table.h: the angle filter's, the noise calibration's, the position filter's, the
 * last named "position_" + its name) and the node's own, each with an index, the struct its value
 * lives in, and whether a [model NAME] section may set it. The one place that knows the keys' order.
 */
#ifndef NODE_KEYS_H
#define NODE_KEYS_H

#include <stddef.h>

#include "hkf/hkf_settings_table.h"
#include "node_config.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Which struct a key's offset is in: the angles' settings, the calibration's, the rest's, the node config's own, a
 * model's per-model settings (node_model_settings_t) or the position filter's. */
typedef enum {
    NODE_KEY_ANGLES,
    NODE_KEY_CALIBRATION,
    NODE_KEY_REST,
    NODE_KEY_NODE,
    NODE_KEY_PER_MODEL,
    NODE_KEY_POSITION,
    NODE_KEY_POSITION_CALIBRATION
} node_key_group_t;

/* How many keys there are; key k (0 <= k < count) is its slot in the base's origin array. */
int node_key_count(void);

/* Key k's description and its group. */
const hkf_setting_t *node_key_setting(int k, node_key_group_t *group);

/* Key k's name as the config file writes it, in text. */
const char *node_key_name(int k, char *text, size_t size);

/* 1 for the position filter's and its calibration's keys (named "position_" + the setting's name). */
int node_key_is_position(node_key_group_t group);

/* The index of the key `name`, or -1. */
int node_key_find(const char *name);

/* The struct a key of `group` is in: the angle settings or per-model settings given, or config's
 * calibration, own or position settings. */
const char *node_key_base(const node_config_t *config, const hkf_settings_t *angles,
                          const node_model_settings_t *per_model, node_key_group_t group);

/* The bytes of one value of setting d. */
size_t node_key_value_size(const hkf_setting_t *d);

/* 1 when a [model NAME] section may set key k: the angles' and the node's per-model keys. */
int node_key_model_may_own(int k);

#ifdef __cplusplus
}
#endif

#endif /* NODE_KEYS_H */

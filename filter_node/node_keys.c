/* node_keys.c - see node_keys.h. */
#include "node_keys.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

/* Every key is a setting described as libhkf describes its own (hkf/hkf_settings_table.h): the angle
 * filter's, the noise calibration's, the player's rest's, the node's own, then the position filter's and its calibration's
 * (named "position_" + its name). A key's index is its slot in the origin arrays. */
static const hkf_setting_t node_settings[] = {
    {"pair_second_alone_from_yaw", offsetof(node_config_t, second_alone_from_yaw), HKF_SETTING_REAL, 1, "deg", 0, 180,
     0, 0, NULL, "two models on one channel: the second alone where the first's |yaw| >= this"},
};
#define NODE_SETTING_COUNT ((int)(sizeof node_settings / sizeof node_settings[0]))

/* The node's keys that a [model NAME] section may set too (node_model_settings_t). */
static const hkf_setting_t per_model_settings[] = {
    {"position_r_scale", offsetof(node_model_settings_t, position_r_scale), HKF_SETTING_REAL, 1, "", 1, 1e6, 0, 0,
     NULL, "the model's position R as a multiple of position_r_const (the face mesh fit's)"},
};
#define PER_MODEL_SETTING_COUNT ((int)(sizeof per_model_settings / sizeof per_model_settings[0]))
#define POSITION_PREFIX "position_"

static const int node_setting_count = NODE_SETTING_COUNT, per_model_setting_count = PER_MODEL_SETTING_COUNT;

/* The keys' groups in key order, each a settings table and its length: key k is the k-th row of them all. */
static const struct {
    node_key_group_t group;
    const hkf_setting_t *table;
    const int *count;
} key_groups[] = {
    {NODE_KEY_ANGLES, hkf_settings_table, &hkf_settings_table_count},
    {NODE_KEY_CALIBRATION, hkf_calibration_settings_table, &hkf_calibration_settings_table_count},
    {NODE_KEY_REST, hkf_rest_settings_table, &hkf_rest_settings_table_count},
    {NODE_KEY_NODE, node_settings, &node_setting_count},
    {NODE_KEY_PER_MODEL, per_model_settings, &per_model_setting_count},
    {NODE_KEY_POSITION, hkf_position_settings_table, &hkf_position_settings_table_count},
    {NODE_KEY_POSITION_CALIBRATION, hkf_calibration_settings_table, &hkf_calibration_settings_table_count},
};
#define KEY_GROUP_COUNT ((int)(sizeof key_groups / sizeof key_groups[0]))

int node_key_count(void)
{
    int g, count = 0;
    for (g = 0; g < KEY_GROUP_COUNT; ++g) {
        count += *key_groups[g].count;
    }
    return count;
}

const hkf_setting_t *node_key_setting(int k, node_key_group_t *group)
{
    int g;
    for (g = 0; g < KEY_GROUP_COUNT - 1 && k >= *key_groups[g].count; ++g) {
        k -= *key_groups[g].count;
    }
    *group = key_groups[g].group;
    return &key_groups[g].table[k];
}

int node_key_is_position(node_key_group_t group)
{
    return group == NODE_KEY_POSITION || group == NODE_KEY_POSITION_CALIBRATION;
}

/* The key's name as the config file writes it. */
const char *node_key_name(int k, char *text, size_t size)
{
    node_key_group_t group;
    const hkf_setting_t *d = node_key_setting(k, &group);
    snprintf(text, size, "%s%s", node_key_is_position(group) ? POSITION_PREFIX : "", d->name);
    return text;
}

int node_key_find(const char *name)
{
    int k;
    for (k = 0; k < node_key_count(); ++k) {
        char text[64];
        if (strcmp(node_key_name(k, text, sizeof text), name) == 0) {
            return k;
        }
    }
    return -1;
}

/* The struct a key's offset is in: the angle settings or per-model settings given, or the config's calibration,
 * own, position or position calibration. */
const char *node_key_base(const node_config_t *config, const hkf_settings_t *angles,
                            const node_model_settings_t *per_model, node_key_group_t group)
{
    switch (group) {
    case NODE_KEY_ANGLES: return (const char *)angles;
    case NODE_KEY_CALIBRATION: return (const char *)&config->calibration;
    case NODE_KEY_REST: return (const char *)&config->rest;
    case NODE_KEY_NODE: return (const char *)config;
    case NODE_KEY_PER_MODEL: return (const char *)per_model;
    case NODE_KEY_POSITION_CALIBRATION: return (const char *)&config->position_calibration;
    case NODE_KEY_POSITION: break;
    }
    return (const char *)&config->position;
}

size_t node_key_value_size(const hkf_setting_t *d)
{
    switch (d->type) {
    case HKF_SETTING_UINT: return sizeof(unsigned);
    case HKF_SETTING_CHOICE: return sizeof(int);
    case HKF_SETTING_CURVE: return sizeof(hkf_noise_curve_t);
    case HKF_SETTING_REAL:
    case HKF_SETTING_RATE: break;
    }
    return (size_t)d->count * sizeof(hkf_real_t);
}

/* 1 when a [model NAME] section may set key k: the angles' and the node's per-model keys. */
int node_key_model_may_own(int k)
{
    node_key_group_t group;
    (void)node_key_setting(k, &group);
    return group == NODE_KEY_ANGLES || group == NODE_KEY_PER_MODEL;
}

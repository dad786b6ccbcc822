/* node_config.c - see node_config.h: the defaults, the table of models and what an assignment does to
 * them (the file and --set: node_config_file.c; the check: node_config_check.c; the printing:
 * node_config_print.c). */
#include "node_config.h"

#include "hkf/hkf_models.h"
#include "model_name.h"
#include "node_config_parts.h"
#include "node_keys.h"
#include "setting_text.h"

#include <stdio.h>
#include <string.h>

/* Model m's built-in value of key `name`, as a [model NAME] section would set it. */
static void set_builtin(node_model_t *m, const char *name, const setting_value_t *value)
{
    node_model_setting_t *set = &m->sets[m->set_count++];
    set->key = node_key_find(name);
    set->value = *value;
    set->origin[0] = '\0'; /* built in */
}

/* A model of libhkf's table (hkf_models.h): its curves, r_const = each curve's minimum, and the values it
 * has of its own. */
static void add_builtin_model(node_config_t *config, const hkf_model_info_t *info)
{
    static const char *const curves[3] = {"noise.pitch", "noise.yaw", "noise.roll"};
    node_model_t *m = &config->models[config->model_count++];
    setting_value_t v;
    int a;
    strcpy(m->name, info->name);
    for (a = 0; a < 3; ++a) {
        v.curve = info->noise[a];
        set_builtin(m, curves[a], &v);
    }
    for (a = 0; a < 3; ++a) {
        v.real[a] = info->noise[a].tau - info->noise[a].lambda;
    }
    set_builtin(m, "r_const", &v);
    if (info->position_r_scale > 0) {
        v.real[0] = info->position_r_scale;
        set_builtin(m, "position_r_scale", &v);
    }
    if (info->still_wander > 0) {
        v.real[0] = info->still_wander;
        set_builtin(m, "still_wander", &v);
    }
}

void node_config_defaults(node_config_t *config)
{
    int i;
    memset(config, 0, sizeof *config);
    config->settings = hkf_default_settings;
    config->second_alone_from_yaw = (hkf_real_t)NODE_SECOND_ALONE_FROM_YAW;
    config->position = hkf_position_default_settings;
    config->position_calibration = hkf_default_calibration_settings;
    config->calibration = hkf_default_calibration_settings;
    config->rest = hkf_default_rest_settings;
    config->model_settings.position_r_scale = (hkf_real_t)NODE_BOX_POSITION_R_SCALE;
    for (i = 0; i < hkf_model_count; ++i) { /* libhkf's table of models */
        add_builtin_model(config, &hkf_models[i]);
    }
}

/* The same in the config's own settings, to write. */
static char *config_base(node_config_t *config, node_key_group_t group)
{
    const char *base = node_key_base(config, &config->settings, &config->model_settings, group);
    return (char *)config + (base - (const char *)config);
}

/* The text of key k's value, parsed and within its range, into *v; else -1 with what it should have been. */
static int parse_value(int k, const char *text, setting_value_t *v, char *error, size_t error_size)
{
    node_key_group_t group;
    const hkf_setting_t *d = node_key_setting(k, &group);
    char name[64], range[160];
    const int parsed = setting_text_parse(d, text, v);
    if (parsed == 0 && hkf_setting_in_range(d, v)) {
        return 0;
    }
    node_key_name(k, name, sizeof name);
    if (parsed == -2) {
        snprintf(error, error_size, "%s = %s: a value is NaN, infinite or beyond the range of a number here", name,
                 text);
    } else {
        snprintf(error, error_size, "%s wants %s %s, not '%s'", name, setting_text_wants(d, node_key_is_position(group)),
                 setting_text_range(d, range, sizeof range), text);
    }
    return -1;
}

node_model_t *node_config_model_entry(node_config_t *config, const char *name, char *error, size_t error_size)
{
    int i;
    node_model_t *m;
    for (i = 0; i < config->model_count; ++i) {
        if (strcmp(config->models[i].name, name) == 0) {
            return &config->models[i];
        }
    }
    if (!model_name_valid(name)) {
        snprintf(error, error_size, "a model name has 1 to %d letters, digits, '_' or '-', not '%.60s'",
                 HKF_HEAD_POSE_MEASUREMENT_T_MODEL_NAME_MAX, name);
        return NULL;
    }
    if (config->model_count == NODE_MAX_MODELS) {
        snprintf(error, error_size, "more than %d models", NODE_MAX_MODELS);
        return NULL;
    }
    m = &config->models[config->model_count++];
    memset(m, 0, sizeof *m);
    strcpy(m->name, name);
    return m;
}

static void set_origin(char *slot, const char *origin)
{
    snprintf(slot, NODE_ORIGIN_MAX, "%s", origin);
}

const node_model_setting_t *node_config_model_set(const node_model_t *m, int k)
{
    int i;
    for (i = 0; i < m->set_count; ++i) {
        if (m->sets[i].key == k) {
            return &m->sets[i];
        }
    }
    return NULL;
}

void node_config_replay(const node_config_t *config, const node_model_t *m, hkf_settings_t *angles,
                        node_model_settings_t *per_model)
{
    int i;
    *angles = config->settings;
    *per_model = config->model_settings;
    for (i = 0; i < m->set_count; ++i) {
        node_key_group_t group;
        const hkf_setting_t *d = node_key_setting(m->sets[i].key, &group);
        char *base = group == NODE_KEY_PER_MODEL ? (char *)per_model : (char *)angles;
        memcpy(base + d->offset, &m->sets[i].value, node_key_value_size(d));
    }
}

/* Model `model`'s value of a's key: a new assignment of its section, or the one it had replaced. */
static int set_model_key(node_config_t *config, const char *model, const node_assignment_t *a, char *error,
                         size_t error_size)
{
    const int k = node_key_find(a->key);
    node_model_setting_t *set;
    setting_value_t v;
    node_model_t *m;
    if (k < 0 || !node_key_model_may_own(k)) {
        snprintf(error, error_size, "unknown key '%s' for a model (--print-config lists them)", a->key);
        return -1;
    }
    m = node_config_model_entry(config, model, error, error_size);
    if (m == NULL || parse_value(k, a->value, &v, error, error_size) != 0) {
        return -1;
    }
    set = (node_model_setting_t *)node_config_model_set(m, k);
    if (set == NULL) {
        set = &m->sets[m->set_count++]; /* room: each key once, NODE_MODEL_MAX_SETS >= the keys */
        set->key = k;
    }
    set->value = v;
    set_origin(set->origin, a->origin);
    return 0;
}

/* The base's value of a's key. */
static int set_base_key(node_config_t *config, const node_assignment_t *a, char *error, size_t error_size)
{
    const int k = node_key_find(a->key);
    node_key_group_t group;
    const hkf_setting_t *d;
    setting_value_t v;
    if (k < 0) {
        snprintf(error, error_size, "unknown key '%s' (--print-config lists them)", a->key);
        return -1;
    }
    d = node_key_setting(k, &group);
    if (parse_value(k, a->value, &v, error, error_size) != 0) {
        return -1;
    }
    memcpy(config_base(config, group) + d->offset, &v, node_key_value_size(d));
    set_origin(config->origin[k], a->origin);
    return 0;
}

/* a to the base settings, or to model's (a's key may name one: model.NAME.KEY): 0, or -1 with the error. */
int node_config_apply(node_config_t *config, const char *model, node_assignment_t *a, char *error, size_t error_size)
{
    if (strncmp(a->key, "model.", 6) == 0 && model == NULL) {
        char *name = a->key + 6, *dot = strchr(name, '.');
        if (dot == NULL) {
            snprintf(error, error_size, "'%s' is not model.NAME.KEY", a->key);
            return -1;
        }
        *dot = '\0';
        a->key = dot + 1;
        return set_model_key(config, name, a, error, error_size);
    }
    return model != NULL ? set_model_key(config, model, a, error, error_size)
                         : set_base_key(config, a, error, error_size);
}

/* The model named `model` in the table, or NULL. */
static const node_model_t *model_named(const node_config_t *config, const char *model)
{
    int i;
    for (i = 0; model != NULL && i < config->model_count; ++i) {
        if (strcmp(config->models[i].name, model) == 0) {
            return &config->models[i];
        }
    }
    return NULL;
}

node_model_settings_t node_config_model_settings(const node_config_t *config, const char *model)
{
    const node_model_t *m = model_named(config, model);
    hkf_settings_t angles;
    node_model_settings_t per_model = config->model_settings;
    if (m != NULL) {
        node_config_replay(config, m, &angles, &per_model);
    }
    return per_model;
}

hkf_settings_t node_config_for_model(const node_config_t *config, const char *model, int *known)
{
    const node_model_t *m = model_named(config, model);
    hkf_settings_t angles = config->settings;
    node_model_settings_t per_model;
    *known = m != NULL;
    if (m != NULL) {
        node_config_replay(config, m, &angles, &per_model);
    }
    return angles;
}

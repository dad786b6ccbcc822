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

/* A model of libhkf's table (hkf_models.h) in the node's from the start. */
static void add_builtin_model(node_config_t *config, const char *name, const hkf_noise_curve_t noise[3])
{
    node_model_t *m = &config->models[config->model_count++];
    strcpy(m->name, name);
    memcpy(m->noise, noise, sizeof m->noise);
    m->r_const[0] = noise[0].tau - noise[0].lambda;
    m->r_const[1] = noise[1].tau - noise[1].lambda;
    m->r_const[2] = noise[2].tau - noise[2].lambda;
}

/* A built-in model's own value of a real setting of the angles or the node's per-model ones (as a
 * `[model NAME]` section sets it). */
static void own_builtin_real(node_model_t *m, const char *name, hkf_real_t value)
{
    const int k = node_key_find(name);
    node_key_group_t group;
    const hkf_setting_t *d = node_key_setting(k, &group);
    char *base = group == NODE_KEY_PER_MODEL ? (char *)&m->own_node : (char *)&m->own;
    *(hkf_real_t *)(void *)(base + d->offset) = value;
    m->own_keys |= 1ul << k;
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
    config->model_settings.position_r_scale = (hkf_real_t)NODE_BOX_POSITION_R_SCALE;
    for (i = 0; i < hkf_model_count; ++i) { /* libhkf's table of models: each one's curves and own values */
        const hkf_model_info_t *info = &hkf_models[i];
        node_model_t *m = &config->models[config->model_count];
        add_builtin_model(config, info->name, info->noise);
        if (info->position_r_scale > 0) {
            own_builtin_real(m, "position_r_scale", info->position_r_scale);
        }
        if (info->still_wander > 0) {
            own_builtin_real(m, "still_wander", info->still_wander);
        }
    }
}

/* The same in the config's own settings, to write. */
static char *config_base(node_config_t *config, node_key_group_t group)
{
    const char *base = node_key_base(config, &config->settings, &config->model_settings, group);
    return (char *)config + (base - (const char *)config);
}

/* Key k := the text, into its field in the struct at base, once it parses and is within its range;
 * else -1 with what it should have been. */
static int set_value(char *base, int k, const char *text, char *error, size_t error_size)
{
    node_key_group_t group;
    const hkf_setting_t *d = node_key_setting(k, &group);
    setting_value_t v;
    char name[64], range[160];
    const int parsed = setting_text_parse(d, text, &v);
    if (parsed == 0 && hkf_setting_in_range(d, &v)) {
        memcpy(base + d->offset, &v, node_key_value_size(d));
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
    memcpy(m->noise, config->settings.noise, sizeof m->noise);
    memcpy(m->r_const, config->settings.r_const, sizeof m->r_const);
    return m;
}

static void set_origin(char *slot, const char *origin)
{
    snprintf(slot, NODE_ORIGIN_MAX, "%s", origin);
}

int node_config_model_owns(const node_model_t *m, int k)
{
    node_key_group_t group;
    const hkf_setting_t *d = node_key_setting(k, &group);
    return node_key_model_may_own(k) &&
           ((group == NODE_KEY_ANGLES && node_key_model_always_owns(d)) || (m->own_keys >> k & 1ul) != 0);
}

/* The base's per-model settings with a model's own. */
node_model_settings_t node_config_per_model_of(const node_config_t *config, const node_model_t *m)
{
    node_model_settings_t s = config->model_settings;
    int i;
    for (i = 0; i < node_key_per_model_count(); ++i) { /* the few per-model keys alone */
        const int k = node_key_of_per_model(i);
        node_key_group_t group;
        const hkf_setting_t *d = node_key_setting(k, &group);
        if ((m->own_keys >> k & 1ul) != 0) {
            memcpy((char *)&s + d->offset, (const char *)&m->own_node + d->offset, node_key_value_size(d));
        }
    }
    return s;
}

/* The base settings with a model's curves, r_const and own keys. */
hkf_settings_t node_config_settings_of(const node_config_t *config, const node_model_t *m)
{
    hkf_settings_t s = config->settings;
    int k;
    memcpy(s.noise, m->noise, sizeof s.noise);
    memcpy(s.r_const, m->r_const, sizeof s.r_const);
    for (k = 0; k < node_key_count(); ++k) {
        node_key_group_t group;
        const hkf_setting_t *d = node_key_setting(k, &group);
        if (group == NODE_KEY_ANGLES && !node_key_model_always_owns(d) && (m->own_keys >> k & 1ul) != 0) {
            memcpy((char *)&s + d->offset, (const char *)&m->own + d->offset, node_key_value_size(d));
        }
    }
    return s;
}

static int set_model_key(node_config_t *config, const char *model, const node_assignment_t *a, char *error,
                         size_t error_size)
{
    const char *name = a->key;
    const int k = node_key_find(name);
    node_key_group_t group;
    const hkf_setting_t *d;
    node_model_t *m;
    hkf_settings_t scratch;
    if (k < 0 || !node_key_model_may_own(k)) {
        snprintf(error, error_size, "unknown key '%s' for a model (--print-config lists them)", name);
        return -1;
    }
    d = node_key_setting(k, &group);
    m = node_config_model_entry(config, model, error, error_size);
    if (m == NULL) {
        return -1;
    }
    if (group == NODE_KEY_PER_MODEL) {
        node_model_settings_t own = node_config_per_model_of(config, m);
        if (set_value((char *)&own, k, a->value, error, error_size) != 0) {
            return -1;
        }
        m->own_node = own;
        m->own_keys |= 1ul << k;
        set_origin(m->origin[k], a->origin);
        return 0;
    }
    scratch = node_config_settings_of(config, m);
    if (set_value((char *)&scratch, k, a->value, error, error_size) != 0) {
        return -1;
    }
    memcpy(m->noise, scratch.noise, sizeof m->noise);
    memcpy(m->r_const, scratch.r_const, sizeof m->r_const);
    if (!node_key_model_always_owns(d)) {
        memcpy((char *)&m->own + d->offset, (const char *)&scratch + d->offset, node_key_value_size(d));
        m->own_keys |= 1ul << k;
    }
    set_origin(m->origin[k], a->origin);
    return 0;
}

/* a to the base settings, or to model's (a's key may name one: model.NAME.KEY): 0, or -1 with the error. */
int node_config_apply(node_config_t *config, const char *model, node_assignment_t *a, char *error, size_t error_size)
{
    node_key_group_t group;
    int k;
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
    if (model != NULL) {
        return set_model_key(config, model, a, error, error_size);
    }
    k = node_key_find(a->key);
    if (k < 0) {
        snprintf(error, error_size, "unknown key '%s' (--print-config lists them)", a->key);
        return -1;
    }
    (void)node_key_setting(k, &group);
    if (set_value(config_base(config, group), k, a->value, error, error_size) != 0) {
        return -1;
    }
    set_origin(config->origin[k], a->origin);
    return 0;
}

node_model_settings_t node_config_model_settings(const node_config_t *config, const char *model)
{
    int i;
    for (i = 0; model != NULL && i < config->model_count; ++i) {
        if (strcmp(config->models[i].name, model) == 0) {
            return node_config_per_model_of(config, &config->models[i]);
        }
    }
    return config->model_settings;
}

hkf_settings_t node_config_for_model(const node_config_t *config, const char *model, int *known)
{
    int i;
    *known = 0;
    for (i = 0; i < config->model_count; ++i) {
        if (strcmp(config->models[i].name, model) == 0) {
            *known = 1;
            return node_config_settings_of(config, &config->models[i]);
        }
    }
    return config->settings;
}

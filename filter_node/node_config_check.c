/* node_config_check.c - see node_config.h: every settings set passes libhkf's init, or the error names
 * where the offending values were given. */
#include "node_config.h"

#include "node_config_parts.h"
#include "node_keys.h"
#include "setting_text.h"

#include <stdio.h>
#include <string.h>

#define STRING_OF(x) #x
#define STRING_OF_VALUE(x) STRING_OF(x) /* a macro's value as text */

/* "where: key = value; " for each key of `group` that the init error `result` is about and that was given
 * somewhere (for a model: its own or the base's), appended to text. */
static void describe_origins(const node_config_t *config, const node_model_t *model, node_key_group_t want, int result,
                             char *text, size_t size)
{
    hkf_settings_t s = config->settings;
    node_model_settings_t per_model = config->model_settings;
    int k;
    if (model != NULL) {
        node_config_replay(config, model, &s, &per_model);
    }
    for (k = 0; k < node_key_count(); ++k) {
        node_key_group_t group;
        const hkf_setting_t *d = node_key_setting(k, &group);
        const node_model_setting_t *set = model != NULL ? node_config_model_set(model, k) : NULL;
        const char *origin = set != NULL ? set->origin : config->origin[k];
        const char *base = node_key_base(config, &s, &per_model, group);
        char name[64], value[160];
        const size_t used = strlen(text);
        if (group != want || !hkf_setting_is_about(d, result) || origin[0] == '\0') {
            continue; /* another group's, not this error's, or a default: not what the user wrote */
        }
        setting_text_format(d, base + d->offset, value, sizeof value);
        snprintf(text + used, size - used, "%s: %s = %s; ", origin, node_key_name(k, name, sizeof name), value);
    }
}

int node_config_check(const node_config_t *config, char *error, size_t error_size)
{
    hkf_filter_t probe;
    hkf_position_filter_t position_probe;
    hkf_calibration_t calibration_probe;
    hkf_rest_t rest_probe;
    int m, result = hkf_position_init(&position_probe, &config->position);
    char where[600] = "";
    if (result == HKF_OK) {
        result = hkf_calibration_init_position(&calibration_probe, &config->position_calibration, &position_probe);
        if (result != HKF_OK) {
            describe_origins(config, NULL, NODE_KEY_POSITION_CALIBRATION, result, where, sizeof where);
            snprintf(error, error_size, "%sinvalid position settings (position_*): %s", where, hkf_result_string(result));
            return -1;
        }
    }
    if (result != HKF_OK) {
        describe_origins(config, NULL, NODE_KEY_POSITION, result, where, sizeof where);
        snprintf(error, error_size, "%sinvalid position settings (position_*): %s", where,
                 result == HKF_ERROR_SETTING_GATE /* libhkf's text names the angles' gate_sigma too */
                     ? "position_max_speed is not in [0, " STRING_OF_VALUE(HKF_MAX_SPEED) "] cm/s, or the gate is on "
                       "(position_max_speed > 0) with position_max_gate_rejections 0"
                     : hkf_result_string(result));
        return -1;
    }
    result = hkf_rest_init(&rest_probe, &config->rest);
    if (result != HKF_OK) {
        describe_origins(config, NULL, NODE_KEY_REST, result, where, sizeof where);
        snprintf(error, error_size, "%sinvalid rest settings: %s", where, hkf_result_string(result));
        return -1;
    }
    result = hkf_init(&probe, &config->settings);
    if (result != HKF_OK) {
        describe_origins(config, NULL, NODE_KEY_ANGLES, result, where, sizeof where);
        snprintf(error, error_size, "%sinvalid settings: %s", where, hkf_result_string(result));
        return -1;
    }
    for (m = 0; m < config->model_count; ++m) {
        int known;
        const hkf_settings_t s = node_config_for_model(config, config->models[m].name, &known);
        result = hkf_init(&probe, &s);
        if (result != HKF_OK) {
            describe_origins(config, &config->models[m], NODE_KEY_ANGLES, result, where, sizeof where);
            snprintf(error, error_size, "%sinvalid settings for model '%s': %s", where, config->models[m].name,
                     hkf_result_string(result));
            return -1;
        }
    }
    return 0;
}

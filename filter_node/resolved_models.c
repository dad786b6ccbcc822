/* resolved_models.c - see resolved_models.h. */
#include "resolved_models.h"

#include <string.h>

static int resolve(resolved_model_t *m, const hkf_settings_t *settings, node_model_settings_t per_model)
{
    const hkf_model_noise_t noise = hkf_model_noise_of(settings);
    m->settings = *settings;
    m->position_r_scale = (float)per_model.position_r_scale;
    return hkf_model_noise_init(&m->noise, &noise);
}

int resolved_models_init(resolved_models_t *r, const node_config_t *config)
{
    int i, result;
    memset(r, 0, sizeof *r);
    r->second_alone_from_yaw = config->second_alone_from_yaw;
    result = resolve(&r->base, &config->settings, config->model_settings);
    for (i = 0; result == HKF_OK && i < config->model_count; ++i) {
        int known;
        const hkf_settings_t s = node_config_for_model(config, config->models[i].name, &known);
        memcpy(r->names[i], config->models[i].name, sizeof r->names[i]);
        result = resolve(&r->models[i], &s, node_config_model_settings(config, config->models[i].name));
        r->models[i].in_table = 1;
        r->count = i + 1;
    }
    return result;
}

const resolved_model_t *resolved_models_find(const resolved_models_t *r, const char *model)
{
    int i;
    for (i = 0; i < r->count; ++i) {
        if (strcmp(r->names[i], model != NULL ? model : "") == 0) {
            return &r->models[i];
        }
    }
    return &r->base;
}

/* node_config_print.c - see node_config.h: the configuration in the config file's format, optionally with
 * where each value was set. */
#include "node_config.h"

#include "node_config_parts.h"
#include "node_keys.h"
#include "setting_text.h"

#include <stdio.h>

/* "key = value  # [where; ]what": `where` is the origin ("FILE:LINE" or "--set"), or `unset` when it has none;
 * NULL leaves it out (a configuration that reads back to the same text). */
static void print_line(const char *name, const char *value, const char *comment, const char *origin,
                       const char *unset, FILE *out)
{
    const char *where = origin == NULL ? NULL : origin[0] != '\0' ? origin : unset;
    fprintf(out, "%-28s = %-36s # %s%s%s\n", name, value, where != NULL ? where : "", where != NULL ? "; " : "",
            comment);
}

/* Key k's line, its value in the struct at base, its comment "unit; what". */
static void print_key(int k, const char *base, const char *origin, const char *unset, FILE *out)
{
    node_key_group_t group;
    const hkf_setting_t *d = node_key_setting(k, &group);
    char name[64], value[160], comment[200];
    setting_text_format(d, base + d->offset, value, sizeof value);
    snprintf(comment, sizeof comment, "%s%s%s", d->unit, d->unit[0] != '\0' ? "; " : "", d->what);
    print_line(node_key_name(k, name, sizeof name), value, comment, origin, unset, out);
}

static void print_all(const node_config_t *config, int origins, FILE *out)
{
    int k, m;
    fprintf(out, "# hkf-filter effective configuration%s\n",
            origins ? " (after each value: where it was set, or default / built in)" : "");
    for (k = 0; k < node_key_count(); ++k) {
        node_key_group_t group;
        (void)node_key_setting(k, &group);
        print_key(k, node_key_base(config, &config->settings, &config->model_settings, group),
                  origins ? config->origin[k] : NULL, "default", out);
    }
    for (m = 0; m < config->model_count; ++m) {
        const node_model_t *model = &config->models[m];
        hkf_settings_t s;
        node_model_settings_t per_model;
        node_config_replay(config, model, &s, &per_model);
        fprintf(out, "\n[model %s]\n", model->name);
        for (k = 0; k < node_key_count(); ++k) {
            node_key_group_t group;
            (void)node_key_setting(k, &group);
            const node_model_setting_t *set = node_config_model_set(model, k);
            if (set != NULL) {
                print_key(k, node_key_base(config, &s, &per_model, group), origins ? set->origin : NULL, "built in", out);
            }
        }
    }
}

void node_config_print(const node_config_t *config, FILE *out)
{
    print_all(config, 0, out);
}

void node_config_print_origins(const node_config_t *config, FILE *out)
{
    print_all(config, 1, out);
}

/*
 * node_config_parts.h - what node_config.c (the model table and assignments), node_config_file.c (the
 * text a user writes: the file and --set), node_config_check.c and node_config_print.c share. Not for
 * the node: node_config.h is its interface.
 */
#ifndef NODE_CONFIG_PARTS_H
#define NODE_CONFIG_PARTS_H

#include <stddef.h>

#include "node_config.h"

/* One "key = value" to apply (the key split out of its line, changed in place for model.NAME.KEY), and
 * where it was given ("FILE:LINE" or "--set"). */
typedef struct {
    char *key;
    const char *value;
    const char *origin;
} node_assignment_t;

/* a to the base settings, or to model's (a's key may name one: model.NAME.KEY): 0, or -1 with the error. */
int node_config_apply(node_config_t *config, const char *model, node_assignment_t *a, char *error, size_t error_size);

/* The table's entry for the model `name`, added (with no assignments: the base's values) if it is not there; NULL with the
 * error for a bad name or a full table. */
node_model_t *node_config_model_entry(node_config_t *config, const char *name, char *error, size_t error_size);

/* Model m's assignment of key k, or NULL: it takes the base's value. */
const node_model_setting_t *node_config_model_set(const node_model_t *m, int k);

/* The base's angle settings and per-model settings with model m's assignments replayed over them. */
void node_config_replay(const node_config_t *config, const node_model_t *m, hkf_settings_t *angles,
                        node_model_settings_t *per_model);

#endif /* NODE_CONFIG_PARTS_H */

/*
 * node_settings_live.h - the settings a player changes while hkf-filter runs (tracker_setting_t on the
 * command channel: the live view's stillness knob, hkf-cmd) and saving them (tracker_command_t's
 * SAVE_SETTINGS). A value goes through the config file's own checks (node_config_set, node_config_check)
 * on a copy of the run's config; taken, it goes into that config, which stays the one truth, and into the
 * node at once. Saving writes the live keys into the user's config file (config_files.h), every other line
 * of it kept, the new file read back through the same checks before it replaces the old one (kept as .bak).
 */
#ifndef NODE_SETTINGS_LIVE_H
#define NODE_SETTINGS_LIVE_H

#include <stddef.h>

#include "filter_node.h"
#include "node_config.h"
#include "hkf_tracker_setting_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/* key = value taken live: key one of the live keys ("stillness"), value what the config file would take.
 * 0, or -1 with the reason in error (nothing changed). */
int node_setting_apply(filter_node_t *node, node_config_t *config, const char *key, const char *value, char *error,
                       size_t error_size);

/* A command-channel payload that is a tracker_setting_t, taken (node_setting_apply): 1; refused: 0 with the
 * reason in error; not a tracker_setting_t: -1. */
int node_setting_take_message(filter_node_t *node, node_config_t *config, const void *data, int size, char *error,
                              size_t error_size);

/* The live keys' values of config written into the user's config file (created, with its folder, when
 * missing). 0 with the file's path in path, or -1 with the reason in error (the old file untouched). */
int node_settings_save(const node_config_t *config, char *path, size_t path_size, char *error, size_t error_size);

#ifdef __cplusplus
}
#endif

#endif /* NODE_SETTINGS_LIVE_H */

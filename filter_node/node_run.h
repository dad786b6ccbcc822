/*
 * node_run.h - one run of hkf-filter: its options (hkf_filter_main.c reads them
 * from the command line and the config files) and what the two runners share:
 * the node, the CSV, the counts of what went wrong, the paths a run never
 * writes over. The runners: node_run_live.c (over LCM) and node_run_offline.c
 * (a log into a log, through filter_node_offline.h).
 */
#ifndef NODE_RUN_H
#define NODE_RUN_H

#include <stdio.h>

#include <lcm/lcm.h>

#include "config_files.h"
#include "filter_node.h"
#include "node_config.h"

typedef struct {
    const char *input_url, *output_url;
    const char *input_channel, *output_channel, *command_channel;
    const char *status_channel; /* --status-channel, or the output channel's + "_STATUS" (status_channel_text) */
    char status_channel_text[LCM_MAX_CHANNEL_NAME_LENGTH + 8];
    const char *offline_in, *offline_out;
    const char *csv_path;
    const char *config_paths[8]; /* inputs too: never written over */
    char found_config[CONFIG_FILES_MAX][CONFIG_FILES_PATH_MAX]; /* the system's and the user's, where found */
    int config_count;
    int config_given;            /* --config: the user's file (where SAVE_SETTINGS writes) is not read */
    double rate_hz;
    int print_config;
    node_config_t config;
} node_options_t;

typedef struct {
    node_options_t *options;
    filter_node_t node;
    lcm_t *out_lcm;
    FILE *csv;
    int reported_decode_errors, reported_unknown_commands;
    unsigned long unknown_commands, publish_errors, csv_errors;
    unsigned long said_measured, said_spoiled; /* the node's rests said so far (node_run_say_rest) */
    unsigned long published_ok;  /* poses and statuses LCM took: a file:// output must hold them all (lcm_file_url.h) */
} node_run_t;

#define STRING_OF(x) #x
#define STRING_OF_VALUE(x) STRING_OF(x)
#define NODE_RUN_LONG_MODEL_HINT                                                                                           \
    " (its model id is longer than the " STRING_OF_VALUE(HKF_HEAD_POSE_MEASUREMENT_T_MODEL_NAME_MAX)             \
    " bytes head_pose_measurement_t.lcm allows)"

/* The paths this run reads or writes, other than `except`: a file it opens
 * for writing must be none of them. Returns how many are in keep (room for 3 + 8). */
int node_run_paths_to_keep(const node_options_t *o, const char *except, const char **keep);

/* No output may be an input or the other output: checked for all before any is opened. 1 when so, 0 (said). */
int node_run_outputs_distinct(const node_options_t *o);

/* --csv, with its header (node_run_outputs_distinct has checked it is no other file of the run; live,
 * `keep` holds the logs the LCM URLs name). 0, or -1 (said). */
int node_run_open_csv(node_run_t *run, const char *const *keep, int count);

/* A message on `channel` did not decode: counted, and said the first five times (hint: why, or ""). */
void node_run_report_decode_error(node_run_t *run, const char *channel, const char *hint);

/* The player's rest (node_rest.h): what happened to it since the last call, said (a rest measured; a
 * spoiled one, the first NODE_RUN_SPOILED_SAID times). */
#define NODE_RUN_SPOILED_SAID 10
void node_run_say_rest(node_run_t *run);

/* The rest at the end of a run: how many were measured and spoiled, and the last one measured, or the
 * built-in wander held. */
void node_run_say_rest_summary(const filter_node_t *node, FILE *to);

/* The live run (node_run_live.c): subscribes, filters, publishes until a signal. Exit status 0 or 1. */
int node_run_live(node_run_t *run);

/* The offline run (node_run_offline.c): --offline IN OUT. Exit status 0 or 1. */
int node_run_offline(node_run_t *run);

#endif /* NODE_RUN_H */

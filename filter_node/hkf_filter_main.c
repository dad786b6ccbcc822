/*
 * hkf-filter - the filter node: subscribes raw head poses (HEAD_POSE_RAW),
 * publishes filtered ones (HEAD_POSE), obeys HEAD_TRACKER_CMD. Offline, it
 * filters an LCM log into another LCM log, deterministically, through the
 * same filter_node code. This file: the options and the start; the runs are
 * node_run_live.c and node_run_offline.c (node_run.h).
 */
#define _POSIX_C_SOURCE 200809L

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arguments.h"
#include "config_files.h"
#include "lcm_file_url.h"
#include "node_config.h"
#include "node_run.h"
#include "safe_files.h"

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-filter [options]                       live: LCM in, LCM out\n"
            "       hkf-filter --offline IN.lcmlog OUT.lcmlog [options]   log in, log out\n"
            "Filters raw head poses (hkf.head_pose_measurement_t) with libhkf's adaptive Kalman\n"
            "filter into hkf.head_pose_t; RECENTER / RESET / SAVE_SETTINGS arrive as\n"
            "hkf.tracker_command_t, a setting changed live (stillness) as hkf.tracker_setting_t,\n"
            "checked as the config file's line; SAVE_SETTINGS writes it into the user's config file.\n"
            "When tracking starts and at each RECENTER or RESET it measures the player's rest\n"
            "(rest_time, 2 s: the player looks at the screen's centre and keeps still), which sets\n"
            "how far a resting pose may wander (stillness x the measured wander) and the centre;\n"
            "until then the wander is still_wander. The status says where the rest stands.\n"
            "  --lcm-url URL        LCM provider for input and output (default " LCM_URL_DEFAULT ")\n"
            "  --input-url URL      LCM provider to subscribe on (default: --lcm-url)\n"
            "  --output-url URL     LCM provider to publish on (default: --lcm-url)\n"
            "  --input-channel C    raw poses (default HEAD_POSE_RAW)\n"
            "  --output-channel C   filtered poses (default HEAD_POSE)\n"
            "  --command-channel C  commands (default HEAD_TRACKER_CMD)\n"
            "  --status-channel C   hkf.tracker_status_t after each pose: the player's rest (default: the\n"
            "                       output channel's name + _STATUS, HEAD_POSE_STATUS)\n"
            "  --rate HZ            also publish poses extrapolated to this rate between measurements\n"
            "  --config FILE        settings file (repeatable); without it: " CONFIG_FILES_SYSTEM_DIR "/" CONFIG_FILES_NAME "\n"
            "                       (or $HKF_SYSTEM_CONFIG_DIR's), then ~/.config/hkf/" CONFIG_FILES_NAME "\n"
            "                       (or $XDG_CONFIG_HOME's), each where it exists\n"
            "  --set KEY=VALUE      override one setting (repeatable), e.g. --set lc_theta=3,\n"
            "                       --set model.whenet.noise.yaw='7 4 0 30' (any key, for one model)\n"
            "  --print-config       print the effective settings, each with where it was set, and exit\n"
            "  --offline IN OUT     filter the log IN into the log OUT as fast as possible\n"
            "  --csv FILE           also write every published pose as CSV\n"
            "  --help, --version    this text; the version\n"
            "Stops on SIGINT / SIGTERM / SIGHUP (live) or at the end of IN (offline) with a summary.\n"
            "Exit status: 0; 1 when a file or LCM provider fails (a write that did not reach the disk\n"
            "included); 2 for bad arguments or settings.\n");
}

/* Every channel name is one LCM accepts, and each of the four is the node's for one use only (a status
 * message on the pose or input channel would reach every subscriber of that one): 0, or 2 (said). */
static int check_channels(const node_options_t *o)
{
    const char *const channels[] = {o->input_channel, o->output_channel, o->command_channel, o->status_channel};
    static const char *const options[] = {"--input-channel", "--output-channel", "--command-channel", "--status-channel"};
    for (int i = 0; i < 4; ++i) {
        if (channels[i][0] == '\0' || strlen(channels[i]) > LCM_MAX_CHANNEL_NAME_LENGTH) {
            fprintf(stderr, "hkf-filter: a channel name has 1 to %d characters, not '%.80s%s'\n",
                    LCM_MAX_CHANNEL_NAME_LENGTH, channels[i], strlen(channels[i]) > 80 ? "..." : "");
            return 2;
        }
        for (int j = 0; j < i; ++j) {
            if (strcmp(channels[i], channels[j]) == 0) {
                fprintf(stderr, "hkf-filter: %s and %s are both '%s': each of the node's channels has one use\n",
                        options[j], options[i], channels[i]);
                return 2;
            }
        }
    }
    return 0;
}

/* Where an option that names a string goes (the LCM URL's is the caller's), or NULL. */
static const char **string_option(node_options_t *o, const char *arg, const char **lcm_url)
{
    static const struct {
        const char *name;
        size_t offset;
    } strings[] = {
        {"--input-url", offsetof(node_options_t, input_url)},           {"--output-url", offsetof(node_options_t, output_url)},
        {"--input-channel", offsetof(node_options_t, input_channel)},   {"--output-channel", offsetof(node_options_t, output_channel)},
        {"--command-channel", offsetof(node_options_t, command_channel)},
        {"--status-channel", offsetof(node_options_t, status_channel)}, {"--csv", offsetof(node_options_t, csv_path)},
    };
    if (strcmp(arg, "--lcm-url") == 0) {
        return lcm_url;
    }
    for (size_t k = 0; k < sizeof strings / sizeof strings[0]; ++k) {
        if (strcmp(arg, strings[k].name) == 0) {
            return (const char **)(void *)((char *)o + strings[k].offset);
        }
    }
    return NULL;
}

/* --rate, --config or --set with its value: 0, -1 when arg is none of them, 2 for a bad value (said). */
static int settings_option(node_options_t *o, const char *arg, const char *value)
{
    char error[600];
    if (strcmp(arg, "--rate") == 0) {
        if (!argument_number(value, 0.1, 10000.0, &o->rate_hz)) {
            fprintf(stderr, "hkf-filter: --rate wants a frequency from 0.1 to 10000 Hz, not '%s'\n", value);
            return 2;
        }
        return 0;
    }
    if (strcmp(arg, "--config") == 0) {
        o->config_given = 1;
        if (o->config_count < (int)(sizeof o->config_paths / sizeof o->config_paths[0])) {
            o->config_paths[o->config_count++] = value;
        }
        if (node_config_read_file(&o->config, value, error, sizeof error) != 0) {
            fprintf(stderr, "hkf-filter: %s\n", error);
            return 2;
        }
        return 0;
    }
    if (strcmp(arg, "--set") == 0) {
        if (node_config_set(&o->config, value, error, sizeof error) != 0) {
            fprintf(stderr, "hkf-filter: --set: %s\n", error);
            return 2;
        }
        return 0;
    }
    return -1;
}

/* How many values follow option arg on the command line (--offline's two, another option's one, 0). */
static int values_of(node_options_t *o, const char *arg)
{
    const char *ignored;
    if (strcmp(arg, "--offline") == 0) {
        return 2;
    }
    return string_option(o, arg, &ignored) != NULL || strcmp(arg, "--rate") == 0 || strcmp(arg, "--config") == 0 ||
           strcmp(arg, "--set") == 0;
}

/* Without --config on the command line: the system's and the user's files, where they exist
 * (config_files.h), read before any --set. 0, or 2 (said) when one is bad. */
static int read_found_configs(int argc, char **argv, node_options_t *o)
{
    config_files_t found;
    char error[600];
    for (int i = 1; i < argc; i += 1 + values_of(o, argv[i])) { /* an option's value is no option: --csv --config */
        if (strcmp(argv[i], "--config") == 0 || strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0 ||
            strcmp(argv[i], "--version") == 0) {
            return 0; /* --help and --version answer whatever the files hold */
        }
    }
    config_files_find(&found);
    for (int i = 0; i < found.count; ++i) {
        o->config_paths[o->config_count++] = o->found_config[i];
        memcpy(o->found_config[i], found.path[i], sizeof found.path[i]);
        if (node_config_read_file(&o->config, found.path[i], error, sizeof error) != 0) {
            fprintf(stderr, "hkf-filter: %s\n", error);
            return 2;
        }
    }
    return 0;
}

/* 0 = run, 1 = done (help, print-config), 2 = bad arguments */
static int parse_options(int argc, char **argv, node_options_t *o)
{
    const char *lcm_url = LCM_URL_DEFAULT;
    memset(o, 0, sizeof *o);
    node_config_defaults(&o->config);
    o->input_channel = "HEAD_POSE_RAW";
    o->output_channel = "HEAD_POSE";
    o->command_channel = "HEAD_TRACKER_CMD";
    if (read_found_configs(argc, argv, o) != 0) return 2;
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        const char **string = value != NULL ? string_option(o, arg, &lcm_url) : NULL;
        int result;
        if (argument_help_or_version(arg, "hkf-filter", usage)) {
            return 1;
        } else if (strcmp(arg, "--print-config") == 0) {
            o->print_config = 1;
        } else if (string != NULL) {
            *string = argv[++i];
        } else if (value != NULL && (result = settings_option(o, arg, value)) >= 0) {
            if (result != 0) return result;
            ++i;
        } else if (value != NULL && strcmp(arg, "--offline") == 0 && i + 2 < argc) {
            o->offline_in = argv[++i];
            o->offline_out = argv[++i];
        } else {
            fprintf(stderr, "hkf-filter: unknown or incomplete argument '%s' (see --help)\n", arg);
            return 2;
        }
    }
    o->input_url = lcm_url_resolve(o->input_url ? o->input_url : lcm_url); /* '': $LCM_DEFAULT_URL, as LCM reads it */
    o->output_url = lcm_url_resolve(o->output_url ? o->output_url : lcm_url);
    if (o->status_channel == NULL) { /* beside the poses: HEAD_POSE_STATUS */
        snprintf(o->status_channel_text, sizeof o->status_channel_text, "%.*s_STATUS", LCM_MAX_CHANNEL_NAME_LENGTH,
                 o->output_channel);
        o->status_channel = o->status_channel_text;
    }
    return check_channels(o);
}

/* Every settings set (the base and each model's) must pass hkf_init. */
static int validate_config(const node_config_t *config)
{
    char error[800];
    if (node_config_check(config, error, sizeof error) != 0) {
        fprintf(stderr, "hkf-filter: %s\n", error);
        return -1;
    }
    return 0;
}

static void print_summary(const filter_node_t *node, FILE *to)
{
    const filter_node_counts_t *c = &node->counts;
    fprintf(to,
            "hkf-filter: %lu measurements (%lu without a face), %lu poses published (%lu extrapolated); "
            "rejected: %lu out of order, %lu duplicates, %lu bad values, %lu undecodable; "
            "%lu clock jumps (%lu followed), %lu from another publisher; %lu track restarts, "
            "%lu with an unknown model, %lu commands; the estimator fell silent %lu times (LOST published); "
            "%lu second-model measurements fused into their frame (%lu not used; %lu frames waited for one); "
            "positions: %lu bad values, %lu refused by the outlier gate; "
            "%lu frames with a reading refused as a gross error (%g deg from both the other model's and the track's)\n",
            c->received, c->without_face, c->published, c->extrapolated, c->out_of_order, c->duplicates,
            c->bad_values, c->decode_errors, c->clock_jumps, c->clock_resyncs, c->other_publisher, c->restarts,
            c->unknown_models, c->commands, c->silences, c->paired, c->unpaired, c->awaited, c->bad_positions,
            c->positions_gated, c->gross_refused, FILTER_NODE_GROSS_DEG);
    node_run_say_rest_summary(node, to);
}

int main(int argc, char **argv)
{
    static node_options_t options;
    static node_run_t run;
    int status;
    switch (parse_options(argc, argv, &options)) {
    case 1: return 0;
    case 2: return 2;
    default: break;
    }
    if (validate_config(&options.config) != 0) {
        return 2;
    }
    if (options.print_config) {
        node_config_print_origins(&options.config, stdout);
        if (safe_close(stdout) != 0) { /* a full disk, a closed pipe: not a printed config */
            fprintf(stderr, "hkf-filter: --print-config: writing the settings failed\n");
            return 1;
        }
        return 0;
    }
    run.options = &options;
    safe_files_fail_writes_past_size_limit();
    filter_node_init(&run.node, &options.config);
    if (!node_run_outputs_distinct(&options)) {
        status = 1;
    } else if (options.offline_in != NULL) {
        status = node_run_offline(&run);
    } else {
        status = node_run_live(&run);
    }
    if (run.csv != NULL && (safe_close(run.csv) != 0 || run.csv_errors > 0)) {
        fprintf(stderr, "hkf-filter: error writing '%s' (a full disk?): it is cut\n", options.csv_path);
        status = 1;
    }
    print_summary(&run.node, stderr);
    return status;
}

/*
 * hkf-filter - the filter node: subscribes raw head poses (HEAD_POSE_RAW),
 * publishes filtered ones (HEAD_POSE), obeys HEAD_TRACKER_CMD. Offline, it
 * filters an LCM log into another LCM log, deterministically, through the
 * same filter_node code.
 */
#define _POSIX_C_SOURCE 200809L

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "filter_node.h"
#include "filter_node_offline.h"
#include "lcm_log_writer.h"
#include "lcm_wait.h"
#include "message_decode.h"
#include "config_files.h"
#include "node_config.h"
#include "node_schedule.h"
#include "pose_csv.h"
#include "safe_files.h"
#include "lcm_file_url.h"

typedef struct {
    const char *input_url, *output_url;
    const char *input_channel, *output_channel, *command_channel;
    const char *offline_in, *offline_out;
    const char *csv_path;
    const char *config_paths[8]; /* inputs too: never written over */
    char found_config[CONFIG_FILES_MAX][CONFIG_FILES_PATH_MAX]; /* the system's and the user's, where found */
    int config_count;
    double rate_hz;
    int print_config;
    node_config_t config;
} options_t;

typedef struct {
    options_t *options;
    filter_node_t node;
    lcm_t *out_lcm;
    FILE *csv;
    int reported_decode_errors, reported_unknown_commands;
    unsigned long unknown_commands, publish_errors, csv_errors;
    unsigned long published_ok;  /* poses LCM took: a file:// output must hold them all (lcm_file_url.h) */
} node_run_t;

/* The capture clock, for the latency a pose reports. */
static int64_t wall_utime(void)
{
    return clock_wall_us();
}

/* The receive clock of the live node: arrivals, silence, --rate ticks. It
 * never steps, so a wall clock stepped back (NTP, a user, a resumed VM) shows
 * in the estimator's stamps alone, where the clock rule sees it. */
static int64_t arrival_utime(void)
{
    return clock_monotonic_us();
}

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-filter [options]                       live: LCM in, LCM out\n"
            "       hkf-filter --offline IN.lcmlog OUT.lcmlog [options]   log in, log out\n"
            "Filters raw head poses (hkf.head_pose_measurement_t) with libhkf's adaptive Kalman\n"
            "filter into hkf.head_pose_t; RECENTER / RESET arrive as hkf.tracker_command_t.\n"
            "  --lcm-url URL        LCM provider for input and output (default " LCM_URL_DEFAULT ")\n"
            "  --input-url URL      LCM provider to subscribe on (default: --lcm-url)\n"
            "  --output-url URL     LCM provider to publish on (default: --lcm-url)\n"
            "  --input-channel C    raw poses (default HEAD_POSE_RAW)\n"
            "  --output-channel C   filtered poses (default HEAD_POSE)\n"
            "  --command-channel C  commands (default HEAD_TRACKER_CMD)\n"
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

/* Every channel name is one LCM accepts: 0, or 2 (said). */
static int check_channels(const options_t *o)
{
    const char *const channels[] = {o->input_channel, o->output_channel, o->command_channel};
    for (int i = 0; i < 3; ++i) {
        if (channels[i][0] == '\0' || strlen(channels[i]) > LCM_MAX_CHANNEL_NAME_LENGTH) {
            fprintf(stderr, "hkf-filter: a channel name has 1 to %d characters, not '%.80s%s'\n",
                    LCM_MAX_CHANNEL_NAME_LENGTH, channels[i], strlen(channels[i]) > 80 ? "..." : "");
            return 2;
        }
    }
    return 0;
}

/* Where an option that names a string goes (the LCM URL's is the caller's), or NULL. */
static const char **string_option(options_t *o, const char *arg, const char **lcm_url)
{
    static const struct {
        const char *name;
        size_t offset;
    } strings[] = {
        {"--input-url", offsetof(options_t, input_url)},           {"--output-url", offsetof(options_t, output_url)},
        {"--input-channel", offsetof(options_t, input_channel)},   {"--output-channel", offsetof(options_t, output_channel)},
        {"--command-channel", offsetof(options_t, command_channel)}, {"--csv", offsetof(options_t, csv_path)},
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
static int settings_option(options_t *o, const char *arg, const char *value)
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
static int values_of(options_t *o, const char *arg)
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
static int read_found_configs(int argc, char **argv, options_t *o)
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
static int parse_options(int argc, char **argv, options_t *o)
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
            "%lu second-model measurements fused into their frame (%lu not used); "
            "positions: %lu bad values, %lu refused by the outlier gate\n",
            c->received, c->without_face, c->published, c->extrapolated, c->out_of_order, c->duplicates,
            c->bad_values, c->decode_errors, c->clock_jumps, c->clock_resyncs, c->other_publisher, c->restarts,
            c->unknown_models, c->commands, c->silences, c->paired, c->unpaired, c->bad_positions,
            c->positions_gated);
}

#define STRING_OF(x) #x
#define STRING_OF_VALUE(x) STRING_OF(x)
#define LONG_MODEL_HINT                                                                                           \
    " (its model id is longer than the " STRING_OF_VALUE(HKF_HEAD_POSE_MEASUREMENT_T_MODEL_NAME_MAX)             \
    " bytes head_pose_measurement_t.lcm allows)"

static void report_decode_error(node_run_t *run, const char *channel, const char *hint)
{
    ++run->node.counts.decode_errors;
    if (run->reported_decode_errors++ < 5) {
        fprintf(stderr, "hkf-filter: a message on %s did not decode%s; counted and skipped%s\n", channel, hint,
                run->reported_decode_errors == 5 ? " (no more such messages)" : "");
    }
}

/* ---- live ---- */

static void publish(node_run_t *run, hkf_head_pose_t *pose)
{
    pose->latency_us = wall_utime() - pose->measurement_utime;
    if (hkf_head_pose_t_publish(run->out_lcm, run->options->output_channel, pose) != 0) {
        if (run->publish_errors++ < 5) {
            fprintf(stderr, "hkf-filter: publishing on %s failed\n", run->options->output_channel);
        }
    } else {
        ++run->published_ok;
    }
    if (run->csv != NULL && pose_csv_write(run->csv, pose) != 0 && run->csv_errors++ == 0) {
        fprintf(stderr, "hkf-filter: writing '%s' failed (a full disk?)\n", run->options->csv_path);
    }
}

static void on_measurement(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    node_run_t *run = user;
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    if (message_decode_measurement(rbuf->data, (int)rbuf->data_size, &m) != 0) {
        report_decode_error(run, channel,
                            message_model_id_too_long(rbuf->data, (int)rbuf->data_size) ? LONG_MODEL_HINT : "");
        return;
    }
    if (filter_node_receive(&run->node, &m, arrival_utime(), &pose)) {
        publish(run, &pose);
    }
    hkf_head_pose_measurement_t_decode_cleanup(&m);
}

static void on_command(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    node_run_t *run = user;
    hkf_tracker_command_t command;
    if (hkf_tracker_command_t_decode(rbuf->data, 0, (int)rbuf->data_size, &command) < 0) {
        report_decode_error(run, channel, "");
        return;
    }
    if (filter_node_command(&run->node, &command) != 0) {
        ++run->unknown_commands;
        if (run->reported_unknown_commands++ < 5) { /* a flood must not flood the terminal */
            fprintf(stderr, "hkf-filter: unknown command %d on %s ignored%s\n", command.command, channel,
                    run->reported_unknown_commands == 5 ? " (no more such messages; counted)" : "");
        }
    }
}

static int paths_to_keep(const options_t *o, const char *except, const char **keep);

/* --csv, with its header (outputs_distinct has checked it is no other file of the run; live, `keep`
 * holds the logs the LCM URLs name). */
static int open_csv(node_run_t *run, const char *const *keep, int count)
{
    const options_t *o = run->options;
    if (o->csv_path == NULL) {
        return 0;
    }
    run->csv = safe_open_output(o->csv_path, "w", keep, count, "hkf-filter");
    if (run->csv == NULL) {
        return -1;
    }
    if (pose_csv_write_header(run->csv) != 0) {
        run->csv_errors = 1;
    }
    return 0;
}

/* The live URLs' file:// rules (lcm_file_url.h), before LCM opens either: the input reads a regular
 * file; the output writes none of the run's other files. 0, or -1 with the reason. */
static int check_live_urls(const options_t *o, lcm_file_url_t *input, lcm_file_url_t *output)
{
    const char *keep[3 + 8 + 1];
    int count;
    if (lcm_file_url_check(o->input_url, "input", NULL, 0, "hkf-filter", input) != 0) {
        return -1;
    }
    if (strcmp(o->input_url, o->output_url) == 0 && !input->is_file) {
        *output = *input; /* one provider for both */
        return 0;
    }
    count = paths_to_keep(o, NULL, keep);
    if (input->is_file) {
        keep[count++] = input->path;
    }
    return lcm_file_url_check(o->output_url, "output", keep, count, "hkf-filter", output);
}

/* The LCM providers of a live run, subscribed: the input (which is also the output when the URLs are the
 * same; run->out_lcm is set), or NULL (said). */
static lcm_t *open_live(node_run_t *run)
{
    const options_t *o = run->options;
    lcm_t *in = lcm_create(o->input_url);
    if (in == NULL) {
        fprintf(stderr, "hkf-filter: cannot open LCM provider '%s'\n", o->input_url);
        return NULL;
    }
    run->out_lcm = strcmp(o->input_url, o->output_url) == 0 ? in : lcm_create(o->output_url);
    if (run->out_lcm == NULL) {
        fprintf(stderr, "hkf-filter: cannot open LCM provider '%s'\n", o->output_url);
        lcm_destroy(in);
        return NULL;
    }
    if (lcm_wait_subscribe(in, o->input_channel, on_measurement, run, "hkf-filter") == NULL ||
        lcm_wait_subscribe(in, o->command_channel, on_command, run, "hkf-filter") == NULL) {
        if (run->out_lcm != in) {
            lcm_destroy(run->out_lcm);
        }
        lcm_destroy(in);
        return NULL;
    }
    return in;
}

/* Handles what arrives until a stop is asked for: measurements and commands, then what is due
 * between them (node_schedule.h: the silence's LOST poses and the --rate ticks). 0, or 1 when LCM
 * failed. */
static int live_loop(node_run_t *run, lcm_t *in)
{
    const int64_t tick_us = run->options->rate_hz > 0.0 ? (int64_t)(1e6 / run->options->rate_hz) : 0;
    node_schedule_t schedule;
    node_schedule_init(&schedule, tick_us, 1); /* LOST repeated for late subscribers */
    while (!lcm_wait_stop_requested()) {
        hkf_head_pose_t pose;
        int64_t due;
        const int64_t wake = node_schedule_wake(&schedule, &run->node);
        if (lcm_wait_and_handle(in, lcm_wait_time(wake, arrival_utime()), "hkf-filter") < 0) {
            return 1;
        }
        while (node_schedule_next(&schedule, &run->node, arrival_utime(), &pose, &due)) {
            publish(run, &pose);
        }
    }
    return 0;
}

static int run_live(node_run_t *run)
{
    const options_t *o = run->options;
    lcm_file_url_t input_file, output_file;
    const char *url_files[2];
    int files = 0;
    lcm_t *in;
    int status;
    if (check_live_urls(o, &input_file, &output_file) != 0) {
        return 1;
    }
    if (input_file.is_file) {
        url_files[files++] = input_file.path;
    }
    if (output_file.is_file) {
        url_files[files++] = output_file.path;
    }
    /* the CSV only now: it must not be a log the URLs name (truncated before LCM reads it) */
    if (open_csv(run, url_files, files) != 0 || (in = open_live(run)) == NULL) {
        return 1;
    }
    lcm_wait_stop_on_signals();
    fprintf(stderr, "hkf-filter: %s -> %s on %s%s%s\n", o->input_channel, o->output_channel, o->input_url,
            run->out_lcm != in ? " -> " : "", run->out_lcm != in ? o->output_url : "");
    status = live_loop(run, in);
    if (run->out_lcm != in) {
        lcm_destroy(run->out_lcm);
    }
    lcm_destroy(in);
    if (lcm_file_url_verify(&output_file, run->published_ok, "hkf-filter") != 0) {
        status = 1;
    }
    if (run->unknown_commands > 0) {
        fprintf(stderr, "hkf-filter: %lu unknown commands ignored\n", run->unknown_commands);
    }
    if (run->publish_errors > 0) {
        fprintf(stderr, "hkf-filter: %lu poses could not be published on %s\n", run->publish_errors, o->output_channel);
        status = 1;
    }
    return status;
}

/* ---- offline ---- */

/* The paths this run reads or writes, other than `except`: a file it opens
 * for writing must be none of them. Returns how many are in keep. */
static int paths_to_keep(const options_t *o, const char *except, const char **keep)
{
    const char *all[3 + 8];
    int i, count = 0, n = 0;
    all[count++] = o->offline_in;
    all[count++] = o->offline_out;
    all[count++] = o->csv_path;
    for (i = 0; i < o->config_count; ++i) {
        all[count++] = o->config_paths[i];
    }
    for (i = 0; i < count; ++i) {
        if (all[i] != NULL && all[i] != except) {
            keep[n++] = all[i];
        }
    }
    return n;
}

/* No output may be an input or the other output: checked for all before any is opened. */
static int outputs_distinct(const options_t *o)
{
    const char *const outputs[] = {o->offline_out, o->csv_path};
    const char *keep[3 + 8];
    int i, k, count;
    for (i = 0; i < 2; ++i) {
        if (outputs[i] == NULL) {
            continue;
        }
        count = paths_to_keep(o, outputs[i], keep);
        for (k = 0; k < count; ++k) {
            if (safe_same_file(outputs[i], keep[k])) {
                fprintf(stderr, "hkf-filter: '%s' is also '%s', which this run reads or writes; refusing to write "
                                "over it\n", outputs[i], keep[k]);
                return 0;
            }
        }
    }
    return 1;
}

/* What an offline run found in its input, said: a stop, damage, a cut, undecodable messages. */
static void say_offline_report(const node_run_t *run, const filter_node_offline_report_t *report, int status)
{
    const options_t *o = run->options;
    if (report->stopped) {
        fprintf(stderr, "hkf-filter: stopped by a signal after %lu events of '%s'; '%s' is whole up to there\n",
                report->events, o->offline_in, o->offline_out);
    }
    if (status != 0 && !report->write_failed && !report->csv_failed && !report->stopped) {
        fprintf(stderr, "hkf-filter: '%s' is not a file that can be read from any position\n", o->offline_in);
    }
    if (report->skipped_bytes > 0) { /* damage inside the log: what was around it was filtered */
        fprintf(stderr, "hkf-filter: '%s' is damaged: %ld bytes between its events are no event, skipped\n",
                o->offline_in, report->skipped_bytes);
    }
    if (report->cut_bytes > 0) { /* the whole events were filtered; say where the log was cut */
        fprintf(stderr, "hkf-filter: '%s' is cut off: its last %ld bytes are part of an event, ignored; "
                        "its %lu whole events were filtered\n", o->offline_in, report->cut_bytes, report->events);
    }
    if (run->node.counts.decode_errors > 0) {
        fprintf(stderr, "hkf-filter: %lu messages did not decode; counted and skipped\n",
                run->node.counts.decode_errors);
    }
    if (report->long_model_ids > 0) {
        fprintf(stderr, "hkf-filter: %lu of them%s\n", report->long_model_ids, LONG_MODEL_HINT);
    }
    if (report->unknown_commands > 0) {
        fprintf(stderr, "hkf-filter: %lu unknown commands ignored\n", report->unknown_commands);
    }
}

/* The offline run's files: the input first, as a regular file (a named pipe would block and cannot
 * seek); then the outputs, which outputs_distinct has checked are neither the input nor each other.
 * The input, or NULL (said; nothing left open). */
static FILE *open_offline(node_run_t *run, lcm_log_writer_t *out)
{
    char error[600];
    FILE *out_file, *in = safe_open_input(run->options->offline_in, error, sizeof error);
    if (in == NULL) {
        fprintf(stderr, "hkf-filter: %s\n", error);
        return NULL;
    }
    out_file = safe_open_output(run->options->offline_out, "wb", NULL, 0, "hkf-filter");
    if (out_file == NULL) {
        fclose(in);
        return NULL;
    }
    lcm_log_writer_start(out, out_file);
    if (open_csv(run, NULL, 0) != 0) {
        fclose(in);
        (void)lcm_log_writer_close(out);
        return NULL;
    }
    return in;
}

static int run_offline(node_run_t *run)
{
    const options_t *o = run->options;
    filter_node_offline_t offline;
    filter_node_offline_report_t report;
    lcm_log_writer_t out;
    int status;
    FILE *in = open_offline(run, &out);
    if (in == NULL) {
        return 1;
    }
    offline.input_channel = o->input_channel;
    offline.output_channel = o->output_channel;
    offline.command_channel = o->command_channel;
    offline.tick_us = o->rate_hz > 0.0 ? (int64_t)(1e6 / o->rate_hz) : 0;
    offline.csv = run->csv;
    offline.stop_requested = lcm_wait_stop_requested;
    lcm_wait_stop_on_signals(); /* SIGINT / SIGTERM / SIGHUP: stop between events, close the output whole */
    status = filter_node_offline(&run->node, &offline, in, &out, &report);
    say_offline_report(run, &report, status);
    status = report.stopped ? -1 : status;
    run->csv_errors += report.csv_failed != 0;
    fclose(in);
    if (lcm_log_writer_close(&out) != 0) {
        fprintf(stderr, "hkf-filter: error writing '%s' (a full disk?): it is incomplete; the filtering stopped "
                        "at the first failed write\n", o->offline_out);
        return 1;
    }
    return status != 0 ? 1 : 0;
}

int main(int argc, char **argv)
{
    static options_t options;
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
    if (!outputs_distinct(&options)) {
        status = 1;
    } else if (options.offline_in != NULL) {
        status = run_offline(&run);
    } else {
        status = run_live(&run);
    }
    if (run.csv != NULL && (safe_close(run.csv) != 0 || run.csv_errors > 0)) {
        fprintf(stderr, "hkf-filter: error writing '%s' (a full disk?): it is cut\n", options.csv_path);
        status = 1;
    }
    print_summary(&run.node, stderr);
    return status;
}

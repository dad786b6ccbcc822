/*
 * hkf-filter - the filter node: subscribes raw head poses (HEAD_POSE_RAW),
 * publishes filtered ones (HEAD_POSE), obeys HEAD_TRACKER_CMD. Offline, it
 * filters an LCM log into another LCM log, deterministically, through the
 * same filter_node code.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <lcm/lcm.h>

#include "filter_node.h"
#include "filter_node_offline.h"
#include "lcm_wait.h"
#include "node_config.h"
#include "pose_csv.h"

#define DEFAULT_LCM_URL "udpm://239.255.76.67:7667?ttl=0"

typedef struct {
    const char *input_url, *output_url;
    const char *input_channel, *output_channel, *command_channel;
    const char *offline_in, *offline_out;
    const char *csv_path;
    double rate_hz;
    int print_config;
    node_config_t config;
} options_t;

typedef struct {
    options_t *options;
    filter_node_t node;
    lcm_t *out_lcm;
    FILE *csv;
    int64_t last_arrival_us;   /* wall clock when the last measurement was handled */
    int reported_decode_errors;
} node_run_t;

static int64_t wall_utime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-filter [options]                       live: LCM in, LCM out\n"
            "       hkf-filter --offline IN.lcmlog OUT.lcmlog [options]   log in, log out\n"
            "Filters raw head poses (hkf.head_pose_measurement_t) with libhkf's adaptive Kalman\n"
            "filter into hkf.head_pose_t; RECENTER / RESET arrive as hkf.tracker_command_t.\n"
            "  --lcm-url URL        LCM provider for input and output (default " DEFAULT_LCM_URL ")\n"
            "  --input-url URL      LCM provider to subscribe on (default: --lcm-url)\n"
            "  --output-url URL     LCM provider to publish on (default: --lcm-url)\n"
            "  --input-channel C    raw poses (default HEAD_POSE_RAW)\n"
            "  --output-channel C   filtered poses (default HEAD_POSE)\n"
            "  --command-channel C  commands (default HEAD_TRACKER_CMD)\n"
            "  --rate HZ            also publish poses extrapolated to this rate between measurements\n"
            "  --config FILE        settings file (see tools/filter_node/hkf-filter.conf)\n"
            "  --set KEY=VALUE      override one setting (repeatable), e.g. --set lc_theta=3,\n"
            "                       --set model.whenet.noise.yaw='7 4 0 30'\n"
            "  --print-config       print the effective settings and exit\n"
            "  --offline IN OUT     filter the log IN into the log OUT as fast as possible\n"
            "  --csv FILE           also write every published pose as CSV\n"
            "  --help               this text\n"
            "Stops on SIGINT / SIGTERM (live) or at the end of IN (offline) with a summary.\n");
}

/* 0 = run, 1 = done (help, print-config), 2 = bad arguments */
static int parse_options(int argc, char **argv, options_t *o)
{
    char error[600];
    const char *lcm_url = DEFAULT_LCM_URL;
    int i;
    memset(o, 0, sizeof *o);
    node_config_defaults(&o->config);
    o->input_channel = "HEAD_POSE_RAW";
    o->output_channel = "HEAD_POSE";
    o->command_channel = "HEAD_TRACKER_CMD";
    for (i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            usage(stdout);
            return 1;
        } else if (strcmp(arg, "--print-config") == 0) {
            o->print_config = 1;
        } else if (value == NULL) {
            fprintf(stderr, "hkf-filter: unknown or incomplete argument '%s' (see --help)\n", arg);
            return 2;
        } else if (strcmp(arg, "--lcm-url") == 0) {
            lcm_url = argv[++i];
        } else if (strcmp(arg, "--input-url") == 0) {
            o->input_url = argv[++i];
        } else if (strcmp(arg, "--output-url") == 0) {
            o->output_url = argv[++i];
        } else if (strcmp(arg, "--input-channel") == 0) {
            o->input_channel = argv[++i];
        } else if (strcmp(arg, "--output-channel") == 0) {
            o->output_channel = argv[++i];
        } else if (strcmp(arg, "--command-channel") == 0) {
            o->command_channel = argv[++i];
        } else if (strcmp(arg, "--rate") == 0) {
            char *end = NULL;
            o->rate_hz = strtod(argv[++i], &end);
            if (*end != '\0' || !(o->rate_hz > 0.0 && o->rate_hz <= 10000.0)) {
                fprintf(stderr, "hkf-filter: --rate wants a frequency from 0 to 10000 Hz, not '%s'\n", argv[i]);
                return 2;
            }
        } else if (strcmp(arg, "--config") == 0) {
            if (node_config_read_file(&o->config, argv[++i], error, sizeof error) != 0) {
                fprintf(stderr, "hkf-filter: %s\n", error);
                return 2;
            }
        } else if (strcmp(arg, "--set") == 0) {
            if (node_config_set(&o->config, argv[++i], error, sizeof error) != 0) {
                fprintf(stderr, "hkf-filter: --set: %s\n", error);
                return 2;
            }
        } else if (strcmp(arg, "--csv") == 0) {
            o->csv_path = argv[++i];
        } else if (strcmp(arg, "--offline") == 0 && i + 2 < argc) {
            o->offline_in = argv[++i];
            o->offline_out = argv[++i];
        } else {
            fprintf(stderr, "hkf-filter: unknown or incomplete argument '%s' (see --help)\n", arg);
            return 2;
        }
    }
    o->input_url = o->input_url ? o->input_url : lcm_url;
    o->output_url = o->output_url ? o->output_url : lcm_url;
    return 0;
}

/* Every settings set (the base and each model's) must pass hkf_init. */
static int validate_config(const node_config_t *config)
{
    hkf_filter_t probe;
    int m, result = hkf_init(&probe, &config->settings);
    if (result != HKF_OK) {
        fprintf(stderr, "hkf-filter: invalid settings: %s\n", hkf_result_string(result));
        return -1;
    }
    for (m = 0; m < config->model_count; ++m) {
        int known;
        const hkf_settings_t s = node_config_for_model(config, config->models[m].name, &known);
        result = hkf_init(&probe, &s);
        if (result != HKF_OK) {
            fprintf(stderr, "hkf-filter: invalid settings for model '%s': %s\n", config->models[m].name,
                    hkf_result_string(result));
            return -1;
        }
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
            "%lu second-model measurements fused into their frame (%lu not used)\n",
            c->received, c->without_face, c->published, c->extrapolated, c->out_of_order, c->duplicates,
            c->bad_values, c->decode_errors, c->clock_jumps, c->clock_resyncs, c->other_publisher, c->restarts,
            c->unknown_models, c->commands, c->silences, c->paired, c->unpaired);
}

static void report_decode_error(node_run_t *run, const char *channel)
{
    ++run->node.counts.decode_errors;
    if (run->reported_decode_errors++ < 5) {
        fprintf(stderr, "hkf-filter: a message on %s did not decode; counted and skipped\n", channel);
    }
}

/* ---- live ---- */

static void publish(node_run_t *run, hkf_head_pose_t *pose)
{
    pose->latency_us = wall_utime() - pose->measurement_utime;
    if (hkf_head_pose_t_publish(run->out_lcm, run->options->output_channel, pose) != 0) {
        fprintf(stderr, "hkf-filter: publishing on %s failed\n", run->options->output_channel);
    }
    if (run->csv != NULL) {
        pose_csv_write(run->csv, pose);
    }
}

static void on_measurement(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    node_run_t *run = user;
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    if (filter_node_decode(rbuf->data, (int)rbuf->data_size, &m) != 0) {
        report_decode_error(run, channel);
        return;
    }
    run->last_arrival_us = wall_utime();
    if (filter_node_receive(&run->node, &m, run->last_arrival_us, &pose)) {
        publish(run, &pose);
    }
    hkf_head_pose_measurement_t_decode_cleanup(&m);
}

static void on_command(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    node_run_t *run = user;
    hkf_tracker_command_t command;
    if (hkf_tracker_command_t_decode(rbuf->data, 0, (int)rbuf->data_size, &command) < 0) {
        report_decode_error(run, channel);
        return;
    }
    if (filter_node_command(&run->node, &command) != 0) {
        fprintf(stderr, "hkf-filter: unknown command %d on %s ignored\n", command.command, channel);
    }
}

static int run_live(node_run_t *run)
{
    const options_t *o = run->options;
    lcm_t *in = lcm_create(o->input_url);
    const int64_t tick_us = o->rate_hz > 0.0 ? (int64_t)(1e6 / o->rate_hz) : 0;
    int64_t next_tick = wall_utime() + tick_us;
    if (in == NULL) {
        fprintf(stderr, "hkf-filter: cannot open LCM provider '%s'\n", o->input_url);
        return 1;
    }
    run->out_lcm = strcmp(o->input_url, o->output_url) == 0 ? in : lcm_create(o->output_url);
    if (run->out_lcm == NULL) {
        fprintf(stderr, "hkf-filter: cannot open LCM provider '%s'\n", o->output_url);
        lcm_destroy(in);
        return 1;
    }
    if (lcm_wait_subscribe(in, o->input_channel, on_measurement, run, "hkf-filter") == NULL ||
        lcm_wait_subscribe(in, o->command_channel, on_command, run, "hkf-filter") == NULL) {
        if (run->out_lcm != in) {
            lcm_destroy(run->out_lcm);
        }
        lcm_destroy(in);
        return 1;
    }
    lcm_wait_stop_on_signals();
    fprintf(stderr, "hkf-filter: %s -> %s on %s%s%s\n", o->input_channel, o->output_channel, o->input_url,
            run->out_lcm != in ? " -> " : "", run->out_lcm != in ? o->output_url : "");

    while (!lcm_wait_stop_requested()) {
        const int64_t silence_due = filter_node_silence_due(&run->node);
        const int64_t wake = tick_us > 0 && (silence_due == 0 || next_tick < silence_due) ? next_tick : silence_due;
        if (lcm_wait_and_handle(in, lcm_wait_time(wake, wall_utime()), "hkf-filter") < 0) {
            break;
        }
        {
            hkf_head_pose_t pose;
            if (filter_node_silence(&run->node, wall_utime(), &pose)) { /* the estimator has gone quiet */
                publish(run, &pose);
            }
        }
        if (tick_us > 0 && wall_utime() >= next_tick) {
            /* between measurements: the pose at the capture clock's "now" */
            hkf_head_pose_t pose;
            const int64_t since = wall_utime() - run->last_arrival_us;
            if (run->node.have_time && since > 0 && run->node.last_utime <= INT64_MAX - since &&
                filter_node_extrapolate(&run->node, run->node.last_utime + since, &pose)) {
                publish(run, &pose);
            }
            next_tick += tick_us;
            if (next_tick < wall_utime()) {
                next_tick = wall_utime() + tick_us;
            }
        }
    }
    if (run->out_lcm != in) {
        lcm_destroy(run->out_lcm);
    }
    lcm_destroy(in);
    return 0;
}

/* ---- offline ---- */

static int run_offline(node_run_t *run)
{
    const options_t *o = run->options;
    filter_node_offline_t offline;
    filter_node_offline_report_t report;
    FILE *in = fopen(o->offline_in, "rb");
    lcm_eventlog_t *out;
    int status;
    if (in == NULL) {
        fprintf(stderr, "hkf-filter: cannot read the LCM log '%s': %s\n", o->offline_in, strerror(errno));
        return 1;
    }
    out = lcm_eventlog_create(o->offline_out, "w");
    if (out == NULL) {
        fprintf(stderr, "hkf-filter: cannot write the LCM log '%s'\n", o->offline_out);
        fclose(in);
        return 1;
    }
    offline.input_channel = o->input_channel;
    offline.output_channel = o->output_channel;
    offline.command_channel = o->command_channel;
    offline.tick_us = o->rate_hz > 0.0 ? (int64_t)(1e6 / o->rate_hz) : 0;
    offline.csv = run->csv;
    offline.stop_requested = lcm_wait_stop_requested;
    lcm_wait_stop_on_signals(); /* SIGINT / SIGTERM: stop between events, close the output whole */
    status = filter_node_offline(&run->node, &offline, in, out, &report);
    if (report.stopped) {
        fprintf(stderr, "hkf-filter: stopped by a signal after %lu events of '%s'; '%s' is whole up to there\n",
                report.events, o->offline_in, o->offline_out);
        status = -1;
    }
    if (status != 0 && !report.write_failed && !report.stopped) {
        fprintf(stderr, "hkf-filter: '%s' is not a file that can be read from any position\n", o->offline_in);
    }
    if (report.skipped_bytes > 0) { /* damage inside the log: what was around it was filtered */
        fprintf(stderr, "hkf-filter: '%s' is damaged: %ld bytes between its events are no event, skipped\n",
                o->offline_in, report.skipped_bytes);
    }
    if (report.cut_bytes > 0) { /* the whole events were filtered; say where the log was cut */
        fprintf(stderr, "hkf-filter: '%s' is cut off: its last %ld bytes are part of an event, ignored; "
                        "its %lu whole events were filtered\n", o->offline_in, report.cut_bytes, report.events);
    }
    if (run->node.counts.decode_errors > 0) {
        fprintf(stderr, "hkf-filter: %lu messages did not decode; counted and skipped\n",
                run->node.counts.decode_errors);
    }
    if (report.unknown_commands > 0) {
        fprintf(stderr, "hkf-filter: %lu unknown commands ignored\n", report.unknown_commands);
    }
    fclose(in);
    lcm_eventlog_destroy(out);
    if (report.write_failed) {
        fprintf(stderr, "hkf-filter: error writing '%s'\n", o->offline_out);
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
        node_config_print(&options.config, stdout);
        return 0;
    }
    run.options = &options;
    filter_node_init(&run.node, &options.config);
    if (options.csv_path != NULL) {
        run.csv = fopen(options.csv_path, "w");
        if (run.csv == NULL) {
            fprintf(stderr, "hkf-filter: cannot write '%s': %s\n", options.csv_path, strerror(errno));
            return 1;
        }
        pose_csv_write_header(run.csv);
    }
    status = options.offline_in != NULL ? run_offline(&run) : run_live(&run);
    if (run.csv != NULL && fclose(run.csv) != 0) {
        fprintf(stderr, "hkf-filter: error writing '%s'\n", options.csv_path);
        status = 1;
    }
    print_summary(&run.node, stderr);
    return status;
}

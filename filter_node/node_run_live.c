/* node_run_live.c - see node_run.h: hkf-filter live, over LCM: measurements and commands in, poses out,
 * what is due between them on the receive clock (node_schedule.h). */
#define _POSIX_C_SOURCE 200809L

#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <lcm/lcm.h>

#include "clocks.h"
#include "lcm_file_url.h"
#include "lcm_wait.h"
#include "message_decode.h"
#include "node_run.h"
#include "node_settings_live.h"
#include "node_schedule.h"
#include "pose_csv.h"

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

/* One publish's outcome counted (0: LCM took it), and its failure said the first five times. */
static void count_publish(node_run_t *run, int result, const char *channel)
{
    if (result != 0) {
        if (run->publish_errors++ < 5) {
            fprintf(stderr, "hkf-filter: publishing on %s failed\n", channel);
        }
    } else {
        ++run->published_ok;
    }
}

/* A pose, and after a pose that is not extrapolated the status that goes with it (the CSV has both). */
static void publish(node_run_t *run, hkf_head_pose_t *pose)
{
    hkf_tracker_status_t status;
    const node_options_t *o = run->options;
    pose->latency_us = wall_utime() - pose->measurement_utime;
    filter_node_status(&run->node, pose, &status);
    count_publish(run, hkf_head_pose_t_publish(run->out_lcm, o->output_channel, pose), o->output_channel);
    if (!pose->extrapolated) {
        count_publish(run, hkf_tracker_status_t_publish(run->out_lcm, o->status_channel, &status), o->status_channel);
    }
    if (run->csv != NULL && pose_csv_write(run->csv, pose, &status) != 0 && run->csv_errors++ == 0) {
        fprintf(stderr, "hkf-filter: writing '%s' failed (a full disk?)\n", run->options->csv_path);
    }
}

static void on_measurement(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    node_run_t *run = user;
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    if (message_decode_measurement(rbuf->data, (int)rbuf->data_size, &m) != 0) {
        node_run_report_decode_error(run, channel,
                            message_model_id_too_long(rbuf->data, (int)rbuf->data_size) ? NODE_RUN_LONG_MODEL_HINT : "");
        return;
    }
    if (filter_node_receive(&run->node, &m, arrival_utime(), &pose)) {
        publish(run, &pose);
    }
    node_run_say_rest(run);
    hkf_head_pose_measurement_t_decode_cleanup(&m);
}

/* SAVE_SETTINGS: the live settings into the user's config file (node_settings_live.h), said and counted. */
static void save_settings(node_run_t *run)
{
    char path[CONFIG_FILES_PATH_MAX], error[CONFIG_FILES_PATH_MAX + 256];
    ++run->node.counts.commands;
    if (node_settings_save(&run->options->config, path, sizeof path, error, sizeof error) != 0) {
        ++run->node.counts.settings_unsaved;
        fprintf(stderr, "hkf-filter: the settings were not saved: %s\n", error);
        return;
    }
    ++run->node.counts.settings_saved;
    fprintf(stderr, "hkf-filter: the settings saved in %s (stillness %.3g)%s\n", path,
            (double)run->options->config.rest.stillness,
            run->options->config_given ? "; this run reads --config instead, so a run without --config "
                                                    "takes them" : "");
}

/* A setting changed live (tracker_setting_t), said; -1 when the payload is not one. */
static int take_setting(node_run_t *run, const lcm_recv_buf_t *rbuf)
{
    char error[512];
    const int taken = node_setting_take_message(&run->node, &run->options->config, rbuf->data, (int)rbuf->data_size,
                                                error, sizeof error);
    if (taken == 1) {
        fprintf(stderr, "hkf-filter: stillness %.3g taken live; HOLD's wander now %.3f deg^2\n",
                (double)run->options->config.rest.stillness, (double)run->node.rest.result.wander);
    } else if (taken == 0) {
        fprintf(stderr, "hkf-filter: a live setting refused: %s\n", error);
    }
    return taken;
}

static void on_command(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    node_run_t *run = user;
    hkf_tracker_command_t command;
    if (hkf_tracker_command_t_decode(rbuf->data, 0, (int)rbuf->data_size, &command) < 0) {
        if (take_setting(run, rbuf) < 0) node_run_report_decode_error(run, channel, "");
        return;
    }
    if (command.command == HKF_TRACKER_COMMAND_T_SAVE_SETTINGS) {
        save_settings(run);
    } else if (filter_node_command(&run->node, &command) != 0) {
        ++run->unknown_commands;
        if (run->reported_unknown_commands++ < 5) { /* a flood must not flood the terminal */
            fprintf(stderr, "hkf-filter: unknown command %d on %s ignored%s\n", command.command, channel,
                    run->reported_unknown_commands == 5 ? " (no more such messages; counted)" : "");
        }
    }
}

/* The live URLs' file:// rules (lcm_file_url.h), before LCM opens either: the input reads a regular
 * file; the output writes none of the run's other files. 0, or -1 with the reason. */
static int check_live_urls(const node_options_t *o, lcm_file_url_t *input, lcm_file_url_t *output)
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
    count = node_run_paths_to_keep(o, NULL, keep);
    if (input->is_file) {
        keep[count++] = input->path;
    }
    return lcm_file_url_check(o->output_url, "output", keep, count, "hkf-filter", output);
}

/* The LCM providers of a live run, subscribed: the input (which is also the output when the URLs are the
 * same; run->out_lcm is set), or NULL (said). */
static lcm_t *open_live(node_run_t *run)
{
    const node_options_t *o = run->options;
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

int node_run_live(node_run_t *run)
{
    const node_options_t *o = run->options;
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
    if (node_run_open_csv(run, url_files, files) != 0 || (in = open_live(run)) == NULL) {
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

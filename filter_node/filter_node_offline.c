/*
 * filter_node_offline.c - hkf-filter --offline (see filter_node_offline.h).
 */
#include "filter_node_offline.h"
#include "node_settings_live.h"

#include <string.h>

#include "lcm_log_reader.h"
#include "node_schedule.h"
#include "message_decode.h"
#include "pose_csv.h"

#define MESSAGE_MAX 65536 /* bytes; hkf's messages take under 200 */

typedef struct {
    const filter_node_offline_t *options;
    lcm_log_writer_t *out;
    filter_node_offline_report_t *report;
} output_t;

/* One message into the output log (when there is one). */
static void write_event(output_t *output, int64_t timestamp, const char *channel, const void *data, int size)
{
    if (output->out != NULL && (size < 0 || lcm_log_writer_write(output->out, timestamp, channel, data, size) != 0)) {
        output->report->write_failed = 1;
    }
}

/* A pose, and after a pose that is not extrapolated the status that goes with it (the CSV has both). */
static void write_pose(output_t *output, const filter_node_t *node, int64_t timestamp, const hkf_head_pose_t *pose)
{
    unsigned char buffer[512];
    hkf_tracker_status_t status;
    const int size = hkf_head_pose_t_encoded_size(pose);
    filter_node_status(node, pose, &status);
    const int status_size = hkf_tracker_status_t_encoded_size(&status);
    if (output->options->csv != NULL && pose_csv_write(output->options->csv, pose, &status) != 0) {
        output->report->csv_failed = 1;
    }
    ++output->report->poses_written;
    write_event(output, timestamp, output->options->output_channel, buffer,
                size <= (int)sizeof buffer ? hkf_head_pose_t_encode(buffer, 0, size, pose) : -1);
    if (!pose->extrapolated) {
        write_event(output, timestamp, output->options->status_channel, buffer,
                    status_size <= (int)sizeof buffer ? hkf_tracker_status_t_encode(buffer, 0, status_size, &status) : -1);
    }
}

static void handle_command(filter_node_t *node, output_t *output, const void *data, int size)
{
    hkf_tracker_command_t command;
    char error[512];
    if (hkf_tracker_command_t_decode(data, 0, size, &command) < 0) {
        const int taken = output->options->config != NULL
                              ? node_setting_take_message(node, output->options->config, data, size, error, sizeof error)
                              : -1;
        node->counts.decode_errors += taken < 0;
        output->report->unknown_commands += taken == 0;
    } else if (command.command == HKF_TRACKER_COMMAND_T_SAVE_SETTINGS) {
        ++node->counts.commands; /* a replay writes no file */
    } else if (filter_node_command(node, &command) != 0) {
        ++output->report->unknown_commands;
    }
}

/* What the node publishes between measurements (node_schedule.h) up to log time `now`, each pose
 * written at the time it was due. */
static void publish_due(filter_node_t *node, node_schedule_t *schedule, output_t *output, int64_t now)
{
    hkf_head_pose_t pose;
    int64_t due;
    while (node_schedule_next(schedule, node, now, &pose, &due)) {
        write_pose(output, node, due, &pose);
    }
}

static void handle_measurement(filter_node_t *node, output_t *output, const void *data, int size, int64_t timestamp)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    if (message_decode_measurement(data, size, &m) != 0) {
        ++node->counts.decode_errors;
        output->report->long_model_ids += (unsigned long)message_model_id_too_long(data, size);
        return;
    }
    if (filter_node_receive(node, &m, timestamp, &pose)) {
        write_pose(output, node, timestamp, &pose);
    }
    hkf_head_pose_measurement_t_decode_cleanup(&m);
}

int filter_node_offline(filter_node_t *node, const filter_node_offline_t *options, FILE *in, lcm_log_writer_t *out,
                        filter_node_offline_report_t *report)
{
    static unsigned char data[MESSAGE_MAX];
    lcm_log_reader_t reader;
    lcm_log_event_t event;
    output_t output;
    node_schedule_t schedule;
    memset(report, 0, sizeof *report);
    node_schedule_init(&schedule, options->tick_us, 0); /* a log has no late subscribers: one LOST per silence */
    output.options = options;
    output.out = out;
    output.report = report;
    if (lcm_log_reader_open(&reader, in) != 0) {
        return -1;
    }
    while (lcm_log_reader_next(&reader, &event, data, (int)sizeof data)) {
        if (options->stop_requested != NULL && options->stop_requested()) {
            report->stopped = 1;
            break;
        }
        if (report->write_failed) {
            break; /* the disk is full: no use filtering on */
        }
        const int ours = strcmp(event.channel, options->input_channel) == 0 ||
                         strcmp(event.channel, options->command_channel) == 0;
        if (ours) {
            publish_due(node, &schedule, &output, event.timestamp);
        }
        if (ours && !event.data_read) {
            ++node->counts.decode_errors; /* far too large to be one of hkf's messages */
        } else if (strcmp(event.channel, options->command_channel) == 0) {
            handle_command(node, &output, data, event.datalen);
        } else if (strcmp(event.channel, options->input_channel) == 0) {
            handle_measurement(node, &output, data, event.datalen, event.timestamp);
        }
    }
    if (!report->stopped && !report->write_failed) {
        publish_due(node, &schedule, &output, INT64_MAX); /* the log ends: the estimator is silent from here on */
    }
    report->events = reader.events;
    report->skipped_bytes = reader.skipped;
    report->cut_bytes = report->stopped || report->write_failed ? 0 : lcm_log_reader_cut(&reader);
    return report->write_failed || report->csv_failed ? -1 : 0;
}

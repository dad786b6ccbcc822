/*
 * fuzz_node_log.c - libFuzzer target for hkf-filter --offline: arbitrary bytes
 * as the input LCM log, read by lcm_log_reader and filtered by
 * filter_node_offline (the code the program runs), into a log in memory.
 * Checks that the run ends, that every pose written reads back (so the output
 * log is whole) and is finite, and every status beside it, and that the reader's account adds up: whole
 * events + skipped + cut bytes never exceed the input. hkf-track's status line (track_monitor.h)
 * takes every pose written, as the launcher would, and counts each.
 *
 * Input: [rate byte][the log's bytes]; an odd rate byte adds --rate ticks.
 */
#define _GNU_SOURCE /* fmemopen, open_memstream */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "filter_node_offline.h"
#include "fuzz_checks.h"
#include "track_monitor.h"

#define CHECK(condition, what) fuzz_check((condition), "fuzz_node_log", (what))
#include "lcm_log_reader.h"

static unsigned long long logs, events; /* for the run's summary */

static void print_totals(void)
{
    fprintf(stderr, "fuzz_node_log: %llu logs, %llu events in total\n", logs, events);
}

/* A status written beside a pose: whole, its rest's values finite and in range. */
static void check_status(const unsigned char *data, int size)
{
    hkf_tracker_status_t status;
    int a;
    CHECK(hkf_tracker_status_t_decode(data, 0, size, &status) == size, "an output status does not decode");
    CHECK(status.rest >= HKF_TRACKER_STATUS_T_NO_REST && status.rest <= HKF_TRACKER_STATUS_T_MEASURED,
          "a rest's state unknown");
    CHECK(status.rest_progress >= 0.0f && status.rest_progress <= 1.0f, "a rest's progress outside 0..1");
    CHECK(isfinite(status.wander) && status.wander >= 0.0f, "a wander not finite or negative");
    for (a = 0; a < 3; ++a) {
        CHECK(isfinite(status.rest_spread[a]) && isfinite(status.rest_noise[a]) && isfinite(status.rest_drift[a]) &&
                  isfinite(status.rest_center[a]), "a rest's measurement not finite");
    }
    hkf_tracker_status_t_decode_cleanup(&status);
}

/* Reads the output log back: every pose whole and finite (and every status); returns how many poses. */
static unsigned long read_back(const char *bytes, size_t size)
{
    static unsigned char data[512];
    static track_monitor_t monitor;
    char line[512];
    lcm_log_reader_t reader;
    lcm_log_event_t event;
    unsigned long poses = 0;
    FILE *f;
    if (size == 0) {
        return 0;
    }
    memset(&monitor, 0, sizeof monitor);
    f = fmemopen((void *)bytes, size, "rb");
    CHECK(f != NULL && lcm_log_reader_open(&reader, f) == 0, "cannot read the output back");
    while (lcm_log_reader_next(&reader, &event, data, (int)sizeof data)) {
        hkf_head_pose_t pose;
        if (event.data_read && strcmp(event.channel, "HEAD_POSE_STATUS") == 0) {
            check_status(data, event.datalen);
            continue;
        }
        CHECK(event.data_read && strcmp(event.channel, "HEAD_POSE") == 0, "a stray event in the output");
        CHECK(hkf_head_pose_t_decode(data, 0, event.datalen, &pose) == event.datalen, "an output pose does not decode");
        fuzz_check_pose(&pose, "fuzz_node_log");
        CHECK(pose.position_status >= 0 && pose.position_status <= HKF_HEAD_POSE_T_LOST, "a position status unknown");
        hkf_head_pose_t_decode_cleanup(&pose);
        track_monitor_take_pose(&monitor, data, event.datalen);
        ++poses;
    }
    CHECK(monitor.decode_errors == 0 && (unsigned long)monitor.total_poses == poses, "the monitor missed a pose");
    track_monitor_line(&monitor, 1.0, 1.0, line, sizeof line);
    CHECK(reader.skipped == 0 && lcm_log_reader_cut(&reader) == 0, "the output log is damaged");
    fclose(f);
    return poses;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static node_config_t config;
    static filter_node_t node;
    static int registered;
    filter_node_offline_t options;
    filter_node_offline_report_t report;
    lcm_log_writer_t out;
    FILE *out_file;
    char *written = NULL;
    size_t written_size = 0;
    FILE *in;
    if (!registered) {
        registered = atexit(print_totals) == 0;
    }
    if (size < 1) {
        return 0;
    }
    node_config_defaults(&config);
    CHECK(filter_node_init(&node, &config) == 0, "filter_node_init failed on the defaults");
    options.input_channel = "HEAD_POSE_RAW";
    options.output_channel = "HEAD_POSE";
    options.command_channel = "HEAD_TRACKER_CMD";
    options.status_channel = "HEAD_POSE_STATUS";
    options.tick_us = (data[0] & 1) ? 1000 + 1000 * (int64_t)(data[0] >> 1) : 0;
    options.csv = NULL;
    options.stop_requested = NULL;
    options.config = &config; /* a live setting in the log applied, as the live node does */
    in = size > 1 ? fmemopen((void *)(data + 1), size - 1, "rb") : fopen("/dev/null", "rb");
    out_file = open_memstream(&written, &written_size);
    CHECK(in != NULL && out_file != NULL, "cannot open the in-memory files");
    lcm_log_writer_start(&out, out_file);

    CHECK(filter_node_offline(&node, &options, in, &out, &report) == 0, "filter_node_offline failed");
    CHECK(report.skipped_bytes >= 0 && report.cut_bytes >= 0 &&
              report.skipped_bytes + report.cut_bytes + (long)report.events * 29 <= (long)size - 1,
          "the reader's account exceeds the input");
    fclose(in);
    CHECK(lcm_log_writer_close(&out) == 0, "closing the output log failed");
    CHECK(read_back(written, written_size) == report.poses_written, "poses written and read back differ");
    free(written);
    ++logs;
    events += report.events;
    return 0;
}

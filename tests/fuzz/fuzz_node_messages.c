/*
 * fuzz_node_messages.c - libFuzzer target for hkf-filter's message handling:
 * arbitrary bytes as HEAD_POSE_RAW and HEAD_TRACKER_CMD payloads, decoded by
 * the generated LCM code and handed to filter_node (the code the live node and
 * --offline share), with arbitrary arrival times. Checks that every pose the
 * node would publish is finite (angles, rates, variances, R, centre) and that
 * it never publishes at a capture time its clock rule rejected. The same payloads go to hkf-track's
 * status line (track_monitor.h), as HEAD_POSE_RAW and as HEAD_POSE, and its line is made.
 *
 * Input: a sequence of [kind byte][length byte][arrival: 4 bytes][payload].
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "filter_node.h"
#include "fuzz_checks.h"
#include "message_decode.h"
#include "track_monitor.h"

#define CHECK(condition, what) fuzz_check((condition), "fuzz_node_messages", (what))

static unsigned long long messages; /* payloads handed to the decoders, for the run's summary */

static void print_messages(void)
{
    fprintf(stderr, "fuzz_node_messages: %llu messages in total\n", messages);
}

/* hkf-track's status line takes the payload as HEAD_POSE_RAW and as HEAD_POSE; now and then it makes its line. */
static void monitor_payload(track_monitor_t *monitor, uint8_t kind, const uint8_t *data, size_t length)
{
    char line[512];
    track_monitor_take_raw(monitor, data, (int)length);
    track_monitor_take_pose(monitor, data, (int)length);
    if (kind % 16 == 15) {
        track_monitor_line(monitor, 1.0, 1.0, line, sizeof line);
        CHECK(memchr(line, '\0', sizeof line) != NULL, "an unterminated status line");
    }
}

/* What the runners publish after each message (node_schedule.h's first part): the poses a call left queued and
 * the waiting frames whose deadline is at `now`, each checked, in order. */
static void drain_waiting(filter_node_t *node, int64_t now)
{
    hkf_head_pose_t pose;
    int64_t due, last = INT64_MIN;
    while (filter_node_await_next(node, now, &pose, &due)) {
        fuzz_check_pose(&pose, "fuzz_node_messages");
        CHECK(pose.utime >= last, "a waiting frame's pose out of order");
        last = pose.utime;
    }
}

/* The payload as a HEAD_POSE_RAW measurement through the node, arriving at `arrival`; every pose it would
 * publish is checked, and on kind 2 one extrapolated after it. */
static void measurement_payload(filter_node_t *node, uint8_t kind, const uint8_t *data, size_t length, int64_t arrival)
{
    hkf_head_pose_measurement_t m;
    hkf_head_pose_t pose;
    if (message_decode_measurement(data, (int)length, &m) != 0) {
        return;
    }
    CHECK(m.model != NULL && memchr(m.model, '\0', NODE_MODEL_NAME_MAX + 1) != NULL, "unterminated model");
    const unsigned long jumps = node->counts.clock_jumps;
    const int64_t reference = node->admission.last_utime, published = node->published_utime;
    if (filter_node_receive(node, &m, arrival, &pose)) {
        fuzz_check_pose(&pose, "fuzz_node_messages");
        /* at its capture time; a second model's measurement of an earlier frame at the newest frame's time
         * (the time reference, which it leaves as it was); moved on to the pose published before it (never
         * earlier); or an earlier frame that waited for the second model, published first, after every pose
         * published before */
        CHECK(pose.utime == m.utime ||
                  (pose.utime == reference && reference > m.utime && node->admission.last_utime == reference) ||
                  (pose.utime == published && published > m.utime && pose.extrapolated) ||
                  (pose.utime > published && pose.utime < m.utime && !pose.extrapolated),
              "a pose published for another capture time");
    }
    drain_waiting(node, arrival);
    CHECK(node->counts.clock_jumps == jumps || node->admission.last_utime == reference,
          "a stamp rejected as a clock jump became the time reference");
    if (kind % 4 == 2 && m.utime < INT64_MAX - 300000 &&
        filter_node_extrapolate(node, m.utime + (int64_t)(kind * 997), &pose)) {
        fuzz_check_pose(&pose, "fuzz_node_messages");
    }
    hkf_head_pose_measurement_t_decode_cleanup(&m);
}

/* The payload as a HEAD_TRACKER_CMD command to the node. */
static void command_payload(filter_node_t *node, const uint8_t *data, size_t length, int64_t arrival)
{
    hkf_tracker_command_t command;
    if (hkf_tracker_command_t_decode(data, 0, (int)length, &command) >= 0) {
        (void)filter_node_command(node, &command);
        drain_waiting(node, arrival); /* a command settles the waiting frames */
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static node_config_t config;
    static filter_node_t node;
    static track_monitor_t monitor;
    int64_t arrival = 1700000000000000LL;
    static int registered;
    if (!registered) {
        registered = atexit(print_messages) == 0;
    }
    node_config_defaults(&config);
    if (filter_node_init(&node, &config) != 0) {
        abort();
    }
    memset(&monitor, 0, sizeof monitor);
    while (size >= 6) {
        const uint8_t kind = data[0];
        size_t length = data[1];
        uint32_t step;
        memcpy(&step, data + 2, sizeof step);
        arrival += (int64_t)(step % 2000000u) - 1000; /* mostly forward, sometimes back a little */
        data += 6;
        size -= 6;
        length = length < size ? length : size;
        ++messages;
        monitor_payload(&monitor, kind, data, length);
        if (kind % 4 == 3) {
            command_payload(&node, data, length, arrival);
        } else {
            measurement_payload(&node, kind, data, length, arrival);
        }
        data += length;
        size -= length;
    }
    return 0;
}

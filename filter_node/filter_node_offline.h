/*
 * filter_node_offline.h - hkf-filter --offline: an LCM log of raw poses (and
 * commands) in, a log of filtered poses out, deterministically, through the
 * same filter_node code as the live node, in log time (each event's timestamp
 * is its arrival time). The input is read with lcm_log_reader, so a damaged or
 * hostile log is filtered as far as it is whole and its damage is reported.
 */
#ifndef FILTER_NODE_OFFLINE_H
#define FILTER_NODE_OFFLINE_H

#include <stdint.h>
#include <stdio.h>

#include "filter_node.h"
#include "lcm_log_writer.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const char *input_channel, *output_channel, *command_channel;
    const char *status_channel; /* each pose that is not extrapolated is followed by its tracker_status_t */
    int64_t tick_us; /* > 0: also poses extrapolated every tick_us of capture time (--rate) */
    FILE *csv;       /* NULL, or every pose written as CSV too */
    int (*stop_requested)(void); /* NULL, or polled between events: nonzero stops (a signal) */
    node_config_t *config; /* the run's settings, which a live setting in the log (tracker_setting_t) changes as it
                            * did live (NULL: such a setting is counted as an unknown command); SAVE_SETTINGS
                            * writes no file in a replay */
} filter_node_offline_t;

typedef struct {
    unsigned long events;           /* whole events in the input */
    long skipped_bytes;             /* damage between events, skipped */
    long cut_bytes;                 /* bytes at the end that are part of no whole event */
    unsigned long unknown_commands; /* commands with an unknown code, ignored */
    unsigned long long_model_ids;   /* measurements not decoded: a model id over MODEL_NAME_MAX */
    unsigned long poses_written;
    int write_failed;               /* writing the output log failed (e.g. a full disk) */
    int csv_failed;                 /* writing the CSV failed */
    int stopped;                    /* stopped early by stop_requested; the output is whole so far */
} filter_node_offline_report_t;

/* Filters the log `in` (a seekable file) into `out` (NULL: poses not written,
 * only counted). Returns 0, or -1 if `in` is not seekable or a write failed
 * (the output log stops at the first failed write). */
int filter_node_offline(filter_node_t *node, const filter_node_offline_t *options, FILE *in, lcm_log_writer_t *out,
                        filter_node_offline_report_t *report);

#ifdef __cplusplus
}
#endif

#endif /* FILTER_NODE_OFFLINE_H */

/* node_run_offline.c - see node_run.h: hkf-filter --offline IN OUT: the files opened, the log filtered
 * (filter_node_offline.h), what was found in it said. */
#define _POSIX_C_SOURCE 200809L

#include <stdint.h>
#include <stdio.h>

#include "filter_node_offline.h"
#include "lcm_log_writer.h"
#include "lcm_wait.h"
#include "node_run.h"
#include "safe_files.h"

/* What an offline run found in its input, said: a stop, damage, a cut, undecodable messages. */
static void say_offline_report(const node_run_t *run, const filter_node_offline_report_t *report, int status)
{
    const node_options_t *o = run->options;
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
        fprintf(stderr, "hkf-filter: %lu of them%s\n", report->long_model_ids, NODE_RUN_LONG_MODEL_HINT);
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
    if (node_run_open_csv(run, NULL, 0) != 0) {
        fclose(in);
        (void)lcm_log_writer_close(out);
        return NULL;
    }
    return in;
}

int node_run_offline(node_run_t *run)
{
    const node_options_t *o = run->options;
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
    offline.status_channel = o->status_channel;
    offline.tick_us = o->rate_hz > 0.0 ? (int64_t)(1e6 / o->rate_hz) : 0;
    offline.csv = run->csv;
    offline.stop_requested = lcm_wait_stop_requested;
    offline.config = &run->options->config;
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

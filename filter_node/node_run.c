/* node_run.c - see node_run.h: what the live and the offline runner share. */
#define _POSIX_C_SOURCE 200809L

#include "node_run.h"

#include <stdio.h>

#include "pose_csv.h"
#include "safe_files.h"

void node_run_report_decode_error(node_run_t *run, const char *channel, const char *hint)
{
    ++run->node.counts.decode_errors;
    if (run->reported_decode_errors++ < 5) {
        fprintf(stderr, "hkf-filter: a message on %s did not decode%s; counted and skipped%s\n", channel, hint,
                run->reported_decode_errors == 5 ? " (no more such messages)" : "");
    }
}

void node_run_say_rest(node_run_t *run)
{
    const node_rest_t *r = &run->node.rest;
    char text[400];
    if (r->spoiled_count > run->said_spoiled && run->said_spoiled < NODE_RUN_SPOILED_SAID) {
        node_rest_describe_spoiled(r, text, sizeof text);
        fprintf(stderr, "hkf-filter: %s\n", text);
    }
    if (r->measured_count > run->said_measured) {
        node_rest_describe_measured(r, text, sizeof text);
        fprintf(stderr, "hkf-filter: %s\n", text);
    }
    run->said_spoiled = r->spoiled_count;
    run->said_measured = r->measured_count;
}

void node_run_say_rest_summary(const filter_node_t *node, FILE *to)
{
    const node_rest_t *r = &node->rest;
    char text[400];
    hkf_real_t wander = 0;
    if (r->measured) {
        node_rest_describe_measured(r, text, sizeof text);
        fprintf(to, "hkf-filter: the player's rest: %lu measured, %lu spoiled (%lu of them refused: the head moved "
                    "through it); the last %s\n", r->measured_count, r->spoiled_count, r->refused_count, text);
    } else {
        (void)hkf_get_wander(&node->filter, &wander);
        fprintf(to, "hkf-filter: the player's rest: none measured (%lu spoiled, %lu of them refused: the head moved "
                    "through it); the built-in wander %.3f deg^2 held\n", r->spoiled_count, r->refused_count, (double)wander);
    }
}

/* The paths this run reads or writes, other than `except`: a file it opens
 * for writing must be none of them. Returns how many are in keep. */
int node_run_paths_to_keep(const node_options_t *o, const char *except, const char **keep)
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
int node_run_outputs_distinct(const node_options_t *o)
{
    const char *const outputs[] = {o->offline_out, o->csv_path};
    const char *keep[3 + 8];
    int i, k, count;
    for (i = 0; i < 2; ++i) {
        if (outputs[i] == NULL) {
            continue;
        }
        count = node_run_paths_to_keep(o, outputs[i], keep);
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

/* --csv, with its header (outputs_distinct has checked it is no other file of the run; live, `keep`
 * holds the logs the LCM URLs name). */
int node_run_open_csv(node_run_t *run, const char *const *keep, int count)
{
    const node_options_t *o = run->options;
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

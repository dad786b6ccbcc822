/*
 * hkf-track: the whole live tracker in one command (hkf-estimator, hkf-filter
 * and, with --opentrack, hkf-opentrack), a status line a second, and the
 * programs' summaries at the end. hkf-track --help says more.
 */
#define _POSIX_C_SOURCE 200809L

#include <signal.h>
#include <stdio.h>
#include <string.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "clocks.h"
#include "lcm_wait.h"
#include "safe_files.h"
#include "track_exclusive.h"
#include "track_monitor.h"
#include "track_options.h"
#include "track_programs.h"
#include "view_tracker.h"

static const char *signal_name(int signal_number)
{
    return signal_number == SIGINT ? "SIGINT" : signal_number == SIGTERM ? "SIGTERM" : "SIGHUP";
}

/* Status lines until a stop request, --seconds, or a program's end; the index of the program that ended, or -1. */
static int watch(const track_options_t *o, lcm_t *lcm, track_monitor_t *monitor, track_programs_t *programs,
                 view_tracker_t *view)
{
    const int64_t started = clock_monotonic_us();
    int64_t last_line = started, next_line = started + 1000000;
    char line[1024];
    while (!lcm_wait_stop_requested()) {
        int64_t now = clock_monotonic_us();
        if (o->seconds > 0.0 && (double)(now - started) >= o->seconds * 1e6) return -1;
        if (lcm_wait_and_handle(lcm, lcm_wait_time(next_line, now), "hkf-track") < 0) return -1;
        if (clock_monotonic_us() >= next_line) { /* a line a second; twice a second while the rest counts down */
            const int64_t at = clock_monotonic_us();
            track_monitor_line(monitor, (double)(at - started) / 1e6, (double)(at - last_line) / 1e6, line, sizeof line);
            printf("%s\n", line);
            fflush(stdout);
            if (view != NULL) view_tracker_line(view, line); /* the page shows this very line */
            last_line = at;
            next_line += track_monitor_resting(monitor) ? 500000 : 1000000;
        }
        if (view != NULL) view_tracker_tick(view, clock_monotonic_us());
        int ended = track_programs_reap(programs);
        if (ended >= 0) return ended;
    }
    return -1;
}

/* What the end says: 0 for the source's end or a stop request, 1 for a program that failed. */
static int report_end(const track_programs_t *programs, int ended)
{
    const track_program_t *program = ended >= 0 ? &programs->program[ended] : NULL;
    if (program != NULL && strcmp(program->name, "hkf-estimator") == 0 && program->status == 0) {
        printf("hkf-track: the source ended\n");
        return 0;
    }
    if (program != NULL) {
        fprintf(stderr, "hkf-track: %s stopped with status %d; see %s\n", program->name, program->status,
                program->log);
        return 1;
    }
    if (lcm_wait_stop_requested()) printf("hkf-track: %s: stopping\n", signal_name(lcm_wait_stop_signal()));
    return 0;
}

/* The other programs' exit: 1 when one failed (not stopped cleanly by SIGINT). */
static int report_failures(const track_programs_t *programs, int ended)
{
    int failed = 0;
    for (int i = 0; i < programs->count; ++i) {
        const track_program_t *program = &programs->program[i];
        if (i == ended || program->status == 0 || program->status == -SIGINT) continue;
        fprintf(stderr, "hkf-track: %s exited with status %d; see %s\n", program->name, program->status, program->log);
        failed = 1;
    }
    return failed;
}

/* 1 when a program exited with 2: it refused the command line hkf-track passed on. */
static int refused_arguments(const track_programs_t *programs)
{
    for (int i = 0; i < programs->count; ++i) {
        if (programs->program[i].status == 2) return 1;
    }
    return 0;
}

/* With --view: the live view in this process (view_tracker.h), on the programs' LCM. NULL without --view;
 * view itself once started; NULL with *failed set when it could not start (said). */
static view_tracker_t *start_view(const track_options_t *o, lcm_t *lcm, view_tracker_t *view, int *failed)
{
    view_settings_t settings = VIEW_DEFAULT_SETTINGS;
    *failed = 0;
    if (o->view == NULL) return NULL;
    settings.listen = o->view;
    if (view_tracker_start(view, lcm, &settings) != 0) {
        view_tracker_stop(view);
        *failed = 1;
        return NULL;
    }
    return view;
}

static int run(const track_options_t *o, track_programs_t *programs)
{
    static track_monitor_t monitor;
    static view_tracker_t view_storage;
    view_tracker_t *view;
    int view_failed;
    track_exclusive_t exclusive;
    if (track_programs_make_log_folder(o->logs) != 0) return 1;
    if (track_programs_check_inputs(programs, o, o->logs) != 0) return 1; /* no log over an input: nothing started */
    if (track_exclusive_claim(&exclusive, o->lcm_url, o->logs) != 0) return 2; /* another tracker: nothing started */
    lcm_t *lcm = lcm_create(o->lcm_url); /* resolved by track_options_parse */
    if (lcm == NULL) {
        fprintf(stderr, "hkf-track: LCM could not start on %s\n", o->lcm_url);
        track_exclusive_release(&exclusive);
        return 1;
    }
    view = start_view(o, lcm, &view_storage, &view_failed);
    if (view_failed || track_monitor_start(&monitor, lcm, o->camera != NULL || o->realtime) != 0 ||
        track_programs_start(programs, o->logs) != 0) {
        if (view != NULL) view_tracker_stop(view);
        lcm_destroy(lcm);
        track_exclusive_release(&exclusive);
        return 1;
    }
    printf("hkf-track: logs in %s; Ctrl-C stops\n", o->logs);
    printf("hkf-track: when your face is found, look at the screen's centre and keep still while the line "
           "counts down: hkf-filter measures how your resting head pose wanders, to hold the view still at rest "
           "(again after each recentre)\n");
    fflush(stdout);
    const int64_t started = clock_monotonic_us();
    int ended = watch(o, lcm, &monitor, programs, view);
    int status = report_end(programs, ended);
    track_programs_stop(programs);
    if (view != NULL) view_tracker_stop(view);
    int lost = track_programs_summaries(programs);
    status |= report_failures(programs, ended);
    printf("hkf-track: %ld filtered poses in %.1f s\n", monitor.total_poses,
           (double)(clock_monotonic_us() - started) / 1e6);
    lcm_destroy(lcm);
    track_exclusive_release(&exclusive);
    if (fflush(stdout) != 0 || ferror(stdout)) status = 1;
    if (refused_arguments(programs)) return 2; /* a program refused what hkf-track passed on: a bad command line */
    return status != 0 || lost > 0 ? 1 : 0;
}

int main(int argc, char **argv)
{
    static track_options_t options;
    static track_programs_t programs;
    safe_files_fail_writes_past_size_limit();
    int parsed = track_options_parse(argc, argv, &options);
    if (parsed != 0) return parsed == 1 ? 0 : 2;
    if (track_programs_plan(&programs, &options) != 0) return 2;
    lcm_wait_stop_on_signals();
    return run(&options, &programs);
}

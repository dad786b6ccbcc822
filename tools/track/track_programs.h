/*
 * track_programs.h - the programs hkf-track runs: their command lines, started
 * each in its own process group with its output in a log, watched, stopped in
 * order, and their summaries read back from the logs.
 */
#ifndef TRACK_PROGRAMS_H
#define TRACK_PROGRAMS_H

#include <stddef.h>
#include <sys/types.h>

#include "track_options.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TRACK_PROGRAMS 4      /* hkf-opentrack (to opentrack, to FlightGear), hkf-filter, hkf-estimator */
#define TRACK_MAX_ARGS 64
#define TRACK_TEXT_SIZE 16384 /* the characters of all arguments */
#define TRACK_PATH_SIZE 4096

typedef struct {
    const char *name;      /* the program */
    const char *log_name;  /* its log's, LOGS/LOG_NAME.log: the name, or the bridge's to FlightGear */
    char *argv[TRACK_MAX_ARGS + 1];
    int argc;
    char log[TRACK_PATH_SIZE];
    pid_t pid;
    int running;
    int status; /* its exit code, or minus the signal that ended it */
    int stopped; /* hkf-track stopped it (Ctrl-C, a stop): an empty log is then no lost output */
} track_program_t;

typedef struct {
    track_program_t program[TRACK_PROGRAMS]; /* in start order: the consumers first, so no pose is missed */
    int count;
    char text[TRACK_TEXT_SIZE];
    size_t used;
} track_programs_t;

/* The command lines for o: the programs beside hkf-track (installed), in the
 * build tree it runs from, or in o->build. 0, or 2 with the reason on stderr
 * (a program missing, arguments too long). */
int track_programs_plan(track_programs_t *p, const track_options_t *o);

/* Starts each program with its output in LOGS/LOG_NAME.log, prints its command
 * line, and waits 0.3 s before the next one so the subscribers listen before
 * the estimator publishes. 0, or 1 (said) when a log or a process could not
 * be made; the programs started are then stopped. */
int track_programs_start(track_programs_t *p, const char *logs);

/* Notes every file the planned programs will read (safe_note_read, safe_note_folder): --source, hkf-filter's
 * config (--config, or the files it finds without one), hkf-estimator's models and specs; then checks that no
 * log in LOGS is one of them, or anything else an output may not be (safe_output_problem). 0, or 1 (said):
 * nothing may start. Call before any log is opened. */
int track_programs_check_inputs(const track_programs_t *p, const track_options_t *o, const char *logs);

/* mkdir -p logs: 0, or 1 (said). Before track_programs_start, which writes the logs there. */
int track_programs_make_log_folder(const char *logs);

/* The index of a program that has ended since the last call, or -1. */
int track_programs_reap(track_programs_t *p);

/* SIGINT to each program still running, the last started first; SIGKILL after
 * 5 s (said). Every program's status is known afterwards. */
void track_programs_stop(track_programs_t *p);

/* Prints each program's summary (its last count line, and its last line) and
 * returns how many logs were empty: their output was lost (said). */
int track_programs_summaries(const track_programs_t *p);

#ifdef __cplusplus
}
#endif

#endif /* TRACK_PROGRAMS_H */

/* track_programs.c - see track_programs.h. */
#define _GNU_SOURCE

#include "track_programs.h"

#include <ctype.h>
#include <limits.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "config_files.h"
#include "safe_files.h"

static void sleep_ms(long ms)
{
    struct timespec wait = {ms / 1000, (ms % 1000) * 1000000L};
    while (nanosleep(&wait, &wait) != 0 && errno == EINTR) {
    }
}

/* Copies text into the arguments' storage; NULL when it is full. */
static char *keep_text(track_programs_t *p, const char *text, size_t length)
{
    if (p->used + length + 1 > sizeof p->text) return NULL;
    char *copy = p->text + p->used;
    memcpy(copy, text, length);
    copy[length] = '\0';
    p->used += length + 1;
    return copy;
}

static int add(track_programs_t *p, track_program_t *program, const char *text)
{
    char *copy = program->argc < TRACK_MAX_ARGS ? keep_text(p, text, strlen(text)) : NULL;
    if (copy == NULL) return -1;
    program->argv[program->argc++] = copy;
    program->argv[program->argc] = NULL;
    return 0;
}

static int add_option(track_programs_t *p, track_program_t *program, const char *name, const char *value)
{
    if (value == NULL) return 0;
    return add(p, program, name) == 0 && add(p, program, value) == 0 ? 0 : -1;
}

/* Adds the words of text as a shell splits them: blanks separate, '...' and "..." quote, \ escapes. */
static int add_words(track_programs_t *p, track_program_t *program, const char *text)
{
    char word[TRACK_PATH_SIZE];
    size_t length = 0;
    int in_word = 0;
    char quote = 0;
    for (const char *c = text;; ++c) {
        if (*c == '\0' || (!quote && isspace((unsigned char)*c))) {
            if (quote) return -1; /* an open quote */
            if (in_word && (word[length] = '\0', add(p, program, word) != 0)) return -1;
            if (*c == '\0') return 0;
            in_word = 0, length = 0;
            continue;
        }
        in_word = 1;
        if ((*c == '\'' || *c == '"') && (!quote || quote == *c)) {
            quote = quote ? 0 : *c;
            continue;
        }
        if (*c == '\\' && quote != '\'' && c[1] != '\0') ++c;
        if (length + 1 >= sizeof word) return -1;
        word[length++] = *c;
    }
}

/* The folders of hkf-filter and hkf-opentrack, and of hkf-estimator: o->build's tools/ and estimator/;
 * else hkf-track's own folder for all (installed), or, in a build tree, its own and ../estimator.
 * 0, or -1 when a path does not fit. */
static int program_folders(const track_options_t *o, char *tools, char *estimator, size_t size)
{
    char self[TRACK_PATH_SIZE], beside[TRACK_PATH_SIZE];
    int fits;
    if (o->build != NULL) {
        fits = snprintf(tools, size, "%s/tools", o->build) < (int)size;
        return fits && snprintf(estimator, size, "%s/estimator", o->build) < (int)size ? 0 : -1;
    }
    ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
    self[n > 0 ? n : 0] = '\0';
    char *slash = strrchr(self, '/');
    if (slash != NULL) *slash = '\0';
    fits = snprintf(tools, size, "%s", n > 0 ? self : ".") < (int)size &&
           snprintf(beside, sizeof beside, "%s/hkf-estimator", tools) < (int)sizeof beside;
    if (fits && access(beside, X_OK) == 0) return snprintf(estimator, size, "%s", tools) < (int)size ? 0 : -1;
    return fits && snprintf(estimator, size, "%s/../estimator", tools) < (int)size ? 0 : -1;
}

static track_program_t *next_program(track_programs_t *p, const char *name, const char *log_name,
                                     const char *folder)
{
    char path[TRACK_PATH_SIZE + 32];
    track_program_t *program = &p->program[p->count++];
    memset(program, 0, sizeof *program);
    program->name = name;
    program->log_name = log_name;
    if (snprintf(path, sizeof path, "%s/%s", folder, name) < (int)sizeof path) add(p, program, path);
    return program;
}

static int plan_opentrack(track_programs_t *p, const track_options_t *o, const char *tools)
{
    track_program_t *bridge = next_program(p, "hkf-opentrack", "hkf-opentrack", tools);
    return add_option(p, bridge, "--lcm-url", o->lcm_url) | add_option(p, bridge, "--host", o->opentrack_host) |
           add_option(p, bridge, "--port", o->opentrack_port) | add_words(p, bridge, o->opentrack_args);
}

/* --flightgear [HOST:]PORT: the bridge in its FlightGear mode, its log apart from opentrack's. */
static int plan_flightgear(track_programs_t *p, const track_options_t *o, const char *tools)
{
    track_program_t *bridge = next_program(p, "hkf-opentrack", "hkf-opentrack-flightgear", tools);
    return add(p, bridge, "--flightgear") | add_option(p, bridge, "--lcm-url", o->lcm_url) |
           add_option(p, bridge, "--host", o->flightgear_host) | add_option(p, bridge, "--port", o->flightgear_port) |
           add_words(p, bridge, o->flightgear_args);
}

static int plan_filter_and_estimator(track_programs_t *p, const track_options_t *o, const char *tools,
                                     const char *estimator_folder)
{
    track_program_t *filter = next_program(p, "hkf-filter", "hkf-filter", tools);
    char stillness[64];
    int failed = add_option(p, filter, "--lcm-url", o->lcm_url) | add_option(p, filter, "--config", o->config) |
                 add_option(p, filter, "--rate", o->rate);
    if (o->stillness != NULL) { /* checked: a number, short */
        snprintf(stillness, sizeof stillness, "stillness=%s", o->stillness);
        failed |= add_option(p, filter, "--set", stillness);
    }
    track_program_t *estimator = next_program(p, "hkf-estimator", "hkf-estimator", estimator_folder);
    failed |= add_option(p, estimator, "--source", o->camera != NULL ? o->camera : o->source) |
              add_option(p, estimator, "--lcm-url", o->lcm_url);
    if (o->realtime) failed |= add(p, estimator, "--realtime");
    failed |= add_option(p, estimator, "--model", o->model) | add_option(p, estimator, "--detector", o->detector) |
              add_option(p, estimator, "--second-model", o->second_model);
    return failed;
}

int track_programs_plan(track_programs_t *p, const track_options_t *o)
{
    char tools[TRACK_PATH_SIZE], estimator[TRACK_PATH_SIZE];
    memset(p, 0, sizeof *p);
    if (program_folders(o, tools, estimator, sizeof tools) != 0) {
        fprintf(stderr, "hkf-track: the programs' folder is too long a path\n");
        return 2;
    }
    if ((o->opentrack && plan_opentrack(p, o, tools) != 0) || (o->flightgear != NULL && plan_flightgear(p, o, tools) != 0) ||
        plan_filter_and_estimator(p, o, tools, estimator) != 0) {
        fprintf(stderr, "hkf-track: the programs' arguments are too long, or --opentrack-args or --flightgear-args "
                        "has an open quote\n");
        return 2;
    }
    for (int i = 0; i < p->count; ++i) {
        if (access(p->program[i].argv[0], X_OK) != 0) {
            fprintf(stderr, "hkf-track: %s is missing: install hkf (or, in a source tree, ./run build), or name the "
                            "build with --build DIR\n", p->program[i].argv[0]);
            return 2;
        }
    }
    return 0;
}

/* Prints argv as a shell would read it back: words with other than safe characters in '...'. */
static void print_command(char *const *argv)
{
    for (int i = 0; argv[i] != NULL; ++i) {
        const char *a = argv[i];
        int safe = a[0] != '\0' && strspn(a, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789@%+=:,./_-") ==
                                       strlen(a);
        fputs(i > 0 ? " " : "", stdout);
        if (safe) {
            fputs(a, stdout);
            continue;
        }
        putchar('\'');
        for (const char *c = a; *c != '\0'; ++c) {
            if (*c == '\'') {
                fputs("'\"'\"'", stdout); /* close the quote, a quoted ', open again */
            } else {
                putchar(*c);
            }
        }
        putchar('\'');
    }
}

/* In the child: its own process group (Ctrl-C reaches hkf-track only, which stops the programs in order),
 * SIGTERM should hkf-track die without stopping it, the signals' defaults, its output in the log. The
 * parent-death signal is asked for first, then the parent checked: hkf-track may have died between the
 * fork and the request, which the signal would never tell (the child is then an orphan: it goes). */
static void run_child(const track_program_t *program, int log, pid_t parent)
{
    int devnull;
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(1);
    devnull = open("/dev/null", O_RDONLY);
    setpgid(0, 0);
    signal(SIGXFSZ, SIG_DFL);
    signal(SIGPIPE, SIG_DFL);
    if (devnull < 0 || dup2(devnull, 0) < 0 || dup2(log, 1) < 0 || dup2(log, 2) < 0) _exit(127);
    execv(program->argv[0], program->argv);
    dprintf(2, "hkf-track: could not run %s: %s\n", program->argv[0], strerror(errno));
    _exit(127);
}

static int start_one(track_program_t *program, const char *logs)
{
    char reason[2 * TRACK_PATH_SIZE + 200];
    const pid_t parent = getpid();
    snprintf(program->log, sizeof program->log, "%s/%s.log", logs, program->log_name);
    if (safe_output_problem(program->log, reason, sizeof reason) != 0) { /* an input under another name, /proc ... */
        fprintf(stderr, "hkf-track: %s\n", reason);
        return 1;
    }
    int log = open(program->log, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (log < 0) {
        fprintf(stderr, "hkf-track: cannot write %s: %s\n", program->log, strerror(errno));
        return 1;
    }
    fflush(stdout);
    program->pid = fork();
    if (program->pid == 0) run_child(program, log, parent);
    close(log);
    if (program->pid < 0) {
        fprintf(stderr, "hkf-track: cannot start %s: %s\n", program->name, strerror(errno));
        return 1;
    }
    program->running = 1;
    printf("hkf-track: started %s (pid %ld): ", program->name, (long)program->pid);
    print_command(program->argv);
    printf("\n");
    fflush(stdout);
    return 0;
}

/* The folder the estimator reads SUB from (its main.cpp: <prefix>/share/hkf/SUB beside an installed <prefix>/bin,
 * else the build's), noted. */
static void note_estimator_data(const char *estimator_program, const char *sub, const char *built)
{
    char installed[TRACK_PATH_SIZE + 64], resolved[PATH_MAX];
    struct stat st;
    if (realpath(estimator_program, resolved) != NULL) {
        char *slash = strrchr(resolved, '/');
        if (slash != NULL) *slash = '\0'; /* its folder: bin */
        if (snprintf(installed, sizeof installed, "%s/../share/hkf/%s", resolved, sub) < (int)sizeof installed &&
            stat(installed, &st) == 0 && S_ISDIR(st.st_mode)) {
            safe_note_folder(installed);
            return;
        }
    }
    safe_note_folder(built);
}

int track_programs_check_inputs(const track_programs_t *p, const track_options_t *o, const char *logs)
{
    char reason[2 * TRACK_PATH_SIZE + 200], log[TRACK_PATH_SIZE];
    config_files_t configs;
    const char *models = getenv("HKF_MODELS_DIR");
    if (o->source != NULL) { /* no log may be the source, or one of its images, under another name */
        safe_note_read(o->source);
        safe_note_folder(o->source);
    }
    if (o->config != NULL) {
        safe_note_read(o->config);
    } else { /* hkf-filter's own search */
        config_files_find(&configs);
        for (int i = 0; i < configs.count; ++i) safe_note_read(configs.path[i]);
    }
    for (int i = 0; i < p->count; ++i) {
        if (strcmp(p->program[i].name, "hkf-estimator") != 0) continue;
        if (models != NULL && *models != '\0') {
            safe_note_folder(models);
        } else {
            note_estimator_data(p->program[i].argv[0], "models", HKF_DEFAULT_MODELS_DIR);
        }
        note_estimator_data(p->program[i].argv[0], "specs", HKF_DEFAULT_SPEC_DIR);
    }
    for (int i = 0; i < p->count; ++i) { /* every log, before the first is opened */
        snprintf(log, sizeof log, "%s/%s.log", logs, p->program[i].log_name);
        if (safe_output_problem(log, reason, sizeof reason) != 0) {
            fprintf(stderr, "hkf-track: %s; nothing started\n", reason);
            return 1;
        }
    }
    return 0;
}

/* mkdir -p: the folder and those above it. 0, or -1 with errno. */
static int make_folders(const char *path)
{
    char partial[TRACK_PATH_SIZE];
    if (snprintf(partial, sizeof partial, "%s", path) >= (int)sizeof partial) return errno = ENAMETOOLONG, -1;
    for (char *slash = strchr(partial + 1, '/');; slash = strchr(slash + 1, '/')) {
        if (slash != NULL) *slash = '\0';
        if (mkdir(partial, 0755) != 0 && errno != EEXIST) return -1;
        if (slash == NULL) return 0;
        *slash = '/';
    }
}

int track_programs_make_log_folder(const char *logs)
{
    if (make_folders(logs) != 0) {
        fprintf(stderr, "hkf-track: cannot make the log folder %s: %s\n", logs, strerror(errno));
        return 1;
    }
    return 0;
}

int track_programs_start(track_programs_t *p, const char *logs)
{
    for (int i = 0; i < p->count; ++i) {
        if (start_one(&p->program[i], logs) != 0) {
            track_programs_stop(p);
            return 1;
        }
        sleep_ms(300);
    }
    return 0;
}

static int status_of(int wait_status)
{
    return WIFSIGNALED(wait_status) ? -WTERMSIG(wait_status) : WEXITSTATUS(wait_status);
}

int track_programs_reap(track_programs_t *p)
{
    for (int i = 0; i < p->count; ++i) {
        track_program_t *program = &p->program[i];
        int wait_status;
        if (program->running && waitpid(program->pid, &wait_status, WNOHANG) == program->pid) {
            program->running = 0;
            program->status = status_of(wait_status);
            return i;
        }
    }
    return -1;
}

static void stop_one(track_program_t *program)
{
    int wait_status;
    program->stopped = 1;
    kill(-program->pid, SIGINT); /* its process group (run_child made it): what it started goes too */
    for (int waited = 0; waited < 5000; waited += 20) {
        if (waitpid(program->pid, &wait_status, WNOHANG) == program->pid) {
            program->running = 0;
            program->status = status_of(wait_status);
            return;
        }
        sleep_ms(20);
    }
    fprintf(stderr, "hkf-track: %s did not stop within 5 s; killed\n", program->name);
    kill(-program->pid, SIGKILL);
    waitpid(program->pid, &wait_status, 0);
    program->running = 0;
    program->status = status_of(wait_status);
}

void track_programs_stop(track_programs_t *p)
{
    for (int i = p->count - 1; i >= 0; --i) {
        if (p->program[i].running) stop_one(&p->program[i]);
    }
}

/* 1 when line is "NAME: " and a count: the program's summary line. */
static int is_count_line(const char *line, const char *name)
{
    size_t n = strlen(name);
    return strncmp(line, name, n) == 0 && line[n] == ':' && line[n + 1] == ' ' && isdigit((unsigned char)line[n + 2]);
}

static void blank_free(char *line)
{
    size_t n = strlen(line);
    while (n > 0 && (line[n - 1] == '\n' || line[n - 1] == '\r')) line[--n] = '\0';
}

/* Prints one program's summary; 1 when its log holds nothing. */
static int print_summary(const track_program_t *program)
{
    FILE *log = fopen(program->log, "r");
    char *line = NULL, *count = NULL, *last = NULL;
    size_t capacity = 0;
    while (log != NULL && getline(&line, &capacity, log) >= 0) {
        blank_free(line);
        if (strspn(line, " \t") == strlen(line)) continue;
        if (is_count_line(line, program->name)) free(count), count = strdup(line);
        free(last), last = strdup(line);
    }
    if (count != NULL) printf("%s\n", count);
    if (last != NULL && (count == NULL || strcmp(count, last) != 0)) printf("%s\n", last);
    fflush(stdout);
    const int lost = last == NULL && !program->stopped; /* stopped before its first line: nothing to lose */
    if (lost) {
        fprintf(stderr, "hkf-track: %s's log %s is empty: its output was lost (a full disk?)\n", program->name,
                program->log);
    } else if (last == NULL) {
        printf("hkf-track: %s was stopped before it wrote a line\n", program->name);
    }
    if (log != NULL) fclose(log);
    free(line), free(count);
    int empty = lost;
    free(last);
    return empty;
}

int track_programs_summaries(const track_programs_t *p)
{
    int lost = 0;
    for (int i = 0; i < p->count; ++i) lost += print_summary(&p->program[i]);
    return lost;
}

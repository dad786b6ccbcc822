/* lcm_file_url.c - see lcm_file_url.h. */
#define _XOPEN_SOURCE 700

#include "lcm_file_url.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lcm_log_reader.h"
#include "safe_files.h"

#define FILE_SCHEME "file://"

/* The last "mode=" among the URL's options (after '?', separated by '?' or '&'): 'r', 'w' or 'a'. */
static char mode_of(const char *options)
{
    char mode = 'r';
    const char *p = options;
    while (p != NULL && *p != '\0') {
        const size_t length = strcspn(p, "?&");
        if (length >= 5 && strncmp(p, "mode=", 5) == 0) {
            mode = length == 6 && (p[5] == 'w' || p[5] == 'a') ? p[5] : 'r'; /* LCM reads any other value as r */
        }
        p += length;
        p += *p != '\0';
    }
    return mode;
}

const char *lcm_url_resolve(const char *url)
{
    const char *environment = getenv("LCM_DEFAULT_URL");
    if (url != NULL && url[0] != '\0') {
        return url;
    }
    return environment != NULL && environment[0] != '\0' ? environment : LCM_URL_DEFAULT;
}

int lcm_file_url_parse(const char *url, lcm_file_url_t *u)
{
    const char *network, *options;
    size_t length;
    char mode;
    memset(u, 0, sizeof *u);
    if (url == NULL || strncmp(url, FILE_SCHEME, strlen(FILE_SCHEME)) != 0) {
        return 0;
    }
    network = url + strlen(FILE_SCHEME);
    length = strcspn(network, "?");
    options = network + length;
    if (length >= sizeof u->path) {
        return -1;
    }
    memcpy(u->path, network, length);
    u->path[length] = '\0';
    mode = mode_of(*options == '?' ? options + 1 : options);
    u->is_file = 1;
    u->writes = mode != 'r';
    u->appends = mode == 'a';
    return 0;
}

/* 1 when the file at path is empty or starts with an LCM log's sync word: what a log may be written over. */
static int empty_or_log(const char *path)
{
    char error[PATH_MAX + 64];
    unsigned char word[4];
    size_t got;
    FILE *f = safe_open_to_inspect(path, error, sizeof error);
    if (f == NULL) {
        return 0;
    }
    got = fread(word, 1, sizeof word, f);
    fclose(f);
    return got == 0 || (got == sizeof word && (((unsigned long)word[0] << 24) | ((unsigned long)word[1] << 16) |
                                               ((unsigned long)word[2] << 8) | word[3]) == LCM_LOG_SYNC_WORD);
}

/* The whole events in the log at path and the bytes cut off at its end; -1 when it cannot be read. */
static int count_events(const char *path, unsigned long *events, long *cut)
{
    char error[PATH_MAX + 64];
    static unsigned char data[1];
    lcm_log_reader_t reader;
    lcm_log_event_t event;
    FILE *f = safe_open_to_inspect(path, error, sizeof error);
    if (f == NULL || lcm_log_reader_open(&reader, f) != 0) {
        if (f != NULL) {
            fclose(f);
        }
        return -1;
    }
    while (lcm_log_reader_next(&reader, &event, data, 0) == 1) {
    }
    *events = reader.events;
    *cut = lcm_log_reader_cut(&reader) + reader.skipped;
    fclose(f);
    return 0;
}

/* The checks of an output file:// URL (lcm_file_url_check): 0, or -1 with why not on stderr. */
static int output_url_problem(const char *url, const char *role, const char *const *keep, int count,
                              const char *program, lcm_file_url_t *u)
{
    struct stat st;
    char reason[2 * PATH_MAX + 200];
    int i;
    for (i = 0; i < count; ++i) {
        if (keep[i] != NULL && safe_writes_over(u->path, keep[i])) {
            fprintf(stderr, "%s: the %s URL '%s' names %s'%s', which this run reads or writes; refusing to write over it\n",
                    program, role, url, safe_same_file(u->path, keep[i]) ? "" : "a file inside ", keep[i]);
            return -1;
        }
    }
    if (safe_output_problem(u->path, reason, sizeof reason) != 0) { /* an input by identity, /proc, a device */
        fprintf(stderr, "%s: the %s URL '%s': %s\n", program, role, url, reason);
        return -1;
    }
    if (stat(u->path, &st) == 0 && !empty_or_log(u->path)) { /* a video, an image, a config: never a log's place */
        fprintf(stderr, "%s: the %s URL '%s' names '%s', which is not an LCM log; refusing to write over it\n",
                program, role, url, u->path);
        return -1;
    }
    if (u->appends && stat(u->path, &st) == 0) {
        long cut = 0;
        if (count_events(u->path, &u->events_before, &cut) != 0) {
            fprintf(stderr, "%s: cannot read the log '%s' to append to it\n", program, u->path);
            return -1;
        }
    }
    return 0;
}

int lcm_file_url_check(const char *url, const char *role, const char *const *keep, int count, const char *program,
                       lcm_file_url_t *u)
{
    const int output = strcmp(role, "output") == 0;
    struct stat st;
    url = lcm_url_resolve(url);
    if (lcm_file_url_parse(url, u) != 0) {
        fprintf(stderr, "%s: the %s URL '%s' names a path longer than %d bytes\n", program, role, url, PATH_MAX - 1);
        return -1;
    }
    if (!u->is_file) {
        return 0;
    }
    if (u->path[0] == '\0') {
        fprintf(stderr, "%s: the %s URL '%s' names no file\n", program, role, url);
        return -1;
    }
    if (output != u->writes) {
        fprintf(stderr, "%s: the %s URL '%s' %s; add '?mode=%s'\n", program, role, url,
                output ? "would read the log, not write it" : "would write over the log it should read",
                output ? "w' (or '?mode=a" : "r");
        return -1;
    }
    if (stat(u->path, &st) == 0 && !S_ISREG(st.st_mode)) {
        fprintf(stderr, "%s: the %s URL '%s' names %s, not a regular file: LCM's file provider would %s\n", program,
                role, url, S_ISFIFO(st.st_mode) ? "a named pipe" : S_ISDIR(st.st_mode) ? "a folder" : "a device",
                S_ISFIFO(st.st_mode) ? "wait on it for ever" : "fail on it without a word");
        return -1;
    }
    if (!output) {
        if (stat(u->path, &st) != 0) {
            fprintf(stderr, "%s: cannot read '%s' (the %s URL): %s\n", program, u->path, role, strerror(errno));
            return -1;
        }
        safe_note_read(u->path); /* no output of this run may be it, under any name */
        return 0;
    }
    return output_url_problem(url, role, keep, count, program, u);
}

int lcm_file_url_verify(const lcm_file_url_t *u, unsigned long published, const char *program)
{
    unsigned long events = 0;
    long cut = 0;
    if (!u->is_file || !u->writes) {
        return 0;
    }
    if (count_events(u->path, &events, &cut) != 0) {
        fprintf(stderr, "%s: the log '%s' cannot be read back: the %lu events published to it are lost\n", program,
                u->path, published);
        return -1;
    }
    if (events - u->events_before != published || cut != 0 || events < u->events_before) {
        fprintf(stderr,
                "%s: the log '%s' holds %lu of the %lu events published to it%s (a full disk or a file-size limit?): "
                "data lost\n",
                program, u->path, events >= u->events_before ? events - u->events_before : 0UL, published,
                cut != 0 ? ", and a cut-off end" : "");
        return -1;
    }
    return 0;
}

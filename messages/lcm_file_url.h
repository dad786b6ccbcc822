/*
 * lcm_file_url.h - the safe-output rules (safe_files.h) for LCM's file://
 * provider, which writes an LCM log itself and reports nothing: it opens
 * whatever the URL names (a named pipe blocks it for ever, an input is
 * truncated), ignores failed writes and does not check its close. So a
 * program checks a file:// URL before lcm_create, and after lcm_destroy reads
 * the log back to see that every event it published is there.
 *
 * LCM's URL: file://PATH?mode=r|w|a (read by default; of several mode keys,
 * the last counts, as in lcm_parse_url).
 */
#ifndef LCM_FILE_URL_H
#define LCM_FILE_URL_H

#include <limits.h>

#ifdef __cplusplus
extern "C" {
#endif

/* LCM's own default URL (lcm_create's, when neither the program nor $LCM_DEFAULT_URL names one). */
#define LCM_URL_DEFAULT "udpm://239.255.76.67:7667?ttl=0"

/* The URL LCM opens for `url`, by lcm_create's rule: url itself; when it is NULL or empty,
 * $LCM_DEFAULT_URL; when that is unset or empty too, LCM_URL_DEFAULT. A program checks and opens
 * this one (lcm_file_url_check resolves it too), so an empty --lcm-url cannot slip a file:// URL
 * past the checks through the environment. */
const char *lcm_url_resolve(const char *url);

typedef struct {
    int is_file;                  /* a file:// URL: */
    int writes;                   /* mode w or a */
    int appends;                  /* mode a */
    char path[PATH_MAX];
    unsigned long events_before;  /* appending: the whole events the log held before */
} lcm_file_url_t;

/* Parses url into *u; 0, or -1 for a file:// URL whose path is too long. */
int lcm_file_url_parse(const char *url, lcm_file_url_t *u);

/* Checks url (resolved: lcm_url_resolve) before lcm_create. Any provider but file:// passes. A file:// URL
 * the program reads (role "input") must read (mode r) a regular file; one it
 * writes (role "output") must write (mode w or a), name none of the `count`
 * paths in `keep` (the run's inputs, config and other outputs) nor a file inside
 * one that is a folder, and be none yet, an empty file or an LCM log (a
 * video or an image is never a log's place, whatever the program's inputs). 0, or -1 with the reason on stderr (prefixed by
 * `program`). */
int lcm_file_url_check(const char *url, const char *role, const char *const *keep, int count, const char *program,
                       lcm_file_url_t *u);

/* After lcm_destroy: 0 when a file:// output holds `published` whole events
 * more than before, with nothing cut off; else -1 with what was lost on
 * stderr. 0 for any other provider. */
int lcm_file_url_verify(const lcm_file_url_t *u, unsigned long published, const char *program);

#ifdef __cplusplus
}
#endif

#endif /* LCM_FILE_URL_H */

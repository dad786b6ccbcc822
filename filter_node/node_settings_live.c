/* node_settings_live.c - see node_settings_live.h. */
#define _POSIX_C_SOURCE 200809L

#include "node_settings_live.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "config_files.h"
#include "message_decode.h"
#include "node_config_parts.h"

#define SAVED_FILE_MAX (1024 * 1024) /* a user's config file larger than this is not rewritten */

static const char *const kLiveKeys[] = {"stillness"};

static int is_live_key(const char *key)
{
    size_t i;
    for (i = 0; i < sizeof kLiveKeys / sizeof kLiveKeys[0]; ++i) {
        if (strcmp(key, kLiveKeys[i]) == 0) return 1;
    }
    return 0;
}

int node_setting_apply(filter_node_t *node, node_config_t *config, const char *key, const char *value, char *error,
                       size_t error_size)
{
    node_config_t *trial;
    node_assignment_t a;
    char key_text[32];
    int result = -1;
    if (!is_live_key(key)) {
        snprintf(error, error_size, "'%.63s' cannot change while hkf-filter runs (live: stillness)", key);
        return -1;
    }
    trial = malloc(sizeof *trial);
    if (trial == NULL) {
        snprintf(error, error_size, "out of memory");
        return -1;
    }
    *trial = *config;
    snprintf(key_text, sizeof key_text, "%s", key); /* a live key: short, and no model's (model.NAME.KEY) */
    a.key = key_text;
    a.value = value;
    a.origin = "live (tracker_setting_t)";
    if (node_config_apply(trial, NULL, &a, error, error_size) == 0 && node_config_check(trial, error, error_size) == 0) {
        *config = *trial; /* the run's settings, which --print-config's format and a save write */
        result = node_rest_set_stillness(&node->rest, &node->filter, config->rest.stillness) == HKF_OK ? 0 : -1;
        if (result != 0) snprintf(error, error_size, "the rest refused stillness %s", value);
        ++node->counts.commands;
    }
    free(trial);
    return result;
}

int node_setting_take_message(filter_node_t *node, node_config_t *config, const void *data, int size, char *error,
                              size_t error_size)
{
    hkf_tracker_setting_t setting;
    int taken;
    if (message_decode_setting(data, size, &setting) != 0) { /* its layout checked before anything is allocated */
        return -1;
    }
    taken = node_setting_apply(node, config, setting.key, setting.value, error, error_size) == 0;
    hkf_tracker_setting_t_decode_cleanup(&setting);
    return taken;
}

/* The user's file's text (a regular file up to SAVED_FILE_MAX), "" when there is none: a new buffer, or NULL
 * with the reason. */
static char *read_user_file(const char *path, char *error, size_t error_size)
{
    struct stat info;
    FILE *f;
    char *text = calloc(SAVED_FILE_MAX + 1, 1);
    size_t got;
    if (text == NULL || lstat(path, &info) != 0) {
        if (text == NULL) snprintf(error, error_size, "out of memory");
        return text; /* no file yet: "" */
    }
    if (!S_ISREG(info.st_mode) || info.st_size > SAVED_FILE_MAX || (f = fopen(path, "r")) == NULL) {
        snprintf(error, error_size, "%s is not a regular file up to 1 MiB that can be read: not rewritten", path);
        free(text);
        return NULL;
    }
    got = fread(text, 1, SAVED_FILE_MAX, f);
    if (ferror(f) || fclose(f) != 0 || memchr(text, '\0', got) != NULL) {
        snprintf(error, error_size, "%s could not be read as text: not rewritten", path);
        free(text);
        return NULL;
    }
    return text;
}

/* 1 when line (up to its newline) sets a live key at the top level: "KEY =" with blanks around. */
static int sets_live_key(const char *line)
{
    char key[32];
    size_t n = 0;
    while (*line == ' ' || *line == '\t') ++line;
    while (n + 1 < sizeof key && line[n] != '\0' && line[n] != '=' && line[n] != ' ' && line[n] != '\t' && line[n] != '\n') {
        key[n] = line[n];
        ++n;
    }
    key[n] = '\0';
    line += n;
    while (*line == ' ' || *line == '\t') ++line;
    return *line == '=' && is_live_key(key);
}

/* The old text with its top-level live-key lines dropped and the config's values first, into f. */
static int write_saved_text(FILE *f, const char *old, const node_config_t *config)
{
    int sections = 0, failed = 0;
    failed |= fprintf(f, "stillness = %.6g  # saved from a running hkf-filter (the live view, hkf-cmd)\n",
                      (double)config->rest.stillness) < 0;
    while (*old != '\0') {
        const char *end = strchr(old, '\n');
        const size_t length = end != NULL ? (size_t)(end - old) + 1 : strlen(old);
        const char *first = old + strspn(old, " \t");
        sections |= *first == '[';
        if (sections || !sets_live_key(old)) failed |= fwrite(old, 1, length, f) != length;
        old += length;
    }
    return failed ? -1 : 0;
}

/* The user's file's path, its folder made (mode 0700 where missing, as XDG asks). 0, or -1 with the reason. */
static int user_file(char *path, size_t path_size, char *error, size_t error_size)
{
    char folder[CONFIG_FILES_PATH_MAX];
    char *slash;
    if (config_files_user_path(path, (int)path_size) != 0) {
        snprintf(error, error_size, "no user config folder (HOME and XDG_CONFIG_HOME unset)");
        return -1;
    }
    snprintf(folder, sizeof folder, "%s", path);
    for (slash = strchr(folder + 1, '/'); slash != NULL; slash = strchr(slash + 1, '/')) {
        *slash = '\0';
        if (mkdir(folder, 0700) != 0 && errno != EEXIST) {
            snprintf(error, error_size, "cannot make the folder %s: %s", folder, strerror(errno));
            return -1;
        }
        *slash = '/';
    }
    return 0;
}

/* The file written at fresh read back as the node reads a config file, over the defaults: the same checks, and
 * the live keys as saved. 0, or -1 with the reason. */
static int read_back(const char *fresh, const node_config_t *config, char *error, size_t error_size)
{
    node_config_t *check = malloc(sizeof *check);
    int result = -1;
    if (check == NULL) {
        snprintf(error, error_size, "out of memory");
        return -1;
    }
    node_config_defaults(check);
    if (node_config_read_file(check, fresh, error, error_size) == 0 && node_config_check(check, error, error_size) == 0) {
        result = check->rest.stillness == config->rest.stillness ? 0 : -1;
        if (result != 0) snprintf(error, error_size, "%s does not read back the stillness saved", fresh);
    }
    free(check);
    return result;
}

/* The user's old file, if any, kept as BACKUP (a hard link: the old file itself, untouched). 0, or -1. */
static int keep_backup(const char *path, const char *backup)
{
    if (access(path, F_OK) != 0) return 0;
    if (unlink(backup) != 0 && errno != ENOENT) return -1;
    return link(path, backup);
}

int node_settings_save(const node_config_t *config, char *path, size_t path_size, char *error, size_t error_size)
{
    char fresh[CONFIG_FILES_PATH_MAX + 8], backup[CONFIG_FILES_PATH_MAX + 8];
    char *old;
    FILE *f;
    int failed;
    if (user_file(path, path_size, error, error_size) != 0 || (old = read_user_file(path, error, error_size)) == NULL) {
        return -1;
    }
    snprintf(fresh, sizeof fresh, "%s.new", path);
    snprintf(backup, sizeof backup, "%s.bak", path);
    (void)unlink(fresh); /* a save that stopped halfway */
    f = fopen(fresh, "wx");
    failed = f == NULL || write_saved_text(f, old, config) != 0;
    failed |= f != NULL && (fflush(f) != 0 || fsync(fileno(f)) != 0);
    failed |= f != NULL && fclose(f) != 0;
    free(old);
    if (failed) {
        snprintf(error, error_size, "writing %s failed: %s", fresh, strerror(errno));
    } else if (read_back(fresh, config, error, error_size) == 0) {
        if (keep_backup(path, backup) == 0 && rename(fresh, path) == 0) return 0; /* in its place at once */
        snprintf(error, error_size, "replacing %s failed: %s", path, strerror(errno));
    }
    (void)unlink(fresh);
    return -1;
}

/*
 * hkf-cmd - sends one command to hkf-filter (hkf.tracker_command_t on
 * HEAD_TRACKER_CMD): recenter (the loop-closure centre := the current
 * estimate; hkf-opentrack sends poses relative to it) or reset (forget the
 * track and the centre). For hotkey tools, scripts and simulator buttons.
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <string.h>

#include <lcm/lcm.h>

#include "arguments.h"
#include "clocks.h"
#include "hkf_tracker_command_t.h"
#include "hkf_tracker_setting_t.h"
#include "lcm_file_url.h"
#include "safe_files.h"


static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-cmd recenter|reset|save|stillness X [--lcm-url URL] [--channel C]\n"
            "Sends a command to a running hkf-filter.\n"
            "  recenter        the centre pose := the current head pose (opentrack's camera zero\n"
            "                  follows, through hkf-opentrack)\n"
            "  reset           forget the track and the centre; the next face starts anew\n"
            "  stillness X     how still the view holds at rest, at once: X times the measured wander\n"
            "                  (0 to 100; checked by hkf-filter as its config file's line)\n"
            "  save            hkf-filter writes the settings changed live into the user's config file\n"
            "                  (~/.config/hkf/hkf-filter.conf; the old one kept as .bak)\n"
            "  --lcm-url URL   LCM provider (default " LCM_URL_DEFAULT ")\n"
            "  --channel C     command channel (default HEAD_TRACKER_CMD)\n"
            "  --help          this text (--version: the version)\n");
}

/* Publishes command, or setting where command is NULL, on channel of the LCM URL (resolved as LCM resolves it,
 * then checked): 0, or 1 (said). */
static int send(const char *lcm_url, const char *channel, const hkf_tracker_command_t *command,
                const hkf_tracker_setting_t *setting)
{
    lcm_file_url_t log_file;
    lcm_t *lcm;
    int result;
    lcm_url = lcm_url_resolve(lcm_url); /* '': $LCM_DEFAULT_URL, as LCM reads it */
    if (lcm_file_url_check(lcm_url, "output", NULL, 0, "hkf-cmd", &log_file) != 0) {
        return 1; /* a file:// URL to a named pipe, a device, a file that is no log or in read mode */
    }
    lcm = lcm_create(lcm_url);
    if (lcm == NULL) {
        fprintf(stderr, "hkf-cmd: cannot open LCM provider '%s'\n", lcm_url);
        return 1;
    }
    result = command != NULL ? hkf_tracker_command_t_publish(lcm, channel, command)
                             : hkf_tracker_setting_t_publish(lcm, channel, setting);
    lcm_destroy(lcm);
    if (result != 0) {
        fprintf(stderr, "hkf-cmd: publishing on %s failed\n", channel);
        return 1;
    }
    return lcm_file_url_verify(&log_file, 1, "hkf-cmd") != 0 ? 1 : 0;
}

/* The verb (and stillness's value) into command or setting: 0, or 2 (said). */
static int read_verb(const char *verb, const char *value, hkf_tracker_command_t *command, hkf_tracker_setting_t *setting,
                     int *is_setting)
{
    double stillness;
    *is_setting = strcmp(verb, "stillness") == 0;
    command->command = strcmp(verb, "recenter") == 0 || strcmp(verb, "recentre") == 0 ? HKF_TRACKER_COMMAND_T_RECENTER
                       : strcmp(verb, "reset") == 0                                   ? HKF_TRACKER_COMMAND_T_RESET
                       : strcmp(verb, "save") == 0 ? HKF_TRACKER_COMMAND_T_SAVE_SETTINGS
                                                   : 0;
    if (command->command == 0 && !*is_setting) {
        fprintf(stderr, "hkf-cmd: unknown command '%s': recenter, reset, stillness X or save\n", verb);
        return 2;
    }
    if (*is_setting != (value != NULL)) {
        fprintf(stderr, "hkf-cmd: %s\n", value == NULL ? "stillness wants a value: hkf-cmd stillness X (0 to 100)"
                                                         : "only stillness takes a value");
        return 2;
    }
    if (*is_setting && (strlen(value) > HKF_TRACKER_SETTING_T_TEXT_MAX || !argument_number(value, 0.0, 100.0, &stillness))) {
        fprintf(stderr, "hkf-cmd: stillness wants a multiple of the measured wander from 0 to 100, not '%.80s'\n", value);
        return 2;
    }
    command->utime = setting->utime = clock_wall_us();
    setting->key = (char *)"stillness";
    setting->value = (char *)value;
    return 0;
}

int main(int argc, char **argv)
{
    const char *lcm_url = LCM_URL_DEFAULT, *channel = "HEAD_TRACKER_CMD", *verb = NULL, *value = NULL;
    hkf_tracker_command_t command;
    hkf_tracker_setting_t setting;
    int i, is_setting;
    for (i = 1; i < argc; ++i) {
        if (argument_help_or_version(argv[i], "hkf-cmd", usage)) {
            return 0;
        } else if (strcmp(argv[i], "--lcm-url") == 0 && i + 1 < argc) {
            lcm_url = argv[++i];
        } else if (strcmp(argv[i], "--channel") == 0 && i + 1 < argc) {
            channel = argv[++i];
        } else if (argv[i][0] != '-' && (verb == NULL || value == NULL)) {
            *(verb == NULL ? &verb : &value) = argv[i];
        } else {
            fprintf(stderr, "hkf-cmd: unknown or incomplete argument '%s' (see --help)\n", argv[i]);
            return 2;
        }
    }
    if (channel[0] == '\0' || strlen(channel) > LCM_MAX_CHANNEL_NAME_LENGTH) {
        fprintf(stderr, "hkf-cmd: a channel name has 1 to %d characters, not '%.80s'\n", LCM_MAX_CHANNEL_NAME_LENGTH,
                channel);
        return 2;
    }
    if (verb == NULL) {
        fprintf(stderr, "hkf-cmd: which command? recenter, reset, stillness X or save (see --help)\n");
        return 2;
    }
    if (read_verb(verb, value, &command, &setting, &is_setting) != 0) return 2;
    safe_files_fail_writes_past_size_limit();
    if (send(lcm_url, channel, is_setting ? NULL : &command, &setting) != 0) return 1;
    printf("hkf-cmd: %s%s%s sent on %s\n", verb, value != NULL ? " " : "", value != NULL ? value : "", channel);
    return 0;
}

/*
 * test_node_settings_live.c - a setting changed while hkf-filter runs and saved (filter_node/node_settings_live.c):
 * the value through the config file's checks, taken into the run's config and the node at once; the save
 * writes the user's file with every other line kept, reads it back before it replaces the old one (kept as
 * .bak), and refuses, the old file untouched, what would not read back.
 */
#define _DEFAULT_SOURCE /* mkdtemp, setenv, M_PI */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <cmocka.h>

#include "node_keys.h"
#include "node_settings_live.h"
#include "node_test_support.h"

static char home[256], path[4096];

static void write_text(const char *file, const char *text)
{
    FILE *f = fopen(file, "w");
    assert_non_null(f);
    assert_int_equal(fputs(text, f) >= 0, 1);
    assert_int_equal(fclose(f), 0);
}

static char *read_text(const char *file)
{
    static char text[4096];
    FILE *f = fopen(file, "r");
    size_t n;
    if (f == NULL) return NULL;
    n = fread(text, 1, sizeof text - 1, f);
    text[n] = '\0';
    fclose(f);
    return text;
}

static int with_home(void **state)
{
    char folder[300];
    snprintf(home, sizeof home, "/tmp/hkf-settings-XXXXXX");
    assert_non_null(mkdtemp(home));
    assert_int_equal(setenv("HOME", home, 1), 0);
    assert_int_equal(unsetenv("XDG_CONFIG_HOME"), 0);
    snprintf(folder, sizeof folder, "%s/.config/hkf", home);
    snprintf(path, sizeof path, "%s/hkf-filter.conf", folder);
    return setup_with_rest(state);
}

static int remove_home(void **state)
{
    char command[400];
    (void)state;
    snprintf(command, sizeof command, "rm -rf '%s'", home);
    return system(command);
}

/* A rest measured (a still head with a slow 0.6 deg sine on pitch): its wander is the filter's. */
static void measure_a_rest(void)
{
    hkf_head_pose_t pose;
    int i;
    for (i = 0; i < 70; ++i) {
        hkf_head_pose_measurement_t m =
            measurement(T0 + i * FRAME_US, 1, 0.6 * sin(2.0 * M_PI * i / 40.0), 0.0, 0.0);
        assert_int_equal(filter_node_receive(&node, &m, m.utime, &pose), 1);
    }
    assert_true(node.rest.measured);
}

/* The value through the file's checks: a non-number, one beyond HKF_MAX_STILLNESS and a key that cannot change
 * live are refused with nothing changed; 3 is taken into the config and the filter's wander at once. */
static void test_stillness_taken_live(void **state)
{
    char error[256];
    hkf_real_t before, after;
    (void)state;
    measure_a_rest();
    assert_int_equal(hkf_get_wander(&node.filter, &before), HKF_OK);
    assert_int_equal(node_setting_apply(&node, &config, "stillness", "banana", error, sizeof error), -1);
    assert_int_equal(node_setting_apply(&node, &config, "stillness", "101", error, sizeof error), -1);
    assert_int_equal(node_setting_apply(&node, &config, "rest_time", "3", error, sizeof error), -1);
    assert_non_null(strstr(error, "cannot change while hkf-filter runs"));
    assert_true(config.rest.stillness == 1 && node.counts.commands == 0);
    assert_int_equal(node_setting_apply(&node, &config, "stillness", "3", error, sizeof error), 0);
    assert_int_equal(hkf_get_wander(&node.filter, &after), HKF_OK);
    assert_true(config.rest.stillness == 3 && node.counts.commands == 1);
    assert_true(fabs((double)after - 3.0 * (double)before) < 1e-5);
    assert_string_equal(config.origin[node_key_find("stillness")], "live (tracker_setting_t)");
}

/* No file yet: made, with its folder; then an old one with other lines and an old stillness is rewritten
 * keeping the others, the old kept as .bak; hkf-filter reads the saved value back. */
static void test_save_keeps_the_rest_of_the_file(void **state)
{
    char error[512], saved[4096], backup[4200];
    node_config_t *check = malloc(sizeof *check);
    (void)state;
    config.rest.stillness = 2;
    assert_int_equal(node_settings_save(&config, saved, sizeof saved, error, sizeof error), 0);
    assert_string_equal(saved, path);
    assert_non_null(strstr(read_text(path), "stillness = 2"));
    write_text(path, "# mine\nnoise_rise = 0.3\nstillness = 0.5\n");
    config.rest.stillness = 4;
    assert_int_equal(node_settings_save(&config, saved, sizeof saved, error, sizeof error), 0);
    assert_string_equal(read_text(path), "stillness = 4  # saved from a running hkf-filter (the live view, hkf-cmd)\n"
                                         "# mine\nnoise_rise = 0.3\n");
    snprintf(backup, sizeof backup, "%s.bak", path);
    assert_string_equal(read_text(backup), "# mine\nnoise_rise = 0.3\nstillness = 0.5\n");
    node_config_defaults(check);
    assert_int_equal(node_config_read_file(check, path, error, sizeof error), 0);
    assert_true(check->rest.stillness == 4 && fabs((double)check->calibration.noise_rise - 0.3) < 1e-6);
    free(check);
}

/* A file that would not read back (a bad line of the user's) is not replaced: refused, said, untouched, and no
 * half-written file is left beside it. */
static void test_save_refused_leaves_the_file(void **state)
{
    char error[512], saved[4096], fresh[4200];
    const char *bad = "noise_rise = banana\n";
    (void)state;
    config.rest.stillness = 2;
    assert_int_equal(node_settings_save(&config, saved, sizeof saved, error, sizeof error), 0); /* the folder */
    write_text(path, bad);
    assert_int_equal(node_settings_save(&config, saved, sizeof saved, error, sizeof error), -1);
    assert_non_null(strstr(error, "noise_rise"));
    assert_string_equal(read_text(path), bad);
    snprintf(fresh, sizeof fresh, "%s.new", path);
    assert_int_equal(access(fresh, F_OK), -1);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_stillness_taken_live, with_home, remove_home),
        cmocka_unit_test_setup_teardown(test_save_keeps_the_rest_of_the_file, with_home, remove_home),
        cmocka_unit_test_setup_teardown(test_save_refused_leaves_the_file, with_home, remove_home),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/*
 * test_node_config.c - hkf-filter's settings: the shipped config file, the
 * command-line overrides, the error messages, and --print-config reading back.
 */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmocka.h>

#include "hkf/hkf_settings_table.h"
#include "model_name.h"
#include "hkf/hkf_models.h"
#include "node_config.h"

#ifndef SHIPPED_CONFIG
#error "SHIPPED_CONFIG (filter_node/hkf-filter.conf) must be defined by the build"
#endif

static char error[600];

/* Temporary config files: each write_temp gets its own, all removed when the tests end. */
static char temp_paths[32][64];
static int temp_count;

static const char *write_temp(const char *text)
{
    char *path;
    FILE *f;
    assert_true(temp_count < 32);
    path = temp_paths[temp_count++];
    strcpy(path, "/tmp/hkf_config_test_XXXXXX");
    f = fdopen(mkstemp(path), "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    return path;
}

static int remove_temp_files(void **state)
{
    int i;
    (void)state;
    for (i = 0; i < temp_count; ++i) {
        remove(temp_paths[i]);
    }
    temp_count = 0;
    return 0;
}

static int same_settings(const hkf_settings_t *a, const hkf_settings_t *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

/* The angle settings of config's i-th model (its assignments replayed over the base). */
static hkf_settings_t model_settings(const node_config_t *config, int i)
{
    int known;
    return node_config_for_model(config, config->models[i].name, &known);
}

/* The first n models have the same names, curves and r_const (where they were set may differ). */
static int same_models(const node_config_t *a, const node_config_t *b, int n)
{
    int i;
    for (i = 0; i < n; ++i) {
        const hkf_settings_t sa = model_settings(a, i), sb = model_settings(b, i);
        if (strcmp(a->models[i].name, b->models[i].name) != 0 || memcmp(sa.noise, sb.noise, sizeof sa.noise) != 0 ||
            memcmp(sa.r_const, sb.r_const, sizeof sa.r_const) != 0) {
            return 0;
        }
    }
    return 1;
}

/* The shipped file says what the built-in defaults say. */
static void test_shipped_file_equals_defaults(void **state)
{
    node_config_t from_file, defaults;
    int i;
    (void)state;
    node_config_defaults(&defaults);
    memset(&from_file, 0, sizeof from_file);
    node_config_defaults(&from_file);
    from_file.model_count = 0; /* the file must bring the models itself */
    assert_int_equal(node_config_read_file(&from_file, SHIPPED_CONFIG, error, sizeof error), 0);
    assert_true(same_settings(&from_file.settings, &defaults.settings));
    assert_int_equal(from_file.model_count, 4);
    assert_string_equal(from_file.models[1].name, "hopenet");
    assert_memory_equal(model_settings(&from_file, 1).noise, hkf_noise_hopenet, sizeof hkf_noise_hopenet);
    /* our estimators' fitted curves (dev/fit): the file and the built-in table agree */
    assert_string_equal(from_file.models[2].name, "mesh_pnp");
    assert_memory_equal(model_settings(&from_file, 2).noise, hkf_noise_mesh_pnp, sizeof hkf_noise_mesh_pnp);
    assert_string_equal(from_file.models[3].name, "whenet");
    assert_memory_equal(model_settings(&from_file, 3).noise, hkf_noise_whenet, sizeof hkf_noise_whenet);
    assert_true(same_models(&from_file, &defaults, 4));
    /* the position's quality per model: the file's and the built-in table's */
    assert_true(node_config_model_settings(&from_file, "mesh_pnp").position_r_scale == 1.0f);
    assert_true(node_config_model_settings(&from_file, "whenet").position_r_scale ==
                node_config_model_settings(&defaults, "whenet").position_r_scale);
    assert_true(from_file.model_settings.position_r_scale == defaults.model_settings.position_r_scale);
    /* every model's own settings: the file's, and the built-in ones from libhkf's table of models */
    for (i = 0; i < hkf_model_count; ++i) {
        int known_file, known_defaults;
        const hkf_settings_t f = node_config_for_model(&from_file, hkf_models[i].name, &known_file);
        const hkf_settings_t d = node_config_for_model(&defaults, hkf_models[i].name, &known_defaults);
        assert_true(known_file && known_defaults);
        assert_true(same_settings(&f, &d));
        assert_true(d.still_wander ==
                    (hkf_models[i].still_wander > 0 ? hkf_models[i].still_wander : defaults.settings.still_wander));
    }
}

/* The position's quality is the model's (position_r_scale): the mesh fit's 1 built in, the face box's
 * 25 for the rest; a model may set its own, the base's reaches the others; out of range is refused,
 * and the node's keys that are not per model are refused in a model's section. */
static void test_position_quality_per_model(void **state)
{
    node_config_t c;
    (void)state;
    node_config_defaults(&c);
    assert_true(node_config_model_settings(&c, "mesh_pnp").position_r_scale == 1.0f);
    assert_true(node_config_model_settings(&c, "whenet").position_r_scale == (hkf_real_t)NODE_BOX_POSITION_R_SCALE);
    assert_true(node_config_model_settings(&c, "nobody").position_r_scale == (hkf_real_t)NODE_BOX_POSITION_R_SCALE);
    assert_true(node_config_model_settings(&c, NULL).position_r_scale == (hkf_real_t)NODE_BOX_POSITION_R_SCALE);
    assert_int_equal(node_config_set(&c, "model.whenet.position_r_scale = 4", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "position_r_scale = 9", error, sizeof error), 0);
    assert_true(node_config_model_settings(&c, "whenet").position_r_scale == 4.0f);
    assert_true(node_config_model_settings(&c, "fsanet").position_r_scale == 9.0f);
    assert_true(node_config_model_settings(&c, "mesh_pnp").position_r_scale == 1.0f);
    assert_int_equal(node_config_set(&c, "model.mesh_pnp.position_r_scale = 0.5", error, sizeof error), -1);
    assert_non_null(strstr(error, "position_r_scale wants a number 1 to"));
    assert_int_equal(node_config_set(&c, "model.whenet.pair_second_alone_from_yaw = 30", error, sizeof error), -1);
    assert_non_null(strstr(error, "unknown key 'pair_second_alone_from_yaw' for a model"));
    assert_true(node_config_model_settings(&c, "mesh_pnp").position_r_scale == 1.0f); /* a refused value changes nothing */
}

static void test_overrides(void **state)
{
    node_config_t c;
    hkf_settings_t s;
    int known;
    (void)state;
    node_config_defaults(&c);
    assert_int_equal(node_config_set(&c, "lc_theta = 3.5", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "noise_mode=constant", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "loop_closure=per_axis", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "process_noise = 1 2 3", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "max_gate_rejections=9", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "model.whenet.noise.yaw = 7 4 0.5 30", error, sizeof error), 0);
    assert_true(c.settings.lc_theta == 3.5f);
    assert_int_equal(c.settings.noise_mode, HKF_NOISE_CONSTANT);
    assert_int_equal(c.settings.loop_closure, HKF_LOOP_CLOSURE_PER_AXIS);
    assert_true(c.settings.process_noise[2] == 3.0f);
    assert_int_equal(c.settings.max_gate_rejections, 9);
    s = node_config_for_model(&c, "whenet", &known);
    assert_true(known);
    assert_true(s.noise[1].mu == 0.5f && s.noise[1].sigma == 30.0f);
    assert_true(s.noise[0].tau == hkf_noise_whenet[0].tau); /* the rest from its built-in curves */
    assert_true(s.process_noise[0] == 1.0f);                    /* and the base settings */
    assert_true(s.lc_theta == 3.5f);
    s = node_config_for_model(&c, "nobody", &known);
    assert_false(known);
    /* a model's own settings beyond its curves: only that model's, the rest from the base */
    assert_int_equal(node_config_set(&c, "model.whenet.process_noise = 2 3 4", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "model.whenet.loop_closure = off", error, sizeof error), 0);
    s = node_config_for_model(&c, "whenet", &known);
    assert_true(s.process_noise[0] == 2.0f && s.process_noise[2] == 4.0f);
    assert_int_equal(s.loop_closure, HKF_LOOP_CLOSURE_OFF);
    assert_true(s.noise[1].mu == 0.5f); /* its curves kept */
    assert_true(s.lc_theta == 3.5f);    /* the base's where it sets nothing */
    assert_int_equal(node_config_set(&c, "lc_theta = 4", error, sizeof error), 0);
    s = node_config_for_model(&c, "whenet", &known);
    assert_true(s.lc_theta == 4.0f && s.process_noise[1] == 3.0f); /* a later base change reaches it */
    s = node_config_for_model(&c, "mesh_pnp", &known);
    assert_true(s.process_noise[0] == 1.0f);
    assert_int_equal(s.loop_closure, HKF_LOOP_CLOSURE_PER_AXIS);
}

/* A [model] section is the assignments it makes, replayed over the base: a model's value stands whatever
 * the base says before or after it, a later value of the same key replaces the earlier one, and what it
 * does not set (a new model's curves too) is the base's as it is at the end; it prints what it sets alone. */
static void test_model_is_its_assignments(void **state)
{
    static node_config_t c;
    char printed[16384];
    FILE *f;
    hkf_settings_t s;
    int known;
    (void)state;
    node_config_defaults(&c);
    assert_int_equal(node_config_set(&c, "model.mine.lc_theta = 2", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "model.mine.lc_theta = 6", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "lc_theta = 4", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "noise.yaw = 9 5 1 25", error, sizeof error), 0);
    assert_int_equal(c.models[c.model_count - 1].set_count, 1); /* one key, set twice */
    s = node_config_for_model(&c, "mine", &known);
    assert_true(known && s.lc_theta == 6.0f); /* its own, the later of the two, over the base's later 4 */
    assert_true(s.noise[1].tau == 9.0f && s.noise[1].sigma == 25.0f); /* the base's curve, set after it */
    assert_true(node_config_for_model(&c, "whenet", &known).lc_theta == 4.0f);
    assert_true(node_config_for_model(&c, "whenet", &known).noise[1].tau == hkf_noise_whenet[1].tau);
    f = fmemopen(printed, sizeof printed, "w");
    assert_non_null(f);
    node_config_print(&c, f);
    assert_int_equal(fclose(f), 0);
    assert_non_null(strstr(printed, "[model mine]\nlc_theta "));
    assert_null(strstr(strstr(printed, "[model mine]"), "noise.yaw"));
}

/* Errors name the key, the value, and in files the line. */
static void test_errors(void **state)
{
    node_config_t c;
    (void)state;
    node_config_defaults(&c);
    assert_int_equal(node_config_set(&c, "no_such_key=1", error, sizeof error), -1);
    assert_non_null(strstr(error, "no_such_key"));
    assert_int_equal(node_config_set(&c, "lc_xi=abc", error, sizeof error), -1);
    assert_non_null(strstr(error, "lc_xi"));
    assert_int_equal(node_config_set(&c, "process_noise=1 2", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "lc_xi=0.5x", error, sizeof error), -1); /* trailing text */
    assert_int_equal(node_config_set(&c, "process_noise=1 2 3 4", error, sizeof error), -1);
    assert_true(c.settings.lc_xi == hkf_default_settings.lc_xi);
    assert_int_equal(node_config_set(&c, "noise_mode=fancy", error, sizeof error), -1);
    assert_non_null(strstr(error, "fancy"));
    assert_int_equal(node_config_set(&c, "max_gate_rejections=-1", error, sizeof error), -1);
    /* strtoul reads "-N" as its negation modulo ULONG_MAX + 1: this one would pass as 1 */
    assert_int_equal(node_config_set(&c, "max_gate_rejections=-18446744073709551615", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "lc_theta", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "model.x.bogus=1", error, sizeof error), -1);
    assert_non_null(strstr(error, "bogus"));
    assert_int_equal(node_config_read_file(&c, write_temp("lc_xi = 0.5\n\nbogus line\n"), error, sizeof error), -1);
    assert_non_null(strstr(error, ":3:"));
    assert_int_equal(node_config_read_file(&c, write_temp("[modle x]\n"), error, sizeof error), -1);
    assert_non_null(strstr(error, ":1:"));
    assert_int_equal(node_config_read_file(&c, "/nonexistent/hkf.conf", error, sizeof error), -1);
    assert_non_null(strstr(error, "/nonexistent/hkf.conf"));
}

/* What --print-config prints reads back to the same configuration. */
static void test_print_reads_back(void **state)
{
    node_config_t c, back;
    char path[64];
    FILE *f;
    (void)state;
    node_config_defaults(&c);
    assert_int_equal(node_config_set(&c, "lc_xi=0.25", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "model.whenet.r_const=1 2 3", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "model.whenet.start_rate=100", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "position_r_const = 0.01 0.02 0.5", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "position_process_noise = 1 2 3", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "position_process_noise = 1 2", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "position_r_const = 0 1 1", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "position_noise_time = 0.5", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "position_still_wander = 0.1 0.1 3", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "position_still_wander = -1 0 0", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "position_start_rate = 0.0000001", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "position_noise_time = 1 2", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "position_noise_time = 99", error, sizeof error), -1);
    assert_non_null(strstr(error, "0 to 10 s")); /* the range in numbers, not macro names */
    assert_int_equal(node_config_set(&c, "position_max_speed = 50", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "position_max_speed = 20000", error, sizeof error), -1);
    assert_non_null(strstr(error, "0 to 10000 cm/s"));
    assert_true(c.position_calibration.noise_time == (hkf_real_t)0.5 && c.position.still_wander[2] == (hkf_real_t)3);
    assert_true(c.calibration.noise_time == hkf_default_calibration_settings.noise_time); /* the angles' is its own */
    assert_true(c.position.max_speed == (hkf_real_t)50);
    assert_int_equal(node_config_set(&c, "model.whenet.position_r_scale = 7", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "position_r_scale = 30", error, sizeof error), 0);
    strcpy(path, "/tmp/hkf_config_print_XXXXXX");
    f = fdopen(mkstemp(path), "w");
    node_config_print(&c, f);
    fclose(f);
    memset(&back, 0, sizeof back);
    back.settings = hkf_default_settings;
    assert_int_equal(node_config_read_file(&back, path, error, sizeof error), 0);
    assert_true(same_settings(&c.settings, &back.settings));
    assert_true(back.position.process_noise[2] == c.position.process_noise[2] &&
                back.position.r_const[1] == c.position.r_const[1] &&
                back.position_calibration.noise_time == c.position_calibration.noise_time &&
                back.position.still_wander[2] == c.position.still_wander[2]);
    assert_int_equal(back.model_count, 4);
    assert_true(same_models(&back, &c, 4));
    assert_true(node_config_model_settings(&back, "whenet").position_r_scale == 7.0f &&
                node_config_model_settings(&back, "mesh_pnp").position_r_scale == 1.0f &&
                node_config_model_settings(&back, "fsanet").position_r_scale == 30.0f);
    {
        int known;
        const hkf_settings_t a = node_config_for_model(&c, "whenet", &known), b = node_config_for_model(&back, "whenet", &known);
        assert_true(same_settings(&a, &b) && b.start_rate == 100.0f);
    }
    remove(path);
}

/* Model names: one rule (model_name_valid) for [model NAME] sections,
 * --set model.NAME.KEY and the message's limit: 1 to 31 letters, digits, '_'
 * or '-'. A name --set accepts is one --print-config writes and --config
 * reads back. (Before: --set took "a b", "a]", "a#" and a newline, which the
 * printed config then could not read.) */
static void test_model_names_one_rule(void **state)
{
    static const char *const bad[] = {"a b", "a]", "a#b", "a\nb", "a.b", "", "abcdefghijabcdefghijabcdefghijab"};
    const char *const good = "Abc_def-0123456789abcdefghijklm"; /* 31 characters */
    node_config_t c, back;
    char assignment[128], path[64];
    size_t i;
    FILE *f;
    (void)state;
    node_config_defaults(&c);
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        snprintf(assignment, sizeof assignment, "model.%s.noise.yaw = 7 4 0 30", bad[i]);
        assert_int_equal(node_config_set(&c, assignment, error, sizeof error), -1);
        assert_false(model_name_valid(bad[i]));
    }
    assert_int_equal(c.model_count, 4);
    assert_int_equal((int)strlen(good), HKF_HEAD_POSE_MEASUREMENT_T_MODEL_NAME_MAX);
    snprintf(assignment, sizeof assignment, "model.%s.noise.yaw = 7 4 0 30", good);
    assert_int_equal(node_config_set(&c, assignment, error, sizeof error), 0);
    strcpy(path, "/tmp/hkf_config_names_XXXXXX");
    f = fdopen(mkstemp(path), "w");
    node_config_print(&c, f);
    fclose(f);
    node_config_defaults(&back);
    assert_int_equal(node_config_read_file(&back, path, error, sizeof error), 0);
    assert_int_equal(back.model_count, 5);
    assert_string_equal(back.models[4].name, good);
    assert_true(same_models(&back, &c, 5));
    remove(path);
    assert_int_equal(node_config_read_file(&back, write_temp("[model a#b]\n"), error, sizeof error), -1);
    assert_int_equal(node_config_read_file(&back, write_temp("[model abcdefghijabcdefghijabcdefghijab]\n"), error,
                                           sizeof error), -1);
}

/* Settings that parse but that hkf_init rejects are reported where they were
 * given: FILE:LINE, or --set. (Before: "invalid settings: ..." alone.) */
static void test_check_names_where(void **state)
{
    node_config_t c;
    const char *path;
    char where[400];
    (void)state;
    node_config_defaults(&c);
    assert_int_equal(node_config_check(&c, error, sizeof error), 0);
    path = write_temp("start_rate = 3\nlc_xi = 5\n"); /* a value outside its range: refused at its line */
    assert_int_equal(node_config_read_file(&c, path, error, sizeof error), -1);
    snprintf(where, sizeof where, "%s:2: lc_xi wants a number 0 to 1, not '5'", path);
    assert_non_null(strstr(error, where));
    node_config_defaults(&c);
    assert_int_equal(node_config_set(&c, "r_min=200", error, sizeof error), 0);
    assert_int_equal(node_config_set(&c, "r_max=100", error, sizeof error), 0);
    assert_int_equal(node_config_check(&c, error, sizeof error), -1);
    assert_non_null(strstr(error, "--set: r_min = 200"));
    assert_non_null(strstr(error, "--set: r_max = 100"));
    node_config_defaults(&c);
    path = write_temp("[model mine]\nnoise.yaw = 1 2 3 -4\n");
    assert_int_equal(node_config_read_file(&c, path, error, sizeof error), -1);
    snprintf(where, sizeof where, "%s:2: noise.yaw wants four numbers (tau lambda mu sigma) sigma 0.001 to 10000 deg", path);
    assert_non_null(strstr(error, where));
    node_config_defaults(&c); /* a model's own key, refused where it was set */
    path = write_temp("[model mine]\nstill_wander = -1\n");
    assert_int_equal(node_config_read_file(&c, path, error, sizeof error), -1);
    snprintf(where, sizeof where, "%s:2: still_wander wants a number 0 to 1e+08 deg^2", path);
    assert_non_null(strstr(error, where));
    path = write_temp("noise_time = 20\n"); /* the calibration's, beside the filter */
    assert_int_equal(node_config_read_file(&c, path, error, sizeof error), -1);
    snprintf(where, sizeof where, "%s:1: noise_time wants a number 0 to 10 s", path);
    assert_non_null(strstr(error, where));
    path = write_temp("[model mine]\nnoise_time = 0.5\n"); /* one calibration for the node, not per model */
    assert_int_equal(node_config_read_file(&c, path, error, sizeof error), -1);
    assert_non_null(strstr(error, "unknown key 'noise_time' for a model"));
    node_config_defaults(&c); /* settings each in range but not together, in a model: named where they were set */
    path = write_temp("gate_sigma = 3\n[model mine]\nmax_gate_rejections = 0\n");
    assert_int_equal(node_config_read_file(&c, path, error, sizeof error), 0);
    assert_int_equal(node_config_check(&c, error, sizeof error), -1);
    snprintf(where, sizeof where, "%s:1: gate_sigma = 3; %s:3: max_gate_rejections = 0; ", path, path);
    assert_non_null(strstr(error, where));
    assert_non_null(strstr(error, "'mine'"));
    node_config_defaults(&c); /* the position's too */
    assert_int_equal(node_config_set(&c, "position_max_gate_rejections=0", error, sizeof error), 0);
    assert_int_equal(node_config_check(&c, error, sizeof error), -1);
    assert_non_null(strstr(error, "--set: position_max_gate_rejections = 0; invalid position settings"));
    assert_non_null(strstr(error, "position_max_gate_rejections 0")); /* round 4: the position's keys named, */
    assert_null(strstr(error, "gate_sigma"));                         /* not the angles' gate */
}

/* A value beyond the number type, NaN or infinite is said to be that (not
 * "NaN or infinite" for 1e300); a NUL byte is not "line too long"; a named
 * pipe is refused at once, not waited on. */
static void test_values_and_files_reported_as_they_are(void **state)
{
    node_config_t c;
    const char *path;
    char fifo[64];
    (void)state;
    node_config_defaults(&c);
    assert_int_equal(node_config_set(&c, "lc_theta=1e300", error, sizeof error), -1);
    assert_non_null(strstr(error, "beyond the range"));
    assert_int_equal(node_config_set(&c, "lc_theta=nan", error, sizeof error), -1);
    assert_non_null(strstr(error, "NaN"));
    assert_int_equal(node_config_set(&c, "process_noise=1 inf 1", error, sizeof error), -1);
    assert_non_null(strstr(error, "infinite"));
    if (sizeof(hkf_real_t) < sizeof(double)) { /* round 4: a value that is 0 only in the number type */
        assert_int_equal(node_config_set(&c, "process_noise=1e-300 1 1", error, sizeof error), -1);
        assert_non_null(strstr(error, "beyond the range"));
    }
    assert_int_equal(node_config_set(&c, "process_noise=1e-400 1 1", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "process_noise=0 1 1", error, sizeof error), 0);
    assert_true(c.settings.lc_theta == hkf_default_settings.lc_theta); /* nothing changed */
    path = write_temp("lc_xi = 0.5\n");
    {
        FILE *f = fopen(path, "ab");
        assert_non_null(f);
        fputs("lc_theta = 3", f);
        fputc('\0', f);
        fputs("\n", f);
        fclose(f);
    }
    assert_int_equal(node_config_read_file(&c, path, error, sizeof error), -1);
    assert_non_null(strstr(error, ":2: a NUL byte"));
    strcpy(fifo, "/tmp/hkf_config_fifo_XXXXXX");
    assert_non_null(mkdtemp(fifo));
    strcat(fifo, "/fifo");
    assert_int_equal(mkfifo(fifo, 0600), 0);
    assert_int_equal(node_config_read_file(&c, fifo, error, sizeof error), -1); /* returns: no writer is waited for */
    assert_non_null(strstr(error, "not a regular file"));
    remove(fifo);
    *strrchr(fifo, '/') = '\0';
    rmdir(fifo);
}

/* Every setting of libhkf's tables is a key (the position's as position_NAME), printed and set one way:
 * each takes the value --print-config printed for it, and a value beyond its range is refused. */
static void test_every_setting_is_a_key(void **state)
{
    static node_config_t c;
    static char printed[16384];
    FILE *f = fmemopen(printed, sizeof printed, "w");
    int i;
    (void)state;
    assert_true(hkf_settings_table_count + hkf_calibration_settings_table_count + 1 + hkf_position_settings_table_count <=
                NODE_KEY_SLOTS);
    assert_true(hkf_settings_table_count <= 32); /* a bit each in node_model_t.own_keys */
    node_config_defaults(&c);
    node_config_print(&c, f);
    fclose(f);
    for (i = 0; i < hkf_settings_table_count + hkf_calibration_settings_table_count + hkf_position_settings_table_count;
         ++i) {
        const int angles = i < hkf_settings_table_count;
        const int calibration = !angles && i < hkf_settings_table_count + hkf_calibration_settings_table_count;
        const hkf_setting_t *d = angles        ? &hkf_settings_table[i]
                                 : calibration ? &hkf_calibration_settings_table[i - hkf_settings_table_count]
                                               : &hkf_position_settings_table[i - hkf_settings_table_count -
                                                                              hkf_calibration_settings_table_count];
        char name[64], line[200], *at, *end;
        snprintf(name, sizeof name, "\n%s%s ", angles || calibration ? "" : "position_", d->name);
        at = strstr(printed, name);
        assert_non_null(at);
        end = strchr(at + 1, '#');
        assert_non_null(end);
        snprintf(line, sizeof line, "%.*s", (int)(end - at - 1), at + 1); /* "name = value  " */
        assert_int_equal(node_config_set(&c, line, error, sizeof error), 0);
        if (d->type == HKF_SETTING_REAL) {
            snprintf(line, sizeof line, "%s=%g%s", name + 1, d->max * 2 + 1, d->count == 3 ? " 1 1" : "");
            assert_int_equal(node_config_set(&c, line, error, sizeof error), -1);
            assert_non_null(strstr(error, "wants"));
        }
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_file_equals_defaults),
        cmocka_unit_test(test_overrides),
        cmocka_unit_test(test_position_quality_per_model),
        cmocka_unit_test(test_model_is_its_assignments),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_print_reads_back),
        cmocka_unit_test(test_model_names_one_rule),
        cmocka_unit_test(test_check_names_where),
        cmocka_unit_test(test_every_setting_is_a_key),
        cmocka_unit_test(test_values_and_files_reported_as_they_are),
    };
    return cmocka_run_group_tests(tests, NULL, remove_temp_files);
}

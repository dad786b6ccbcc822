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

#include <cmocka.h>

#include "model_curves.h"
#include "node_config.h"

#ifndef SHIPPED_CONFIG
#error "SHIPPED_CONFIG (tools/filter_node/hkf-filter.conf) must be defined by the build"
#endif

static char error[600];

static const char *write_temp(const char *text)
{
    static char path[64];
    FILE *f;
    strcpy(path, "/tmp/hkf_config_test_XXXXXX");
    f = fdopen(mkstemp(path), "w");
    assert_non_null(f);
    fputs(text, f);
    fclose(f);
    return path;
}

static int same_settings(const hkf_settings_t *a, const hkf_settings_t *b)
{
    return memcmp(a, b, sizeof *a) == 0;
}

/* The shipped file says what the built-in defaults say. */
static void test_shipped_file_equals_defaults(void **state)
{
    node_config_t from_file, defaults;
    (void)state;
    node_config_defaults(&defaults);
    memset(&from_file, 0, sizeof from_file);
    node_config_defaults(&from_file);
    from_file.model_count = 0; /* the file must bring the models itself */
    assert_int_equal(node_config_read_file(&from_file, SHIPPED_CONFIG, error, sizeof error), 0);
    assert_true(same_settings(&from_file.settings, &defaults.settings));
    assert_int_equal(from_file.model_count, 4);
    assert_string_equal(from_file.models[1].name, "hopenet");
    assert_memory_equal(from_file.models[1].noise, hkf_noise_hopenet, sizeof from_file.models[1].noise);
    /* our estimators' fitted curves (tools/fit): the file and the built-in table agree */
    assert_string_equal(from_file.models[2].name, "mesh_pnp");
    assert_memory_equal(from_file.models[2].noise, model_curves_mesh_pnp, sizeof from_file.models[2].noise);
    assert_string_equal(from_file.models[3].name, "whenet");
    assert_memory_equal(from_file.models[3].noise, model_curves_whenet, sizeof from_file.models[3].noise);
    assert_memory_equal(from_file.models, defaults.models, sizeof defaults.models[0] * 4);
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
    assert_true(s.noise[0].tau == model_curves_whenet[0].tau); /* the rest from its built-in curves */
    assert_true(s.process_noise[0] == 1.0f);                    /* and the base settings */
    assert_true(s.lc_theta == 3.5f);
    s = node_config_for_model(&c, "nobody", &known);
    assert_false(known);
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
    assert_int_equal(node_config_set(&c, "noise_mode=fancy", error, sizeof error), -1);
    assert_non_null(strstr(error, "fancy"));
    assert_int_equal(node_config_set(&c, "max_gate_rejections=-1", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "lc_theta", error, sizeof error), -1);
    assert_int_equal(node_config_set(&c, "model.x.lc_theta=1", error, sizeof error), -1);
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
    strcpy(path, "/tmp/hkf_config_print_XXXXXX");
    f = fdopen(mkstemp(path), "w");
    node_config_print(&c, f);
    fclose(f);
    memset(&back, 0, sizeof back);
    back.settings = hkf_default_settings;
    assert_int_equal(node_config_read_file(&back, path, error, sizeof error), 0);
    assert_true(same_settings(&c.settings, &back.settings));
    assert_int_equal(back.model_count, 4);
    assert_memory_equal(back.models, c.models, sizeof c.models[0] * 4);
    remove(path);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_shipped_file_equals_defaults),
        cmocka_unit_test(test_overrides),
        cmocka_unit_test(test_errors),
        cmocka_unit_test(test_print_reads_back),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

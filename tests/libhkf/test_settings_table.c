/*
 * test_settings_table.c - libhkf's settings tables say what hkf_init,
 * hkf_position_init and hkf_rest_init do: every setting is in it once, each end of its range
 * is accepted, a value just outside is refused with the descriptor's error,
 * and hkf_setting_in_range agrees with the init on both sides. The table of
 * models: each one found by its name, once, its curves and its own still_wander
 * a set hkf_init takes in this numeric build.
 */
#include "test_support.h"

#include "hkf/hkf_models.h"
#include "hkf/hkf_position.h"
#include "hkf/hkf_rest.h"
#include "hkf/hkf_settings_table.h"

#include <string.h>

typedef struct {
    const hkf_setting_t *table;
    int count;
    size_t size; /* of the settings struct */
} table_t;

static const table_t *tables(void)
{
    static table_t both[3];
    both[0].table = hkf_settings_table;
    both[0].count = hkf_settings_table_count;
    both[0].size = sizeof(hkf_settings_t);
    both[1].table = hkf_position_settings_table;
    both[1].count = hkf_position_settings_table_count;
    both[1].size = sizeof(hkf_position_settings_t);
    both[2].table = hkf_rest_settings_table;
    both[2].count = hkf_rest_settings_table_count;
    both[2].size = sizeof(hkf_rest_settings_t);
    return both;
}

/* The defaults of the table's struct, in a buffer either struct fits. */
typedef union {
    hkf_settings_t angles;
    hkf_position_settings_t position;
    hkf_rest_settings_t rest;
} any_settings_t;

static any_settings_t defaults_of(const table_t *t)
{
    any_settings_t s;
    memset(&s, 0, sizeof s);
    if (t->table == hkf_settings_table) {
        s.angles = hkf_default_settings;
    } else if (t->table == hkf_rest_settings_table) {
        s.rest = hkf_default_rest_settings;
    } else {
        s.position = hkf_position_default_settings;
    }
    return s;
}

static int init_of(const table_t *t, const any_settings_t *s)
{
    hkf_filter_t f;
    hkf_position_filter_t p;
    hkf_rest_t r;
    if (t->table == hkf_rest_settings_table) {
        return hkf_rest_init(&r, &s->rest);
    }
    return t->table == hkf_settings_table ? hkf_init(&f, &s->angles) : hkf_position_init(&p, &s->position);
}

static size_t value_size(const hkf_setting_t *d)
{
    switch (d->type) {
    case HKF_SETTING_UINT: return sizeof(unsigned);
    case HKF_SETTING_CHOICE: return sizeof(int);
    case HKF_SETTING_CURVE: return sizeof(hkf_noise_curve_t);
    default: return (size_t)d->count * sizeof(hkf_real_t);
    }
}

/* Value `axis` of the setting := v (a curve: its sigma, with a shallow dip every build holds). */
static void set_value(any_settings_t *s, const hkf_setting_t *d, int axis, double v)
{
    char *at = (char *)s + d->offset;
    switch (d->type) {
    case HKF_SETTING_UINT: *(unsigned *)(void *)at = (unsigned)v; break;
    case HKF_SETTING_CHOICE: *(int *)(void *)at = (int)v; break;
    case HKF_SETTING_CURVE: *(hkf_noise_curve_t *)(void *)at = table_curve(2.0, 1.0, 0.0, v); break;
    default: ((hkf_real_t *)(void *)at)[axis] = R(v); break;
    }
}

/* The partner a range shared with another setting needs for v to be accepted: r_min <= r_max (the
 * angles' and the position's), a gate with at least one rejection. */
static void make_room(any_settings_t *s, const table_t *t, const hkf_setting_t *d, double v)
{
    if (t->table == hkf_settings_table && strcmp(d->name, "r_min") == 0) {
        s->angles.r_max = R(HKF_MAX_VARIANCE);
    } else if (t->table == hkf_settings_table && strcmp(d->name, "r_max") == 0) {
        s->angles.r_min = R(HKF_MIN_VARIANCE);
    } else if (t->table == hkf_position_settings_table && strcmp(d->name, "r_min") == 0) {
        s->position.r_max = R(HKF_MAX_VARIANCE);
    } else if (t->table == hkf_position_settings_table && strcmp(d->name, "r_max") == 0) {
        s->position.r_min = R(HKF_MIN_VARIANCE);
    } else if (strcmp(d->name, "max_gate_rejections") == 0 && v == 0) {
        if (t->table == hkf_settings_table) {
            s->angles.gate_sigma = 0;
        } else {
            s->position.max_speed = 0;
        }
    }
}

static void expect(const table_t *t, const hkf_setting_t *d, int axis, double v, int accepted)
{
    any_settings_t s = defaults_of(t);
    int result;
    make_room(&s, t, d, v);
    set_value(&s, d, axis, v);
    result = init_of(t, &s);
    if (accepted ? result != HKF_OK : !hkf_setting_is_about(d, result)) {
        fail_msg("%s[%d] = %g: init gave %d (%s), expected %s", d->name, axis, v, result, hkf_result_string(result),
                 accepted ? "ok" : hkf_result_string(d->error));
    }
    if (hkf_setting_in_range(d, (const char *)&s + d->offset) != accepted) {
        fail_msg("%s[%d] = %g: hkf_setting_in_range disagrees with init", d->name, axis, v);
    }
}

/* min and max (or just above min) accepted; just below min and beyond max refused, on every axis. */
static void test_ranges_are_what_init_applies(void **state)
{
    int k, i, axis;
    (void)state;
    for (k = 0; k < 3; ++k) {
        const table_t *t = &tables()[k];
        for (i = 0; i < t->count; ++i) {
            const hkf_setting_t *d = &t->table[i];
            const double low = d->above_min ? d->min + (d->max - d->min) * 1e-3 : d->min;
            for (axis = 0; axis < d->count; ++axis) {
                expect(t, d, axis, low, 1);
                expect(t, d, axis, d->max, 1);
                if (d->type == HKF_SETTING_UINT) {
                    continue; /* its range is the type's */
                }
                expect(t, d, axis, d->max * 1.5 + 1.0, 0);
                expect(t, d, axis, d->above_min ? d->min : d->min > 0 ? d->min / 2 : d->min - 1.0, 0);
                if (d->type == HKF_SETTING_RATE) {
                    expect(t, d, axis, 0.0, 1); /* off */
                }
            }
        }
    }
}

/* Every field is described once: names unique and found, the values tile the struct. */
static void test_every_setting_once(void **state)
{
    int k, i, j;
    (void)state;
    for (k = 0; k < 3; ++k) {
        const table_t *t = &tables()[k];
        size_t covered = 0;
        for (i = 0; i < t->count; ++i) {
            const hkf_setting_t *d = &t->table[i];
            assert_ptr_equal(hkf_setting_find(t->table, t->count, d->name), d);
            assert_true(d->offset + value_size(d) <= t->size);
            assert_true(d->what != NULL && d->what[0] != '\0' && d->unit != NULL);
            assert_true(d->type != HKF_SETTING_CHOICE || d->choices != NULL);
            for (j = 0; j < i; ++j) { /* no overlap with an earlier one */
                const hkf_setting_t *e = &t->table[j];
                assert_true(d->offset >= e->offset + value_size(e) || e->offset >= d->offset + value_size(d));
            }
            covered += value_size(d);
        }
        if (sizeof(hkf_real_t) == sizeof(int)) { /* no padding: every byte is some setting's */
            assert_int_equal(covered, t->size);
        }
        assert_null(hkf_setting_find(t->table, t->count, "no_such_setting"));
    }
}

static void test_models_table(void **state)
{
    int i, j;
    (void)state;
    assert_true(hkf_model_count >= 4);
    for (i = 0; i < hkf_model_count; ++i) {
        const hkf_model_info_t *m = &hkf_models[i];
        hkf_settings_t s = hkf_default_settings;
        hkf_filter_t f;
        assert_ptr_equal(hkf_find_model(m->name), m);
        for (j = 0; j < i; ++j) {
            assert_true(strcmp(hkf_models[j].name, m->name) != 0);
        }
        memcpy(s.noise, m->noise, sizeof s.noise);
        s.noise_mode = HKF_NOISE_ADAPTIVE;
        if (m->still_wander > 0) {
            s.still_wander = m->still_wander;
        }
        assert_int_equal(hkf_init(&f, &s), HKF_OK);
        assert_true(m->still_wander >= 0 && m->position_r_scale >= 0);
        for (j = 0; j < 3; ++j) { /* Eq. 8 at its centre within the clamp, and rising away from it */
            const double centre = D(hkf_observation_noise(&f, j, m->noise[j].mu));
            const double away = D(hkf_observation_noise(&f, j, R(D(m->noise[j].mu) + 60.0)));
            assert_true(centre >= D(s.r_min) && centre <= D(s.r_max));
            assert_true(away > centre || centre == D(s.r_max));
        }
    }
    assert_ptr_equal(hkf_find_model("mesh_pnp")->noise, hkf_noise_mesh_pnp);
    assert_ptr_equal(hkf_find_model("whenet")->noise, hkf_noise_whenet);
    assert_null(hkf_find_model("no_such_model"));
    assert_null(hkf_find_model("mesh_pn"));
    assert_null(hkf_find_model(NULL));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_ranges_are_what_init_applies),
        cmocka_unit_test(test_every_setting_once),
        cmocka_unit_test(test_models_table),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/*
 * hkf_settings_table.h - one descriptor per setting of hkf_settings_t,
 * hkf_calibration_settings_t and hkf_position_settings_t: its name, where it lies in the struct, its type,
 * unit and the range hkf_init (hkf_calibration_init, hkf_position_init)
 * accepts in this build.
 *
 * For programs that read settings as text (a config file, a command line, a
 * controller's serial console) and must say what a value should have been.
 * Optional: firmware that never calls it does not link it, and hkf_init
 * checks the settings without it. tests/libhkf/test_settings_table.c checks
 * that every range here is the one hkf_init applies.
 *
 *     const hkf_setting_t *d = hkf_setting_find(hkf_settings_table, hkf_settings_table_count, "lc_xi");
 *     const void *value = (const char *)&settings + d->offset;
 *     if (!hkf_setting_in_range(d, value)) ... "lc_xi: 0 to 1"
 *
 * Ranges not of one setting alone are hkf_init's: r_min <= r_max, and a gate
 * that is on needs max_gate_rejections >= 1.
 */
#ifndef HKF_SETTINGS_TABLE_H
#define HKF_SETTINGS_TABLE_H

#include <stddef.h>

#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"
#include "hkf/hkf_position.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    HKF_SETTING_REAL = 0,   /* `count` hkf_real_t, each within the range */
    HKF_SETTING_RATE = 1,   /* one hkf_real_t: 0 (off) or within the range */
    HKF_SETTING_UINT = 2,   /* one unsigned within the range */
    HKF_SETTING_CHOICE = 3, /* one int-sized enum: 0 .. max, named by `choices` */
    HKF_SETTING_CURVE = 4   /* one hkf_noise_curve_t; the range is its sigma's (its other members: hkf.h) */
} hkf_setting_type_t;

typedef struct {
    const char *name;            /* the field's name; an element of an array is "noise.pitch" */
    size_t offset;               /* of the first value in the settings struct */
    hkf_setting_type_t type;
    int count;                   /* values: 1, or 3 (one per axis) */
    const char *unit;            /* of each value; "" for a pure number */
    double min, max;             /* the range of each value, in this build */
    int above_min;               /* 1: the value must exceed min (min itself is refused) */
    int error;                   /* the hkf_result_t of a value outside the range */
    const char *const *choices;  /* HKF_SETTING_CHOICE: the names of 0 .. max */
    const char *what;            /* what it does, in a few words */
} hkf_setting_t;

/* The angle filter's settings (hkf_settings_t), in the order of hkf.h. */
extern const hkf_setting_t hkf_settings_table[];
extern const int hkf_settings_table_count;

/* The noise calibration's settings (hkf_calibration_settings_t). */
extern const hkf_setting_t hkf_calibration_settings_table[];
extern const int hkf_calibration_settings_table_count;

/* The player's rest's settings (hkf_rest_settings_t, hkf_rest.h). */
extern const hkf_setting_t hkf_rest_settings_table[];
extern const int hkf_rest_settings_table_count;

/* The position filter's settings (hkf_position_settings_t), in the order of hkf_position.h. */
extern const hkf_setting_t hkf_position_settings_table[];
extern const int hkf_position_settings_table_count;

/* The descriptor named `name` in a table of `count`, or NULL. */
const hkf_setting_t *hkf_setting_find(const hkf_setting_t *table, int count, const char *name);

/* 1 when every value of the setting at `value` (its field: a settings struct's
 * address + offset, or a copy of the field) is within its range; 0 for a value
 * outside it, NaN or infinite. A curve is checked whole, as hkf_init checks it. */
int hkf_setting_in_range(const hkf_setting_t *setting, const void *value);

/* 1 when hkf_init's error `result` is about this setting. */
int hkf_setting_is_about(const hkf_setting_t *setting, int result);

#ifdef __cplusplus
}
#endif

#endif /* HKF_SETTINGS_TABLE_H */

/*
 * setting_text.h - a setting's value as the config file and --set write it: parsed from text
 * (checked against what the setting takes, not yet against its range) and formatted back to the
 * shortest text that reads back the same, with the words an error message uses for both.
 */
#ifndef SETTING_TEXT_H
#define SETTING_TEXT_H

#include <stddef.h>

#include "hkf/hkf_settings_table.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A setting's value as parsed, before it is checked and stored (room for a curve's four numbers). */
typedef union {
    hkf_real_t real[4];
    hkf_noise_curve_t curve;
    unsigned whole;
    int choice;
} setting_value_t;

/* The text of a value of setting d: 0, -1 when it is not what d takes, -2 for a number beyond the type. */
int setting_text_parse(const hkf_setting_t *d, const char *text, setting_value_t *v);

/* What d takes, for an error message: "a number", "three numbers (x y z)" (xyz: a position's axes), ... */
const char *setting_text_wants(const hkf_setting_t *d, int xyz);

/* The values d takes, from its table entry, into text: "0 to 10 s", "0 or 0.001 to 1000 1/s", "off, norm". */
const char *setting_text_range(const hkf_setting_t *d, char *text, size_t size);

/* The value(s) of setting d at `at` (its field) as the config file writes them. */
void setting_text_format(const hkf_setting_t *d, const void *at, char *value, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* SETTING_TEXT_H */

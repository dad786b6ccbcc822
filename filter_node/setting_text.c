/* setting_text.c - see setting_text.h. */
#include "setting_text.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Reads exactly n numbers separated by blanks: 0, -1 when it is not n numbers,
 * -2 when one is NaN, infinite, or beyond what a hkf_real_t holds (1e300 in a
 * float build). */
static int parse_reals(const char *text, hkf_real_t *out, int n)
{
    const char *p = text;
    int i, beyond = 0;
    for (i = 0; i < n; ++i) {
        char *end = NULL;
        double v;
        errno = 0;
        v = strtod(p, &end);
        if (end == p) {
            return -1;
        }
        if (errno == ERANGE || !isfinite(v) || !isfinite((double)(hkf_real_t)v) ||
            (v != 0.0 && (double)(hkf_real_t)v == 0.0)) {
            beyond = 1; /* underflow to 0 included, in double ("1e-400") or in hkf_real_t ("1e-300" in float) */
        }
        out[i] = (hkf_real_t)v;
        p = end;
    }
    while (isspace((unsigned char)*p)) {
        ++p;
    }
    return *p != '\0' ? -1 : beyond ? -2 : 0;
}

static int parse_name(const char *text, const char *const *names, int count)
{
    int i;
    for (i = 0; i < count; ++i) {
        if (strcmp(text, names[i]) == 0) {
            return i;
        }
    }
    return -1;
}

/* A whole number (no sign) at most max into *out: 0, or -1. */
static int parse_whole(const char *text, double max, unsigned *out)
{
    char *end = NULL;
    unsigned long whole;
    errno = 0;
    whole = strtoul(text, &end, 10);
    if (end == text || *end != '\0' || errno != 0 || text[0] == '-' || (double)whole > max) {
        return -1;
    }
    *out = (unsigned)whole;
    return 0;
}

/* The text of a value of setting d: 0, -1 when it is not what d takes, -2 for a number beyond the type. */
int setting_text_parse(const hkf_setting_t *d, const char *text, setting_value_t *v)
{
    int result;
    switch (d->type) {
    case HKF_SETTING_CURVE:
        result = parse_reals(text, v->real, 4);
        if (result == 0) {
            const hkf_real_t tau = v->real[0], lambda = v->real[1], mu = v->real[2], sigma = v->real[3];
            v->curve.tau = tau;
            v->curve.lambda = lambda;
            v->curve.mu = mu;
            v->curve.sigma = sigma;
        }
        return result;
    case HKF_SETTING_CHOICE:
        v->choice = parse_name(text, d->choices, (int)d->max + 1);
        return v->choice >= 0 ? 0 : -1;
    case HKF_SETTING_UINT: return parse_whole(text, d->max, &v->whole);
    case HKF_SETTING_REAL:
    case HKF_SETTING_RATE: break;
    }
    return parse_reals(text, v->real, d->count);
}

/* What a key takes, for its error message: "a number", "three numbers (x y z)", ... */
const char *setting_text_wants(const hkf_setting_t *d, int xyz)
{
    switch (d->type) {
    case HKF_SETTING_CURVE: return "four numbers (tau lambda mu sigma)";
    case HKF_SETTING_CHOICE: return "one of";
    case HKF_SETTING_UINT: return "a whole number";
    case HKF_SETTING_REAL:
    case HKF_SETTING_RATE: break;
    }
    return d->count == 1 ? "a number" : xyz ? "three numbers (x y z)" : "three numbers (pitch yaw roll)";
}

/* The values d takes, from the table: "0 to 10 s", "more than 0, up to 10 s", "0 or 0.001 to 1000 1/s",
 * "off, norm, per_axis". */
const char *setting_text_range(const hkf_setting_t *d, char *text, size_t size)
{
    const char *space = d->unit[0] != '\0' ? " " : "";
    int i;
    switch (d->type) {
    case HKF_SETTING_CHOICE:
        text[0] = '\0';
        for (i = 0; i <= (int)d->max; ++i) {
            const size_t used = strlen(text);
            snprintf(text + used, size - used, "%s%s", i > 0 ? ", " : "", d->choices[i]);
        }
        return text;
    case HKF_SETTING_CURVE: snprintf(text, size, "sigma %g to %g%s%s", d->min, d->max, space, d->unit); return text;
    case HKF_SETTING_RATE: snprintf(text, size, "0 or %g to %g%s%s", d->min, d->max, space, d->unit); return text;
    case HKF_SETTING_UINT: snprintf(text, size, "%.0f to %.0f", d->min, d->max); return text;
    case HKF_SETTING_REAL: break;
    }
    if (d->above_min) {
        snprintf(text, size, "more than %g, up to %g%s%s", d->min, d->max, space, d->unit);
    } else {
        snprintf(text, size, "%g to %g%s%s", d->min, d->max, space, d->unit);
    }
    return text;
}

/* The shortest text that reads back as the same hkf_real_t. */
static const char *format_real(hkf_real_t v, char *text, size_t size)
{
    int precision;
    for (precision = 6; precision < 17; ++precision) {
        snprintf(text, size, "%.*g", precision, (double)v);
        if ((hkf_real_t)strtod(text, NULL) == v) {
            break;
        }
    }
    return text;
}

/* The value(s) of setting d at `at` (its field) as the config file writes them. */
void setting_text_format(const hkf_setting_t *d, const void *at, char *value, size_t size)
{
    const hkf_real_t *v = (const hkf_real_t *)(const void *)at;
    char a[32], b[32], c[32], e[32];
    switch (d->type) {
    case HKF_SETTING_CURVE: {
        const hkf_noise_curve_t *curve = (const hkf_noise_curve_t *)(const void *)at;
        snprintf(value, size, "%s %s %s %s", format_real(curve->tau, a, sizeof a),
                 format_real(curve->lambda, b, sizeof b), format_real(curve->mu, c, sizeof c),
                 format_real(curve->sigma, e, sizeof e));
        return;
    }
    case HKF_SETTING_CHOICE: snprintf(value, size, "%s", d->choices[*(const int *)(const void *)at]); return;
    case HKF_SETTING_UINT: snprintf(value, size, "%u", *(const unsigned *)(const void *)at); return;
    case HKF_SETTING_REAL:
    case HKF_SETTING_RATE: break;
    }
    if (d->count == 3) {
        snprintf(value, size, "%s %s %s", format_real(v[0], a, sizeof a), format_real(v[1], b, sizeof b),
                 format_real(v[2], c, sizeof c));
    } else {
        snprintf(value, size, "%s", format_real(v[0], a, sizeof a));
    }
}

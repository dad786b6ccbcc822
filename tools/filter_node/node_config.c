/* node_config.c - see node_config.h. */
#define _POSIX_C_SOURCE 200809L
#include "node_config.h"

#include "hkf/hkf_settings_table.h"
#include "model_name.h"
#include "safe_files.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* Every key is a setting described as libhkf describes its own (hkf/hkf_settings_table.h): the angle
 * filter's, the noise calibration's, the node's own, then the position filter's (named "position_" + its
 * name). A key's index is its slot in the origin arrays; a model may own the angle filter's (own_keys has
 * a bit per index). */
typedef enum { GROUP_ANGLES, GROUP_CALIBRATION, GROUP_NODE, GROUP_PER_MODEL, GROUP_POSITION } key_group_t;

static const hkf_setting_t node_settings[] = {
    {"pair_second_alone_from_yaw", offsetof(node_config_t, second_alone_from_yaw), HKF_SETTING_REAL, 1, "deg", 0, 180,
     0, 0, NULL, "two models on one channel: the second alone where the first's |yaw| >= this"},
};
#define NODE_SETTING_COUNT ((int)(sizeof node_settings / sizeof node_settings[0]))

/* The node's keys that a [model NAME] section may set too (node_model_settings_t). */
static const hkf_setting_t per_model_settings[] = {
    {"position_r_scale", offsetof(node_model_settings_t, position_r_scale), HKF_SETTING_REAL, 1, "", 1, 1e6, 0, 0,
     NULL, "the model's position R as a multiple of position_measurement_noise (the face mesh fit's)"},
};
#define PER_MODEL_SETTING_COUNT ((int)(sizeof per_model_settings / sizeof per_model_settings[0]))
#define POSITION_PREFIX "position_"
#define STRING_OF(x) #x
#define STRING_OF_VALUE(x) STRING_OF(x) /* a macro's value as text */

static int key_count(void)
{
    return hkf_settings_table_count + hkf_calibration_settings_table_count + NODE_SETTING_COUNT +
           PER_MODEL_SETTING_COUNT + hkf_position_settings_table_count;
}

static const hkf_setting_t *key_setting(int k, key_group_t *group)
{
    if (k < hkf_settings_table_count) {
        *group = GROUP_ANGLES;
        return &hkf_settings_table[k];
    }
    k -= hkf_settings_table_count;
    if (k < hkf_calibration_settings_table_count) {
        *group = GROUP_CALIBRATION;
        return &hkf_calibration_settings_table[k];
    }
    k -= hkf_calibration_settings_table_count;
    if (k < NODE_SETTING_COUNT) {
        *group = GROUP_NODE;
        return &node_settings[k];
    }
    k -= NODE_SETTING_COUNT;
    if (k < PER_MODEL_SETTING_COUNT) {
        *group = GROUP_PER_MODEL;
        return &per_model_settings[k];
    }
    *group = GROUP_POSITION;
    return &hkf_position_settings_table[k - PER_MODEL_SETTING_COUNT];
}

/* The key's name as the config file writes it. */
static const char *key_name(int k, char *text, size_t size)
{
    key_group_t group;
    const hkf_setting_t *d = key_setting(k, &group);
    snprintf(text, size, "%s%s", group == GROUP_POSITION ? POSITION_PREFIX : "", d->name);
    return text;
}

/* The index of the key `name`, or -1. */
static int find_key(const char *name)
{
    int k;
    for (k = 0; k < key_count(); ++k) {
        char text[64];
        if (strcmp(key_name(k, text, sizeof text), name) == 0) {
            return k;
        }
    }
    return -1;
}

/* The struct a key's offset is in: the angle settings or per-model settings given, or the config's calibration,
 * own or position. */
static const char *key_base(const node_config_t *config, const hkf_settings_t *angles,
                            const node_model_settings_t *per_model, key_group_t group)
{
    switch (group) {
    case GROUP_ANGLES: return (const char *)angles;
    case GROUP_CALIBRATION: return (const char *)&config->calibration;
    case GROUP_NODE: return (const char *)config;
    case GROUP_PER_MODEL: return (const char *)per_model;
    case GROUP_POSITION: break;
    }
    return (const char *)&config->position;
}

/* The same in the config's own settings, to write. */
static char *config_base(node_config_t *config, key_group_t group)
{
    const char *base = key_base(config, &config->settings, &config->model_settings, group);
    return (char *)config + (base - (const char *)config);
}

static size_t value_size(const hkf_setting_t *d)
{
    switch (d->type) {
    case HKF_SETTING_UINT: return sizeof(unsigned);
    case HKF_SETTING_CHOICE: return sizeof(int);
    case HKF_SETTING_CURVE: return sizeof(hkf_noise_curve_t);
    case HKF_SETTING_REAL:
    case HKF_SETTING_RATE: break;
    }
    return (size_t)d->count * sizeof(hkf_real_t);
}

/* The paper's two estimators and ours are in the table from the start. */
static void add_builtin_model(node_config_t *config, const char *name, const hkf_noise_curve_t noise[3])
{
    node_model_t *m = &config->models[config->model_count++];
    strcpy(m->name, name);
    memcpy(m->noise, noise, sizeof m->noise);
    m->r_const[0] = noise[0].tau - noise[0].lambda;
    m->r_const[1] = noise[1].tau - noise[1].lambda;
    m->r_const[2] = noise[2].tau - noise[2].lambda;
}

/* A built-in model's own value of a real setting of the angles or the node's per-model ones (as a
 * `[model NAME]` section sets it). */
static void own_builtin_real(node_model_t *m, const char *name, hkf_real_t value)
{
    const int k = find_key(name);
    key_group_t group;
    const hkf_setting_t *d = key_setting(k, &group);
    char *base = group == GROUP_PER_MODEL ? (char *)&m->own_node : (char *)&m->own;
    *(hkf_real_t *)(void *)(base + d->offset) = value;
    m->own_keys |= 1ul << k;
}

void node_config_defaults(node_config_t *config)
{
    memset(config, 0, sizeof *config);
    config->settings = hkf_default_settings;
    config->second_alone_from_yaw = (hkf_real_t)NODE_SECOND_ALONE_FROM_YAW;
    config->position = hkf_position_default_settings;
    config->calibration = hkf_default_calibration_settings;
    config->model_settings.position_r_scale = (hkf_real_t)NODE_BOX_POSITION_R_SCALE;
    add_builtin_model(config, "fsanet", hkf_noise_fsanet);
    add_builtin_model(config, "hopenet", hkf_noise_hopenet);
    add_builtin_model(config, "mesh_pnp", hkf_noise_mesh_pnp); /* fitted by dev/fit */
    own_builtin_real(&config->models[config->model_count - 1], "position_r_scale", (hkf_real_t)1.0); /* the mesh fit's */
    add_builtin_model(config, "whenet", hkf_noise_whenet);
    /* WHENet's estimate of a resting face wanders further than the mesh's: 1 deg^2 brings its still jitter
     * level with the mesh's (docs/evaluation.md) */
    own_builtin_real(&config->models[config->model_count - 1], "still_wander", (hkf_real_t)1.0);
}


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

/* A key's value as parsed, before it is checked and stored (room for a curve's four numbers). */
typedef union {
    hkf_real_t real[4];
    hkf_noise_curve_t curve;
    unsigned whole;
    int choice;
} key_value_t;

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
static int parse_value(const hkf_setting_t *d, const char *text, key_value_t *v)
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
static const char *wants(const hkf_setting_t *d, key_group_t group)
{
    switch (d->type) {
    case HKF_SETTING_CURVE: return "four numbers (tau lambda mu sigma)";
    case HKF_SETTING_CHOICE: return "one of";
    case HKF_SETTING_UINT: return "a whole number";
    case HKF_SETTING_REAL:
    case HKF_SETTING_RATE: break;
    }
    return d->count == 1 ? "a number" : group == GROUP_POSITION ? "three numbers (x y z)" : "three numbers (pitch yaw roll)";
}

/* The values d takes, from the table: "0 to 10 s", "more than 0, up to 10 s", "0 or 0.001 to 1000 1/s",
 * "off, norm, per_axis". */
static const char *describe_range(const hkf_setting_t *d, char *text, size_t size)
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

/* Key k := the text, into its field in the struct at base, once it parses and is within its range;
 * else -1 with what it should have been. */
static int set_value(char *base, int k, const char *text, char *error, size_t error_size)
{
    key_group_t group;
    const hkf_setting_t *d = key_setting(k, &group);
    key_value_t v;
    char name[64], range[160];
    const int parsed = parse_value(d, text, &v);
    if (parsed == 0 && hkf_setting_in_range(d, &v)) {
        memcpy(base + d->offset, &v, value_size(d));
        return 0;
    }
    key_name(k, name, sizeof name);
    if (parsed == -2) {
        snprintf(error, error_size, "%s = %s: a value is NaN, infinite or beyond the range of a number here", name,
                 text);
    } else {
        snprintf(error, error_size, "%s wants %s %s, not '%s'", name, wants(d, group),
                 describe_range(d, range, sizeof range), text);
    }
    return -1;
}

static node_model_t *find_or_add_model(node_config_t *config, const char *name, char *error, size_t error_size)
{
    int i;
    node_model_t *m;
    for (i = 0; i < config->model_count; ++i) {
        if (strcmp(config->models[i].name, name) == 0) {
            return &config->models[i];
        }
    }
    if (!model_name_valid(name)) {
        snprintf(error, error_size, "a model name has 1 to %d letters, digits, '_' or '-', not '%.60s'",
                 HKF_HEAD_POSE_MEASUREMENT_T_MODEL_NAME_MAX, name);
        return NULL;
    }
    if (config->model_count == NODE_MAX_MODELS) {
        snprintf(error, error_size, "more than %d models", NODE_MAX_MODELS);
        return NULL;
    }
    m = &config->models[config->model_count++];
    memset(m, 0, sizeof *m);
    strcpy(m->name, name);
    memcpy(m->noise, config->settings.noise, sizeof m->noise);
    memcpy(m->r_const, config->settings.r_const, sizeof m->r_const);
    return m;
}

static void set_origin(char *slot, const char *origin)
{
    snprintf(slot, NODE_ORIGIN_MAX, "%s", origin);
}

/* Every model entry has its curves and r_const; any other angle key it may set too. */
static int model_always_owns(const hkf_setting_t *d)
{
    return d->type == HKF_SETTING_CURVE || strcmp(d->name, "r_const") == 0;
}

/* 1 when a [model NAME] section may set key k: the angles' and the node's per-model keys. */
static int model_may_own(int k)
{
    key_group_t group;
    (void)key_setting(k, &group);
    return group == GROUP_ANGLES || group == GROUP_PER_MODEL;
}

static int model_owns(const node_model_t *m, int k)
{
    return model_may_own(k) &&
           ((k < hkf_settings_table_count && model_always_owns(&hkf_settings_table[k])) || (m->own_keys >> k & 1ul) != 0);
}

/* The base's per-model settings with a model's own. */
static node_model_settings_t per_model_of(const node_config_t *config, const node_model_t *m)
{
    /* the per-model keys' indices follow the angles', the calibration's and the node's (key_setting) */
    const int first = hkf_settings_table_count + hkf_calibration_settings_table_count + NODE_SETTING_COUNT;
    node_model_settings_t s = config->model_settings;
    int i;
    for (i = 0; i < PER_MODEL_SETTING_COUNT; ++i) { /* read for every position measurement: the few keys alone */
        const hkf_setting_t *d = &per_model_settings[i];
        if ((m->own_keys >> (first + i) & 1ul) != 0) {
            memcpy((char *)&s + d->offset, (const char *)&m->own_node + d->offset, value_size(d));
        }
    }
    return s;
}

/* The base settings with a model's curves, r_const and own keys. */
static hkf_settings_t settings_of_model(const node_config_t *config, const node_model_t *m)
{
    hkf_settings_t s = config->settings;
    int k;
    memcpy(s.noise, m->noise, sizeof s.noise);
    memcpy(s.r_const, m->r_const, sizeof s.r_const);
    for (k = 0; k < hkf_settings_table_count; ++k) {
        const hkf_setting_t *d = &hkf_settings_table[k];
        if (!model_always_owns(d) && (m->own_keys >> k & 1ul) != 0) {
            memcpy((char *)&s + d->offset, (const char *)&m->own + d->offset, value_size(d));
        }
    }
    return s;
}

/* One "key = value" to apply (the key split out of its line, changed in place for model.NAME.KEY), and
 * where it was given ("FILE:LINE" or "--set"). */
typedef struct {
    char *key;
    const char *value;
    const char *origin;
} assignment_t;

static int set_model_key(node_config_t *config, const char *model, const assignment_t *a, char *error,
                         size_t error_size)
{
    const char *name = a->key;
    const int k = find_key(name);
    key_group_t group;
    const hkf_setting_t *d;
    node_model_t *m;
    hkf_settings_t scratch;
    if (k < 0 || !model_may_own(k)) {
        snprintf(error, error_size, "unknown key '%s' for a model (--print-config lists them)", name);
        return -1;
    }
    d = key_setting(k, &group);
    m = find_or_add_model(config, model, error, error_size);
    if (m == NULL) {
        return -1;
    }
    if (group == GROUP_PER_MODEL) {
        node_model_settings_t own = per_model_of(config, m);
        if (set_value((char *)&own, k, a->value, error, error_size) != 0) {
            return -1;
        }
        m->own_node = own;
        m->own_keys |= 1ul << k;
        set_origin(m->origin[k], a->origin);
        return 0;
    }
    scratch = settings_of_model(config, m);
    if (set_value((char *)&scratch, k, a->value, error, error_size) != 0) {
        return -1;
    }
    memcpy(m->noise, scratch.noise, sizeof m->noise);
    memcpy(m->r_const, scratch.r_const, sizeof m->r_const);
    if (!model_always_owns(d)) {
        memcpy((char *)&m->own + d->offset, (const char *)&scratch + d->offset, value_size(d));
        m->own_keys |= 1ul << k;
    }
    set_origin(m->origin[k], a->origin);
    return 0;
}

static char *trim(char *s)
{
    char *end;
    while (isspace((unsigned char)*s)) {
        ++s;
    }
    end = s + strlen(s);
    while (end > s && isspace((unsigned char)end[-1])) {
        *--end = '\0';
    }
    return s;
}

/* Splits "key = value" (comments already removed). */
static int split_assignment(char *line, char **key, char **value)
{
    char *eq = strchr(line, '=');
    if (eq == NULL) {
        return -1;
    }
    *eq = '\0';
    *key = trim(line);
    *value = trim(eq + 1);
    return (*key)[0] != '\0' && (*value)[0] != '\0' ? 0 : -1;
}

/* a to the base settings, or to model's (a's key may name one: model.NAME.KEY): 0, or -1 with the error. */
static int apply(node_config_t *config, const char *model, assignment_t *a, char *error, size_t error_size)
{
    key_group_t group;
    int k;
    if (strncmp(a->key, "model.", 6) == 0 && model == NULL) {
        char *name = a->key + 6, *dot = strchr(name, '.');
        if (dot == NULL) {
            snprintf(error, error_size, "'%s' is not model.NAME.KEY", a->key);
            return -1;
        }
        *dot = '\0';
        a->key = dot + 1;
        return set_model_key(config, name, a, error, error_size);
    }
    if (model != NULL) {
        return set_model_key(config, model, a, error, error_size);
    }
    k = find_key(a->key);
    if (k < 0) {
        snprintf(error, error_size, "unknown key '%s' (--print-config lists them)", a->key);
        return -1;
    }
    (void)key_setting(k, &group);
    if (set_value(config_base(config, group), k, a->value, error, error_size) != 0) {
        return -1;
    }
    set_origin(config->origin[k], a->origin);
    return 0;
}

int node_config_set(node_config_t *config, const char *assignment, char *error, size_t error_size)
{
    char line[512], *key, *value;
    assignment_t a;
    if (strlen(assignment) >= sizeof line) {
        snprintf(error, error_size, "setting too long");
        return -1;
    }
    strcpy(line, assignment);
    if (split_assignment(line, &key, &value) != 0) {
        snprintf(error, error_size, "'%s' is not KEY=VALUE", assignment);
        return -1;
    }
    a.key = key;
    a.value = value;
    a.origin = "--set";
    return apply(config, NULL, &a, error, error_size);
}

/* One line of in (without its newline) into line: 1, 0 at the end, -1 for a
 * line longer than size - 1, -2 for a NUL byte (not a text file). */
static int read_line(FILE *in, char *line, size_t size)
{
    size_t n = 0;
    int c;
    while ((c = fgetc(in)) != EOF && c != '\n') {
        if (c == '\0') {
            return -2;
        }
        if (n + 1 >= size) {
            return -1;
        }
        line[n++] = (char)c;
    }
    line[n] = '\0';
    return c == EOF && n == 0 ? 0 : 1;
}

/* One line's content (comment and blanks removed, not empty): a [model NAME] section, whose name goes to
 * model, or KEY = VALUE applied to model's settings (the base's when model is ""). 0, or -1 with what is
 * wrong in message. */
static int read_config_line(node_config_t *config, char *text, const char *origin, char *model, char *message,
                            size_t message_size)
{
    char *key, *value;
    assignment_t a;
    if (text[0] == '[') {
        char name[NODE_MODEL_NAME_MAX + 1];
        int n = 0;
        if (sscanf(text, "[model %32[^] \t]]%n", name, &n) != 1 || n == 0 || text[n] != '\0') {
            snprintf(message, message_size, "a section is [model NAME], not '%s'", text);
            return -1;
        }
        if (find_or_add_model(config, name, message, message_size) == NULL) {
            return -1;
        }
        strcpy(model, name);
        return 0;
    }
    if (split_assignment(text, &key, &value) != 0) {
        snprintf(message, message_size, "expected KEY = VALUE, got '%s'", text);
        return -1;
    }
    a.key = key;
    a.value = value;
    a.origin = origin;
    return apply(config, model[0] != '\0' ? model : NULL, &a, message, message_size);
}

int node_config_read_file(node_config_t *config, const char *path, char *error, size_t error_size)
{
    FILE *in = safe_open_input(path, error, error_size); /* a named pipe is refused, not waited on */
    char line[512], model[NODE_MODEL_NAME_MAX + 1] = "";
    char message[400], origin[NODE_ORIGIN_MAX];
    int number = 0, got;
    if (in == NULL) {
        return -1;
    }
    while ((got = read_line(in, line, sizeof line)) != 0) {
        char *text, *hash;
        ++number;
        if (got < 0) {
            snprintf(error, error_size, "%s:%d: %s", path, number,
                     got == -2 ? "a NUL byte (not a text file?)" : "line too long (at most 511 characters)");
            fclose(in);
            return -1;
        }
        snprintf(origin, sizeof origin, "%.80s:%d", path, number);
        hash = strchr(line, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        text = trim(line);
        if (text[0] != '\0' && read_config_line(config, text, origin, model, message, sizeof message) != 0) {
            snprintf(error, error_size, "%s:%d: %s", path, number, message);
            fclose(in);
            return -1;
        }
    }
    if (ferror(in)) {
        snprintf(error, error_size, "%s: read error", path);
        fclose(in);
        return -1;
    }
    fclose(in);
    return 0;
}

static void format_value(const hkf_setting_t *d, const char *at, char *value, size_t size);

/* "where: key = value; " for each key of `group` that the init error `result` is about and that was given
 * somewhere (for a model: its own or the base's), appended to text. */
static void describe_origins(const node_config_t *config, const node_model_t *model, key_group_t want, int result,
                             char *text, size_t size)
{
    hkf_settings_t s = model != NULL ? settings_of_model(config, model) : config->settings;
    const node_model_settings_t per_model = model != NULL ? per_model_of(config, model) : config->model_settings;
    int k;
    for (k = 0; k < key_count(); ++k) {
        key_group_t group;
        const hkf_setting_t *d = key_setting(k, &group);
        const char *origin = model != NULL && model_owns(model, k) ? model->origin[k] : config->origin[k];
        const char *base = key_base(config, &s, &per_model, group);
        char name[64], value[160];
        const size_t used = strlen(text);
        if (group != want || !hkf_setting_is_about(d, result) || origin[0] == '\0') {
            continue; /* another group's, not this error's, or a default: not what the user wrote */
        }
        format_value(d, base + d->offset, value, sizeof value);
        snprintf(text + used, size - used, "%s: %s = %s; ", origin, key_name(k, name, sizeof name), value);
    }
}

int node_config_check(const node_config_t *config, char *error, size_t error_size)
{
    hkf_filter_t probe;
    hkf_position_filter_t position_probe;
    int m, result = hkf_position_init(&position_probe, &config->position);
    char where[600] = "";
    if (result != HKF_OK) {
        describe_origins(config, NULL, GROUP_POSITION, result, where, sizeof where);
        snprintf(error, error_size, "%sinvalid position settings (position_*): %s", where,
                 result == HKF_ERROR_SETTING_GATE /* libhkf's text names the angles' gate_sigma too */
                     ? "position_max_speed is not in [0, " STRING_OF_VALUE(HKF_MAX_SPEED) "] cm/s, or the gate is on "
                       "(position_max_speed > 0) with position_max_gate_rejections 0"
                     : hkf_result_string(result));
        return -1;
    }
    result = hkf_init(&probe, &config->settings);
    if (result != HKF_OK) {
        describe_origins(config, NULL, GROUP_ANGLES, result, where, sizeof where);
        snprintf(error, error_size, "%sinvalid settings: %s", where, hkf_result_string(result));
        return -1;
    }
    for (m = 0; m < config->model_count; ++m) {
        int known;
        const hkf_settings_t s = node_config_for_model(config, config->models[m].name, &known);
        result = hkf_init(&probe, &s);
        if (result != HKF_OK) {
            describe_origins(config, &config->models[m], GROUP_ANGLES, result, where, sizeof where);
            snprintf(error, error_size, "%sinvalid settings for model '%s': %s", where, config->models[m].name,
                     hkf_result_string(result));
            return -1;
        }
    }
    return 0;
}

node_model_settings_t node_config_model_settings(const node_config_t *config, const char *model)
{
    int i;
    for (i = 0; model != NULL && i < config->model_count; ++i) {
        if (strcmp(config->models[i].name, model) == 0) {
            return per_model_of(config, &config->models[i]);
        }
    }
    return config->model_settings;
}

hkf_settings_t node_config_for_model(const node_config_t *config, const char *model, int *known)
{
    int i;
    *known = 0;
    for (i = 0; i < config->model_count; ++i) {
        if (strcmp(config->models[i].name, model) == 0) {
            *known = 1;
            return settings_of_model(config, &config->models[i]);
        }
    }
    return config->settings;
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
static void format_value(const hkf_setting_t *d, const char *at, char *value, size_t size)
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

/* "key = value  # [where; ]what": `where` is the origin ("FILE:LINE" or "--set"), or `unset` when it has none;
 * NULL leaves it out (a configuration that reads back to the same text). */
static void print_line(const char *name, const char *value, const char *comment, const char *origin,
                       const char *unset, FILE *out)
{
    const char *where = origin == NULL ? NULL : origin[0] != '\0' ? origin : unset;
    fprintf(out, "%-28s = %-36s # %s%s%s\n", name, value, where != NULL ? where : "", where != NULL ? "; " : "",
            comment);
}

/* Key k's line, its value in the struct at base, its comment "unit; what". */
static void print_key(int k, const char *base, const char *origin, const char *unset, FILE *out)
{
    key_group_t group;
    const hkf_setting_t *d = key_setting(k, &group);
    char name[64], value[160], comment[200];
    format_value(d, base + d->offset, value, sizeof value);
    snprintf(comment, sizeof comment, "%s%s%s", d->unit, d->unit[0] != '\0' ? "; " : "", d->what);
    print_line(key_name(k, name, sizeof name), value, comment, origin, unset, out);
}

static void print_all(const node_config_t *config, int origins, FILE *out)
{
    int k, m;
    fprintf(out, "# hkf-filter effective configuration%s\n",
            origins ? " (after each value: where it was set, or default / built in)" : "");
    for (k = 0; k < key_count(); ++k) {
        key_group_t group;
        (void)key_setting(k, &group);
        print_key(k, key_base(config, &config->settings, &config->model_settings, group),
                  origins ? config->origin[k] : NULL, "default", out);
    }
    for (m = 0; m < config->model_count; ++m) {
        const node_model_t *model = &config->models[m];
        const hkf_settings_t s = settings_of_model(config, model);
        const node_model_settings_t per_model = per_model_of(config, model);
        fprintf(out, "\n[model %s]\n", model->name);
        for (k = 0; k < key_count(); ++k) {
            key_group_t group;
            (void)key_setting(k, &group);
            if (model_owns(model, k)) {
                print_key(k, key_base(config, &s, &per_model, group), origins ? model->origin[k] : NULL, "built in",
                          out);
            }
        }
    }
}

void node_config_print(const node_config_t *config, FILE *out)
{
    print_all(config, 0, out);
}

void node_config_print_origins(const node_config_t *config, FILE *out)
{
    print_all(config, 1, out);
}

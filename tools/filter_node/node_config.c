/* node_config.c - see node_config.h. */
#define _POSIX_C_SOURCE 200809L
#include "node_config.h"

#include "model_name.h"
#include "safe_files.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

typedef enum { KIND_REAL, KIND_REAL3, KIND_CURVE, KIND_NOISE_MODE, KIND_LOOP_CLOSURE, KIND_UINT } key_kind_t;

typedef struct {
    const char *name;
    key_kind_t kind;
    size_t offset; /* in hkf_settings_t */
    const char *comment;
} config_key_t;

#define FIELD(f) offsetof(hkf_settings_t, f)
#define PAIR_KEY "pair_second_alone_from_yaw"

/* The position filter's keys (hkf_position_settings_t): one or three values within [low, high]. */
typedef struct {
    const char *name;
    int count;
    size_t offset;
    double low, high;
    const char *unit; /* of the range, in the error message */
    const char *comment;
} position_key_t;

#define POSITION_FIELD(f) offsetof(hkf_position_settings_t, f)
static const position_key_t position_keys[] = {
    {"position_process_noise", 3, POSITION_FIELD(process_noise), 0, HKF_MAX_PROCESS_NOISE,
     "", "position filter's q per axis (x y z): cm^2/s^3; calibrated: x n, 1/s^3"},
    {"position_measurement_noise", 3, POSITION_FIELD(measurement_noise), HKF_MIN_VARIANCE, HKF_MAX_VARIANCE,
     " cm^2", "position R per axis (x y z), cm^2; calibrated: n's start (face box: 25 x)"},
    {"position_noise_time", 1, POSITION_FIELD(noise_time), 0, HKF_MAX_TIME, " s",
     "s; position noise calibration's time constant, 0 = off (constant R and q)"},
    {"position_q_boost", 1, POSITION_FIELD(q_boost), 0, HKF_MAX_Q_BOOST, " per s",
     "1/s; calibrated: the position's walk n q_boost e per s while moving, 0 = off"},
    {"position_max_speed", 1, POSITION_FIELD(max_speed), 0, HKF_MAX_SPEED, " cm/s",
     "cm/s; the outlier gate: a position farther from the prediction than this x dt + 3 sigmas is refused, 0 = off"},
};
#define POSITION_KEY_COUNT (sizeof position_keys / sizeof position_keys[0])

static const config_key_t keys[] = {
    {"process_noise", KIND_REAL3, FIELD(process_noise), "q per axis (pitch yaw roll): deg^2/s^3, the moving head's acceleration"},
    {"noise_mode", KIND_NOISE_MODE, FIELD(noise_mode), "constant | adaptive | adaptive_squared"},
    {"noise.pitch", KIND_CURVE, FIELD(noise[0]), "Eq. 8 curve: tau lambda mu sigma, deg"},
    {"noise.yaw", KIND_CURVE, FIELD(noise[1]), "Eq. 8 curve: tau lambda mu sigma, deg"},
    {"noise.roll", KIND_CURVE, FIELD(noise[2]), "Eq. 8 curve: tau lambda mu sigma, deg"},
    {"r_const", KIND_REAL3, FIELD(r_const), "R per axis in constant mode, deg^2"},
    {"r_min", KIND_REAL, FIELD(r_min), "lower clamp of R, deg^2"},
    {"r_max", KIND_REAL, FIELD(r_max), "upper clamp of R, deg^2"},
    {"loop_closure", KIND_LOOP_CLOSURE, FIELD(loop_closure), "off | norm | per_axis (Eq. 9)"},
    {"lc_xi", KIND_REAL, FIELD(lc_xi), "loop-closure fusion factor, 0..1"},
    {"lc_theta", KIND_REAL, FIELD(lc_theta), "loop-closure threshold, deg"},
    {"p0_angle", KIND_REAL, FIELD(p0_angle), "initial angle variance, deg^2"},
    {"p0_rate", KIND_REAL, FIELD(p0_rate), "initial rate variance, and a move's from rest, (deg/s)^2"},
    {"gate_sigma", KIND_REAL, FIELD(gate_sigma), "innovation gate in sigmas, 0 = off"},
    {"max_gate_rejections", KIND_UINT, FIELD(max_gate_rejections), "gated measurements in a row before restarting"},
    {"coast_time", KIND_REAL, FIELD(coast_time), "s without a face before the track is LOST"},
    {"max_dt", KIND_REAL, FIELD(max_dt), "s; a longer gap restarts the track"},
    {"still_wander", KIND_REAL, FIELD(still_wander), "deg^2; motion adaptation: how far a resting head's estimate wanders, beyond R"},
    {"start_rate", KIND_REAL, FIELD(start_rate), "1/s; motion adaptation: how often a still head starts to move, 0 = off (the paper)"},
    {"stop_rate", KIND_REAL, FIELD(stop_rate), "1/s; motion adaptation: how often a moving head stops"},
    {"noise_time", KIND_REAL, FIELD(noise_time), "s; noise calibration's time constant, 0 = off (the paper)"},
    {"noise_rise", KIND_REAL, FIELD(noise_rise), "1/s; how fast the noise estimate may rise"},
};
#define KEY_COUNT (sizeof keys / sizeof keys[0])
typedef char origin_slots_fit[KEY_COUNT + 1 + POSITION_KEY_COUNT <= NODE_KEY_SLOTS ? 1 : -1]; /* the keys, the pair and position keys */
typedef char own_keys_fit[KEY_COUNT <= 32 ? 1 : -1];                     /* a bit per key in node_model_t.own_keys */

static const char *const noise_mode_names[] = {"constant", "adaptive", "adaptive_squared"};
static const char *const loop_closure_names[] = {"off", "norm", "per_axis"};

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

static const config_key_t *find_key(const char *name)
{
    size_t i;
    for (i = 0; i < KEY_COUNT; ++i) {
        if (strcmp(keys[i].name, name) == 0) {
            return &keys[i];
        }
    }
    return NULL;
}

/* A built-in model's own value of a real setting (as a `[model NAME]` section sets it). */
static void own_builtin_real(node_model_t *m, const char *name, hkf_real_t value)
{
    const config_key_t *key = find_key(name);
    *(hkf_real_t *)(void *)((char *)&m->own + key->offset) = value;
    m->own_keys |= 1ul << (key - keys);
}

void node_config_defaults(node_config_t *config)
{
    memset(config, 0, sizeof *config);
    config->settings = hkf_default_settings;
    config->second_alone_from_yaw = (hkf_real_t)NODE_SECOND_ALONE_FROM_YAW;
    config->position = hkf_position_default_settings;
    add_builtin_model(config, "fsanet", hkf_noise_fsanet);
    add_builtin_model(config, "hopenet", hkf_noise_hopenet);
    add_builtin_model(config, "mesh_pnp", hkf_noise_mesh_pnp); /* fitted by dev/fit */
    add_builtin_model(config, "whenet", hkf_noise_whenet);
    /* WHENet's estimate of a resting face wanders further than the mesh's: at the mesh's 0.3 deg^2 its still
     * jitter was 2.9x the mesh's on the shared clips, at 1 deg^2 level with it (docs/evaluation.md) */
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
        if (errno == ERANGE || !isfinite(v) || !isfinite((double)(hkf_real_t)v)) {
            beyond = 1; /* underflow to 0 included: "1e-400" is not what was meant */
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

/* A key of one, three or four numbers (a curve: tau lambda mu sigma) into its field at base. */
static int set_reals(char *base, const config_key_t *key, const char *value, char *error, size_t error_size)
{
    static const char *const wants[] = {"a number", "three numbers (pitch yaw roll)",
                                        "four numbers (tau lambda mu sigma)"};
    const int n = key->kind == KIND_REAL ? 1 : key->kind == KIND_REAL3 ? 3 : 4;
    hkf_real_t v[4];
    switch (parse_reals(value, v, n)) {
    case 0:
        if (key->kind == KIND_CURVE) {
            hkf_noise_curve_t *c = (hkf_noise_curve_t *)(void *)base;
            c->tau = v[0];
            c->lambda = v[1];
            c->mu = v[2];
            c->sigma = v[3];
        } else {
            memcpy(base, v, (size_t)n * sizeof v[0]);
        }
        return 0;
    case -2:
        snprintf(error, error_size, "%s = %s: a value is NaN, infinite or beyond the range of a number here",
                 key->name, value);
        return -1;
    default:
        snprintf(error, error_size, "%s wants %s, not '%s'", key->name, wants[n == 1 ? 0 : n == 3 ? 1 : 2], value);
        return -1;
    }
}

/* A whole number from 0 to 1000000 into the unsigned at base. */
static int set_uint(char *base, const config_key_t *key, const char *value, char *error, size_t error_size)
{
    char *end = NULL;
    unsigned long whole;
    errno = 0;
    whole = strtoul(value, &end, 10);
    if (end != value && *end == '\0' && errno == 0 && whole <= 1000000ul && value[0] != '-') {
        *(unsigned *)(void *)base = (unsigned)whole;
        return 0;
    }
    snprintf(error, error_size, "%s wants a whole number from 0 to 1000000, not '%s'", key->name, value);
    return -1;
}

static int set_key(hkf_settings_t *s, const config_key_t *key, const char *value, char *error, size_t error_size)
{
    char *base = (char *)s + key->offset;
    int n;
    switch (key->kind) {
    case KIND_REAL:
    case KIND_REAL3:
    case KIND_CURVE:
        return set_reals(base, key, value, error, error_size);
    case KIND_NOISE_MODE:
        n = parse_name(value, noise_mode_names, 3);
        if (n >= 0) {
            *(hkf_noise_mode_t *)(void *)base = (hkf_noise_mode_t)n;
            return 0;
        }
        snprintf(error, error_size, "noise_mode is constant, adaptive or adaptive_squared, not '%s'", value);
        return -1;
    case KIND_LOOP_CLOSURE:
        n = parse_name(value, loop_closure_names, 3);
        if (n >= 0) {
            *(int *)(void *)base = n;
            return 0;
        }
        snprintf(error, error_size, "loop_closure is off, norm or per_axis, not '%s'", value);
        return -1;
    case KIND_UINT:
        return set_uint(base, key, value, error, error_size);
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

/* A model's keys: noise.pitch, noise.yaw, noise.roll (0-2) and r_const (3). */
/* Every model entry has its curves and r_const; any other key it may set too. */
static int model_always_owns(const config_key_t *key)
{
    return key->kind == KIND_CURVE || strcmp(key->name, "r_const") == 0;
}

static size_t key_size(const config_key_t *key)
{
    switch (key->kind) {
    case KIND_REAL: return sizeof(hkf_real_t);
    case KIND_REAL3: return 3 * sizeof(hkf_real_t);
    case KIND_CURVE: return sizeof(hkf_noise_curve_t);
    case KIND_NOISE_MODE: return sizeof(hkf_noise_mode_t);
    case KIND_LOOP_CLOSURE: return sizeof(int);
    case KIND_UINT: return sizeof(unsigned);
    }
    return 0;
}

static int model_owns(const node_model_t *m, const config_key_t *key)
{
    return model_always_owns(key) || (m->own_keys >> (key - keys) & 1ul) != 0;
}

/* The base settings with a model's curves, r_const and own keys. */
static hkf_settings_t settings_of_model(const node_config_t *config, const node_model_t *m)
{
    hkf_settings_t s = config->settings;
    size_t k;
    memcpy(s.noise, m->noise, sizeof s.noise);
    memcpy(s.r_const, m->r_const, sizeof s.r_const);
    for (k = 0; k < KEY_COUNT; ++k) {
        if (!model_always_owns(&keys[k]) && (m->own_keys >> k & 1ul) != 0) {
            memcpy((char *)&s + keys[k].offset, (const char *)&m->own + keys[k].offset, key_size(&keys[k]));
        }
    }
    return s;
}

static int set_model_key(node_config_t *config, const char *model, const char *key_name, const char *value,
                         const char *origin, char *error, size_t error_size)
{
    const config_key_t *key = find_key(key_name);
    node_model_t *m;
    hkf_settings_t scratch;
    if (key == NULL) {
        snprintf(error, error_size, "unknown key '%s' for a model (--print-config lists them)", key_name);
        return -1;
    }
    m = find_or_add_model(config, model, error, error_size);
    if (m == NULL) {
        return -1;
    }
    scratch = settings_of_model(config, m);
    if (set_key(&scratch, key, value, error, error_size) != 0) {
        return -1;
    }
    memcpy(m->noise, scratch.noise, sizeof m->noise);
    memcpy(m->r_const, scratch.r_const, sizeof m->r_const);
    if (!model_always_owns(key)) {
        memcpy((char *)&m->own + key->offset, (const char *)&scratch + key->offset, key_size(key));
        m->own_keys |= 1ul << (key - keys);
    }
    set_origin(m->origin[key - keys], origin);
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

/* The index of a base key in keys[], KEY_COUNT for the pair key, then the position keys. */
#define PAIR_SLOT KEY_COUNT
#define POSITION_SLOT(i) (KEY_COUNT + 1 + (i))

static const position_key_t *find_position_key(const char *name)
{
    size_t i;
    for (i = 0; i < POSITION_KEY_COUNT; ++i) {
        if (strcmp(position_keys[i].name, name) == 0) {
            return &position_keys[i];
        }
    }
    return NULL;
}

/* A position key's value(s) into config->position: 0, or -1 with the error. */
static int set_position_key(node_config_t *config, const position_key_t *k, const char *value, const char *origin,
                            char *error, size_t error_size)
{
    hkf_real_t v[3];
    int i, ok = parse_reals(value, v, k->count) == 0;
    for (i = 0; ok && i < k->count; ++i) {
        ok = v[i] >= (hkf_real_t)k->low && v[i] <= (hkf_real_t)k->high;
    }
    if (!ok) {
        snprintf(error, error_size, "%s wants %s, %g to %g%s, not '%s'", k->name,
                 k->count == 3 ? "three values (x y z)" : "a value", k->low, k->high, k->unit, value);
        return -1;
    }
    memcpy((char *)&config->position + k->offset, v, (size_t)k->count * sizeof v[0]);
    set_origin(config->origin[POSITION_SLOT(k - position_keys)], origin);
    return 0;
}

static int apply(node_config_t *config, const char *model, char *key, char *value, const char *origin, char *error,
                 size_t error_size)
{
    const config_key_t *k;
    if (strncmp(key, "model.", 6) == 0 && model == NULL) {
        char *name = key + 6, *dot = strchr(name, '.');
        if (dot == NULL) {
            snprintf(error, error_size, "'%s' is not model.NAME.KEY", key);
            return -1;
        }
        *dot = '\0';
        return set_model_key(config, name, dot + 1, value, origin, error, error_size);
    }
    if (model != NULL) {
        return set_model_key(config, model, key, value, origin, error, error_size);
    }
    if (strcmp(key, PAIR_KEY) == 0) { /* the node's own setting, not libhkf's */
        hkf_real_t v;
        if (parse_reals(value, &v, 1) == 0 && v >= 0 && v <= 180) {
            config->second_alone_from_yaw = v;
            set_origin(config->origin[PAIR_SLOT], origin);
            return 0;
        }
        snprintf(error, error_size, "%s wants degrees from 0 to 180, not '%s'", key, value);
        return -1;
    }
    if (find_position_key(key) != NULL) { /* the position filter's */
        return set_position_key(config, find_position_key(key), value, origin, error, error_size);
    }
    k = find_key(key);
    if (k == NULL) {
        snprintf(error, error_size, "unknown key '%s' (--print-config lists them)", key);
        return -1;
    }
    if (set_key(&config->settings, k, value, error, error_size) != 0) {
        return -1;
    }
    set_origin(config->origin[k - keys], origin);
    return 0;
}

int node_config_set(node_config_t *config, const char *assignment, char *error, size_t error_size)
{
    char line[512], *key, *value;
    if (strlen(assignment) >= sizeof line) {
        snprintf(error, error_size, "setting too long");
        return -1;
    }
    strcpy(line, assignment);
    if (split_assignment(line, &key, &value) != 0) {
        snprintf(error, error_size, "'%s' is not KEY=VALUE", assignment);
        return -1;
    }
    return apply(config, NULL, key, value, "--set", error, error_size);
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
    return apply(config, model[0] != '\0' ? model : NULL, key, value, origin, message, message_size);
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

/* The keys a hkf_init error is about (NULL-terminated). */
static const char *const *keys_of_result(int result)
{
    static const char *const noise_mode[] = {"noise_mode", NULL};
    static const char *const curves[] = {"noise.pitch", "noise.yaw", "noise.roll", NULL};
    static const char *const r_range[] = {"r_min", "r_max", NULL};
    static const char *const r_const[] = {"r_const", NULL};
    static const char *const q[] = {"process_noise", NULL};
    static const char *const lc[] = {"loop_closure", NULL};
    static const char *const lc_xi[] = {"lc_xi", NULL};
    static const char *const lc_theta[] = {"lc_theta", NULL};
    static const char *const p0[] = {"p0_angle", "p0_rate", NULL};
    static const char *const gate[] = {"gate_sigma", "max_gate_rejections", NULL};
    static const char *const coast[] = {"coast_time", NULL};
    static const char *const max_dt[] = {"max_dt", NULL};
    static const char *const motion[] = {"still_wander", "start_rate", "stop_rate", NULL};
    static const char *const calibration[] = {"noise_time", "noise_rise", NULL};
    static const char *const none[] = {NULL};
    switch (result) {
    case HKF_ERROR_SETTING_NOISE_MODE: return noise_mode;
    case HKF_ERROR_SETTING_SIGMA:
    case HKF_ERROR_SETTING_CURVE: return curves;
    case HKF_ERROR_SETTING_R_RANGE: return r_range;
    case HKF_ERROR_SETTING_R_CONST: return r_const;
    case HKF_ERROR_SETTING_PROCESS_NOISE: return q;
    case HKF_ERROR_SETTING_LOOP_CLOSURE: return lc;
    case HKF_ERROR_SETTING_LC_XI: return lc_xi;
    case HKF_ERROR_SETTING_LC_THETA: return lc_theta;
    case HKF_ERROR_SETTING_P0: return p0;
    case HKF_ERROR_SETTING_GATE: return gate;
    case HKF_ERROR_SETTING_COAST_TIME: return coast;
    case HKF_ERROR_SETTING_MAX_DT: return max_dt;
    case HKF_ERROR_SETTING_MOTION: return motion;
    case HKF_ERROR_SETTING_CALIBRATION: return calibration;
    default: return none;
    }
}

static void print_key_value(const hkf_settings_t *s, const config_key_t *key, char *value, size_t size);

/* "where: key = value; " for each key of the error that was given somewhere
 * (a model's curves from its entry), appended to text. */
static void describe_origins(const node_config_t *config, const node_model_t *model, int result, char *text,
                             size_t size)
{
    const char *const *names = keys_of_result(result);
    const hkf_settings_t s = model != NULL ? settings_of_model(config, model) : config->settings;
    for (; *names != NULL; ++names) {
        const config_key_t *key = find_key(*names);
        const char *origin = model != NULL && model_owns(model, key) ? model->origin[key - keys]
                                                                      : config->origin[key - keys];
        char value[160];
        const size_t used = strlen(text);
        if (origin[0] == '\0') {
            continue; /* a default: not what the user wrote */
        }
        print_key_value(&s, key, value, sizeof value);
        snprintf(text + used, size - used, "%s: %s = %s; ", origin, key->name, value);
    }
}

int node_config_check(const node_config_t *config, char *error, size_t error_size)
{
    hkf_filter_t probe;
    hkf_position_filter_t position_probe;
    int m, result = hkf_init(&probe, &config->settings);
    char where[600] = "";
    if (hkf_position_init(&position_probe, &config->position) != HKF_OK) {
        snprintf(error, error_size, "invalid position settings (position_*): %s",
                 hkf_result_string(hkf_position_init(&position_probe, &config->position)));
        return -1;
    }
    if (result != HKF_OK) {
        describe_origins(config, NULL, result, where, sizeof where);
        snprintf(error, error_size, "%sinvalid settings: %s", where, hkf_result_string(result));
        return -1;
    }
    for (m = 0; m < config->model_count; ++m) {
        int known;
        const hkf_settings_t s = node_config_for_model(config, config->models[m].name, &known);
        result = hkf_init(&probe, &s);
        if (result != HKF_OK) {
            describe_origins(config, &config->models[m], result, where, sizeof where);
            snprintf(error, error_size, "%sinvalid settings for model '%s': %s", where, config->models[m].name,
                     hkf_result_string(result));
            return -1;
        }
    }
    return 0;
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

static void print_key_value(const hkf_settings_t *s, const config_key_t *key, char *value, size_t size)
{
    char a[32], b[32], c[32], d[32];
    const char *base = (const char *)s + key->offset;
    const hkf_real_t *v = (const hkf_real_t *)(const void *)base;
    switch (key->kind) {
    case KIND_REAL: snprintf(value, size, "%s", format_real(v[0], a, sizeof a)); break;
    case KIND_REAL3:
        snprintf(value, size, "%s %s %s", format_real(v[0], a, sizeof a), format_real(v[1], b, sizeof b),
                 format_real(v[2], c, sizeof c));
        break;
    case KIND_CURVE: {
        const hkf_noise_curve_t *curve = (const hkf_noise_curve_t *)(const void *)base;
        snprintf(value, size, "%s %s %s %s", format_real(curve->tau, a, sizeof a),
                 format_real(curve->lambda, b, sizeof b), format_real(curve->mu, c, sizeof c),
                 format_real(curve->sigma, d, sizeof d));
        break;
    }
    case KIND_NOISE_MODE: snprintf(value, size, "%s", noise_mode_names[*(const hkf_noise_mode_t *)(const void *)base]); break;
    case KIND_LOOP_CLOSURE: snprintf(value, size, "%s", loop_closure_names[*(const int *)(const void *)base]); break;
    case KIND_UINT: snprintf(value, size, "%u", *(const unsigned *)(const void *)base); break;
    }
}

/* "key = value  # [where; ]what": `where` is the origin ("FILE:LINE" or "--set"), or `unset` when it has none;
 * NULL leaves it out (a configuration that reads back to the same text). */
static void print_line(const char *name, const char *value, const char *comment, const char *origin,
                       const char *unset, FILE *out)
{
    const char *where = origin == NULL ? NULL : origin[0] != '\0' ? origin : unset;
    fprintf(out, "%-20s = %-40s # %s%s%s\n", name, value, where != NULL ? where : "", where != NULL ? "; " : "",
            comment);
}

static void print_key(const hkf_settings_t *s, const config_key_t *key, const char *origin, const char *unset,
                      FILE *out)
{
    char value[160];
    print_key_value(s, key, value, sizeof value);
    print_line(key->name, value, key->comment, origin, unset, out);
}

static void print_position_key(const node_config_t *config, size_t i, int origins, FILE *out)
{
    const position_key_t *k = &position_keys[i];
    const hkf_real_t *v = (const hkf_real_t *)(const void *)((const char *)&config->position + k->offset);
    char three[3][32], line[100];
    if (k->count == 3) {
        snprintf(line, sizeof line, "%s %s %s", format_real(v[0], three[0], 32), format_real(v[1], three[1], 32),
                 format_real(v[2], three[2], 32));
    } else {
        snprintf(line, sizeof line, "%s", format_real(v[0], three[0], 32));
    }
    print_line(k->name, line, k->comment, origins ? config->origin[POSITION_SLOT(i)] : NULL, "default", out);
}

static void print_all(const node_config_t *config, int origins, FILE *out)
{
    char text[32];
    fprintf(out, "# hkf-filter effective configuration%s\n",
            origins ? " (after each value: where it was set, or default / built in)" : "");
    for (size_t i = 0; i < KEY_COUNT; ++i) {
        print_key(&config->settings, &keys[i], origins ? config->origin[i] : NULL, "default", out);
    }
    print_line(PAIR_KEY, format_real(config->second_alone_from_yaw, text, sizeof text),
               "deg; two models on one channel: the second alone where the first's |yaw| >= this",
               origins ? config->origin[PAIR_SLOT] : NULL, "default", out);
    for (size_t i = 0; i < POSITION_KEY_COUNT; ++i) print_position_key(config, i, origins, out);
    for (int m = 0; m < config->model_count; ++m) {
        const node_model_t *model = &config->models[m];
        const hkf_settings_t s = settings_of_model(config, model);
        fprintf(out, "\n[model %s]\n", model->name);
        for (size_t i = 0; i < KEY_COUNT; ++i) {
            if (model_owns(model, &keys[i])) print_key(&s, &keys[i], origins ? model->origin[i] : NULL, "built in", out);
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

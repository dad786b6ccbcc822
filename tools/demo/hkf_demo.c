/*
 * hkf-demo - filters the built-in simulated drive with the paper's filter and
 * its baselines, and prints how much each one smooths and how far it lags.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hkf/hkf.h"
#include "head_motion_sim.h"

typedef struct {
    double seconds;
    unsigned long seed;
    const char *csv_path;
} demo_options_t;

typedef struct {
    const char *name;
    double sq_error[3];   /* sum of squared errors per axis, over frames with an output */
    long outputs;
    double still_step2;   /* sum of squared frame-to-frame changes while the head is still */
    long still_steps;
    double moving_sq_error; /* sum of squared 3-axis errors while the head moves */
    long moving_outputs;
} demo_score_t;

static void usage(FILE *to)
{
    fprintf(to,
            "usage: hkf-demo [--seconds S] [--seed N] [--csv FILE]\n"
            "Filters a built-in simulated drive (30 fps camera, FSA-Net-like estimator noise,\n"
            "outliers and frames without a face) with libhkf and prints a summary.\n"
            "  --seconds S  length of the drive, 1..3600 s (default 60)\n"
            "  --seed N     random seed of the simulated noise (default 1)\n"
            "  --csv FILE   also write every frame: time, truth, raw and filtered angles\n"
            "  --help       this text (--version: the version)\n");
}

static int parse_number(const char *text, double low, double high, double *value)
{
    char *end = NULL;
    errno = 0;
    *value = strtod(text, &end);
    return errno == 0 && end != text && *end == '\0' && *value >= low && *value <= high;
}

/* 0 = run, 1 = help shown, 2 = bad arguments (reported) */
static int parse_options(int argc, char **argv, demo_options_t *o)
{
    int i;
    double v;
    o->seconds = 60.0;
    o->seed = 1;
    o->csv_path = NULL;
    for (i = 1; i < argc; ++i) {
        const int has_value = i + 1 < argc;
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            return 1;
        } else if (strcmp(argv[i], "--version") == 0) {
            printf("hkf-demo %s\n", HKF_VERSION);
            return 1;
        } else if (strcmp(argv[i], "--seconds") == 0 && has_value) {
            if (!parse_number(argv[++i], 1.0, 3600.0, &o->seconds)) {
                fprintf(stderr, "hkf-demo: --seconds wants a number from 1 to 3600, not '%s'\n", argv[i]);
                return 2;
            }
        } else if (strcmp(argv[i], "--seed") == 0 && has_value) {
            if (!parse_number(argv[++i], 0.0, 4294967295.0, &v) || v != floor(v)) {
                fprintf(stderr, "hkf-demo: --seed wants a whole number from 0 to 4294967295, not '%s'\n", argv[i]);
                return 2;
            }
            o->seed = (unsigned long)v;
        } else if (strcmp(argv[i], "--csv") == 0 && has_value) {
            o->csv_path = argv[++i];
        } else {
            fprintf(stderr, "hkf-demo: unknown or incomplete argument '%s' (see --help)\n", argv[i]);
            return 2;
        }
    }
    return 0;
}

static double wrapped(int axis, double d)
{
    if (axis == HKF_AXIS_YAW) {
        d = fmod(d + 180.0, 360.0);
        d = (d < 0.0 ? d + 360.0 : d) - 180.0;
    }
    return d;
}

static void score_frame(demo_score_t *s, const sim_frame_t *frame, const double angle[3],
                        const double previous[3], int have_previous, int previous_still)
{
    double moving = 0.0;
    int a;
    for (a = 0; a < 3; ++a) {
        const double e = wrapped(a, angle[a] - frame->truth[a]);
        s->sq_error[a] += e * e;
        moving += e * e;
        if (have_previous && frame->still && previous_still) {
            const double step = wrapped(a, angle[a] - previous[a]);
            s->still_step2 += step * step;
        }
    }
    if (have_previous && frame->still && previous_still) {
        ++s->still_steps;
    }
    if (!frame->still) {
        s->moving_sq_error += moving;
        ++s->moving_outputs;
    }
    ++s->outputs;
}

/* Runs one filter over the frames; filtered[i] gets its output (NAN where none). */
static int run_filter(const hkf_settings_t *settings, const sim_frame_t *frames, long n,
                      demo_score_t *score, double (*filtered)[3])
{
    hkf_filter_t f;
    hkf_output_t out;
    double previous[3] = {0.0, 0.0, 0.0};
    int have_previous = 0, previous_still = 0;
    long i;
    int a, result = hkf_init(&f, settings);
    if (result != HKF_OK) {
        fprintf(stderr, "hkf-demo: hkf_init: %s\n", hkf_result_string(result));
        return result;
    }
    for (i = 0; i < n; ++i) {
        const float dt = i > 0 ? (float)(frames[i].time - frames[i - 1].time) : 0.0f;
        double angle[3];
        if (frames[i].valid) {
            const float z[3] = {(float)frames[i].measured[0], (float)frames[i].measured[1],
                                (float)frames[i].measured[2]};
            result = hkf_update(&f, z, dt, &out);
        } else {
            result = hkf_predict(&f, dt, &out);
        }
        if (result != HKF_OK) { /* only before the first face: nothing to show yet */
            for (a = 0; a < 3; ++a) {
                filtered[i][a] = NAN;
            }
            have_previous = 0;
            continue;
        }
        for (a = 0; a < 3; ++a) {
            angle[a] = (double)out.angle[a];
            filtered[i][a] = angle[a];
        }
        score_frame(score, &frames[i], angle, previous, have_previous, previous_still);
        memcpy(previous, angle, sizeof previous);
        have_previous = 1;
        previous_still = frames[i].still;
    }
    return HKF_OK;
}

static void score_raw(const sim_frame_t *frames, long n, demo_score_t *score)
{
    long i;
    int have_previous = 0, previous_still = 0;
    const double *previous = NULL;
    for (i = 0; i < n; ++i) {
        if (!frames[i].valid) {
            have_previous = 0;
            continue;
        }
        score_frame(score, &frames[i], frames[i].measured, previous, have_previous, previous_still);
        previous = frames[i].measured;
        have_previous = 1;
        previous_still = frames[i].still;
    }
}

static void print_score(const demo_score_t *s, const demo_score_t *raw)
{
    const double n = (double)(s->outputs > 0 ? s->outputs : 1);
    const double jitter = sqrt(s->still_step2 / (double)(s->still_steps > 0 ? s->still_steps : 1));
    const double raw_jitter = sqrt(raw->still_step2 / (double)(raw->still_steps > 0 ? raw->still_steps : 1));
    printf("%-30s %6.2f %6.2f %6.2f   %8.3f (%5.1f%%)   %6.2f\n", s->name, sqrt(s->sq_error[0] / n),
           sqrt(s->sq_error[1] / n), sqrt(s->sq_error[2] / n), jitter, 100.0 * jitter / raw_jitter,
           sqrt(s->moving_sq_error / (double)(s->moving_outputs > 0 ? s->moving_outputs : 1)));
}

static int write_csv(const char *path, const sim_frame_t *frames, long n, double (*const filtered[])[3],
                     const demo_score_t *scores, int filters)
{
    FILE *out = fopen(path, "w");
    long i;
    int k, a;
    if (out == NULL) {
        fprintf(stderr, "hkf-demo: cannot write '%s': %s\n", path, strerror(errno));
        return 0;
    }
    fprintf(out, "time_s,valid,truth_pitch,truth_yaw,truth_roll,raw_pitch,raw_yaw,raw_roll");
    for (k = 0; k < filters; ++k) {
        fprintf(out, ",f%d_pitch,f%d_yaw,f%d_roll", k, k, k);
    }
    fprintf(out, "\n");
    for (i = 0; i < n; ++i) {
        const sim_frame_t *fr = &frames[i];
        fprintf(out, "%.6f,%d,%.4f,%.4f,%.4f", fr->time, fr->valid, fr->truth[0], fr->truth[1], fr->truth[2]);
        if (fr->valid) {
            fprintf(out, ",%.4f,%.4f,%.4f", fr->measured[0], fr->measured[1], fr->measured[2]);
        } else {
            fprintf(out, ",,,");
        }
        for (k = 0; k < filters; ++k) {
            for (a = 0; a < 3; ++a) {
                if (isnan(filtered[k][i][a])) {
                    fprintf(out, ",");
                } else {
                    fprintf(out, ",%.4f", filtered[k][i][a]);
                }
            }
        }
        fprintf(out, "\n");
    }
    if (fclose(out) != 0) {
        fprintf(stderr, "hkf-demo: error writing '%s'\n", path);
        return 0;
    }
    printf("\nwrote %ld frames to %s (f0..f%d: the filters in the order above)\n", n, path, filters - 1);
    (void)scores;
    return 1;
}

int main(int argc, char **argv)
{
    enum { FILTERS = 4 };
    demo_options_t options;
    sim_config_t config = sim_default_config();
    sim_t sim;
    sim_frame_t *frames;
    double (*filtered[FILTERS])[3];
    hkf_settings_t settings[FILTERS];
    demo_score_t raw, scores[FILTERS];
    long n, i, missing = 0;
    int k, status = 0;

    switch (parse_options(argc, argv, &options)) {
    case 1: return 0;
    case 2: return 2;
    default: break;
    }

    n = (long)(options.seconds * config.fps);
    frames = malloc((size_t)n * sizeof *frames);
    for (k = 0; k < FILTERS; ++k) {
        filtered[k] = malloc((size_t)n * sizeof *filtered[k]);
    }
    for (k = 0; k < FILTERS; ++k) {
        if (filtered[k] == NULL) {
            frames = NULL;
        }
    }
    if (frames == NULL) {
        fprintf(stderr, "hkf-demo: out of memory\n");
        return 1;
    }
    sim_init(&sim, &config, options.seed);
    for (i = 0; i < n; ++i) {
        sim_next(&sim, &frames[i]);
        missing += !frames[i].valid;
    }

    /* The paper's baseline, the paper's adaptive R, the paper's full filter, and libhkf's
     * defaults (Eq. 8 with noise calibration and the motion detector). */
    for (k = 0; k < FILTERS; ++k) {
        settings[k] = hkf_paper_settings;
    }
    settings[0].noise_mode = HKF_NOISE_CONSTANT;
    settings[0].loop_closure = HKF_LOOP_CLOSURE_OFF;
    settings[1].loop_closure = HKF_LOOP_CLOSURE_OFF;
    settings[3] = hkf_default_settings;
    memset(&raw, 0, sizeof raw);
    memset(scores, 0, sizeof scores);
    raw.name = "raw measurements";
    scores[0].name = "standard KF (constant R)";
    scores[1].name = "adaptive KF (Eq. 8)";
    scores[2].name = "adaptive KF + loop closure";
    scores[3].name = "hkf defaults (calibrated)";

    score_raw(frames, n, &raw);
    for (k = 0; k < FILTERS; ++k) {
        if (run_filter(&settings[k], frames, n, &scores[k], filtered[k]) != HKF_OK) {
            return 1;
        }
    }

    printf("hkf-demo: %.0f s simulated drive, %.0f fps, seed %lu: %ld frames, %ld without a face\n\n",
           options.seconds, config.fps, options.seed, n, missing);
    printf("%-30s %-22s %-20s %s\n", "", "RMSE vs truth, deg", "still jitter", "moving");
    printf("%-30s %6s %6s %6s   %-20s %s\n", "filter", "pitch", "yaw", "roll", "deg/frame (vs raw)",
           "RMSE deg");
    print_score(&raw, &raw);
    for (k = 0; k < FILTERS; ++k) {
        print_score(&scores[k], &raw);
    }
    if (options.csv_path != NULL &&
        !write_csv(options.csv_path, frames, n, (double (*const *)[3])filtered, scores, FILTERS)) {
        status = 1;
    }
    free(frames);
    for (k = 0; k < FILTERS; ++k) {
        free(filtered[k]);
    }
    return status;
}

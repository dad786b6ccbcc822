/*
 * hkf-demo - filters the built-in simulated drive with the paper's filter and
 * its baselines, and prints how much each one smooths and how far it lags.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "arguments.h"
#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"
#include "head_motion_sim.h"
#include "pose_angles.h"

/* The display: opentrack or a simulator reads the latest pose DISPLAY_HZ times a
 * second; a frame's pose is there CAPTURE_TO_PUBLISH_S after its capture (the
 * default estimator's measured p99, docs/estimator.md "Accuracy and speed"). Raw poses are
 * held until the next; a filter's are extrapolated to the moment of reading. */
#define DISPLAY_HZ 120.0
#define CAPTURE_TO_PUBLISH_S 0.010

typedef struct {
    double seconds;
    unsigned long seed;
    int error_model; /* a sim_error_model_t */
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
            "usage: hkf-demo [--seconds S] [--seed N] [--errors measured|assumed] [--csv FILE]\n"
            "Filters a built-in simulated drive (30 fps camera, FSA-Net-sized estimator errors,\n"
            "frames without a face) with libhkf and prints a summary, at the frames and at a display.\n"
            "  --seconds S  length of the drive, 1..3600 s (default 60)\n"
            "  --seed N     random seed of the simulated noise (default 1)\n"
            "  --errors M   measured (default): 0.25 deg of white frame noise, the rest of the\n"
            "               error a bias that follows the pose, as our estimators err on real\n"
            "               clips; assumed: hkf 0.1's model, 30 %% of the error white, 0.5 %% outliers\n"
            "  --csv FILE   also write every frame: time, truth, raw and filtered angles\n"
            "  --help       this text (--version: the version)\n");
}

/* 0 = run, 1 = help shown, 2 = bad arguments (reported) */
static int parse_options(int argc, char **argv, demo_options_t *o)
{
    int i;
    double v;
    o->seconds = 60.0;
    o->seed = 1;
    o->error_model = SIM_ERRORS_MEASURED;
    o->csv_path = NULL;
    for (i = 1; i < argc; ++i) {
        const int has_value = i + 1 < argc;
        if (argument_help_or_version(argv[i], "hkf-demo", usage)) {
            return 1;
        } else if (strcmp(argv[i], "--seconds") == 0 && has_value) {
            if (!argument_number(argv[++i], 1.0, 3600.0, &o->seconds)) {
                fprintf(stderr, "hkf-demo: --seconds wants a number from 1 to 3600, not '%s'\n", argv[i]);
                return 2;
            }
        } else if (strcmp(argv[i], "--seed") == 0 && has_value) {
            if (!argument_number(argv[++i], 0.0, 4294967295.0, &v) || v != floor(v)) {
                fprintf(stderr, "hkf-demo: --seed wants a whole number from 0 to 4294967295, not '%s'\n", argv[i]);
                return 2;
            }
            o->seed = (unsigned long)v;
        } else if (strcmp(argv[i], "--errors") == 0 && has_value) {
            ++i;
            if (strcmp(argv[i], "measured") == 0) {
                o->error_model = SIM_ERRORS_MEASURED;
            } else if (strcmp(argv[i], "assumed") == 0) {
                o->error_model = SIM_ERRORS_ASSUMED;
            } else {
                fprintf(stderr, "hkf-demo: --errors wants 'measured' or 'assumed', not '%s'\n", argv[i]);
                return 2;
            }
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
    return axis == HKF_AXIS_YAW ? pose_angle_wrap(d) : d;
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

/* The display's reading at time t of a pose: scored against the truth at t. */
static void score_display(demo_score_t *s, double t, const double angle[3])
{
    sim_frame_t at;
    memset(&at, 0, sizeof at);
    at.time = t;
    sim_head_pose(t, at.truth);
    at.still = sim_head_still(t);
    score_frame(s, &at, angle, NULL, 0, 0);
}

/* The display's readings from the pose of frame i until frame i + 1's arrives:
 * pose(ahead) gives the pose `ahead` s after frame i's capture. */
static double first_reading(double capture)
{
    return ceil((capture + CAPTURE_TO_PUBLISH_S) * DISPLAY_HZ) / DISPLAY_HZ;
}

static void score_readings(demo_score_t *s, const sim_frame_t *frames, long n, long i, const hkf_filter_t *f,
                           const double held[3])
{
    const double until = i + 1 < n ? frames[i + 1].time + CAPTURE_TO_PUBLISH_S : frames[i].time + 1.0 / DISPLAY_HZ;
    double t;
    for (t = first_reading(frames[i].time); t < until; t += 1.0 / DISPLAY_HZ) {
        double angle[3];
        int a;
        if (f != NULL) {
            hkf_output_t out;
            if (hkf_extrapolate(f, (float)(t - frames[i].time), &out) != HKF_OK) {
                continue;
            }
            for (a = 0; a < 3; ++a) {
                angle[a] = (double)out.angle[a];
            }
        } else {
            memcpy(angle, held, sizeof angle);
        }
        score_display(s, t, angle);
    }
}

/* A filter the demo runs: libhkf's settings, and whether the noise calibration runs beside them. */
typedef struct {
    hkf_settings_t settings;
    int calibrated;
} demo_filter_t;

/* Runs one filter over the frames; filtered[i] gets its output (NAN where none),
 * display its readings' score. */
static int run_filter(const demo_filter_t *filter, const sim_frame_t *frames, long n,
                      demo_score_t *score, demo_score_t *display, double (*filtered)[3])
{
    hkf_filter_t f;
    hkf_calibration_t calibration;
    hkf_output_t out;
    double previous[3] = {0.0, 0.0, 0.0};
    int have_previous = 0, previous_still = 0;
    long i;
    int a, result = hkf_init(&f, &filter->settings);
    if (result == HKF_OK && filter->calibrated) {
        result = hkf_calibration_init(&calibration, &hkf_default_calibration_settings, &f);
    }
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
            if (result == HKF_OK && filter->calibrated) {
                result = hkf_calibration_update(&calibration, &f, z, dt);
            }
        } else {
            result = hkf_predict(&f, dt, &out);
            if (result == HKF_OK && filter->calibrated) {
                result = hkf_calibration_update(&calibration, &f, NULL, dt);
            }
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
        score_readings(display, frames, n, i, &f, NULL);
        if (!frames[i].valid) { /* scored on the frames the raw measurements are: those with a face */
            have_previous = 0;
            continue;
        }
        score_frame(score, &frames[i], angle, previous, have_previous, previous_still);
        memcpy(previous, angle, sizeof previous);
        have_previous = 1;
        previous_still = frames[i].still;
    }
    return HKF_OK;
}

static void score_raw(const sim_frame_t *frames, long n, demo_score_t *score, demo_score_t *display)
{
    long i;
    int have_previous = 0, previous_still = 0;
    const double *previous = NULL, *held = NULL;
    for (i = 0; i < n; ++i) {
        if (frames[i].valid) {
            held = frames[i].measured;
        }
        if (held != NULL) { /* the display shows the last pose with a face */
            score_readings(display, frames, n, i, NULL, held);
        }
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

static void print_display_score(const demo_score_t *s)
{
    const double n = (double)(s->outputs > 0 ? s->outputs : 1);
    printf("%-30s %6.2f %6.2f %6.2f   %-20s %6.2f\n", s->name, sqrt(s->sq_error[0] / n), sqrt(s->sq_error[1] / n),
           sqrt(s->sq_error[2] / n), "",
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

enum { FILTERS = 4 };

/* The run: the simulated frames, and per filter its settings, scores and output. */
typedef struct {
    sim_config_t config;
    sim_frame_t *frames;
    long n, missing;
    double (*filtered[FILTERS])[3];
    demo_filter_t filters[FILTERS];
    demo_score_t raw, scores[FILTERS], raw_display, displays[FILTERS];
} demo_run_t;

/* The drive simulated into run->frames, and room for each filter's output: 0, or -1 out of memory. */
static int simulate(demo_run_t *run, const demo_options_t *options)
{
    sim_t sim;
    int k, ok;
    run->config = options->error_model == SIM_ERRORS_ASSUMED ? sim_assumed_config() : sim_default_config();
    run->n = (long)(options->seconds * run->config.fps);
    run->frames = malloc((size_t)run->n * sizeof *run->frames);
    ok = run->frames != NULL;
    for (k = 0; k < FILTERS; ++k) {
        run->filtered[k] = malloc((size_t)run->n * sizeof *run->filtered[k]);
        ok = ok && run->filtered[k] != NULL;
    }
    if (!ok) {
        return -1;
    }
    sim_init(&sim, &run->config, options->seed);
    for (long i = 0; i < run->n; ++i) {
        sim_next(&sim, &run->frames[i]);
        run->missing += !run->frames[i].valid;
    }
    return 0;
}

/* The paper's baseline, the paper's adaptive R, the paper's full filter, and libhkf's
 * defaults (Eq. 8 and the motion adaptation, the noise calibration beside them). */
static void set_up_filters(demo_run_t *run)
{
    static const char *const names[FILTERS] = {"standard KF (constant R)", "adaptive KF (Eq. 8)",
                                               "adaptive KF + loop closure", "hkf defaults (calibrated)"};
    for (int k = 0; k < FILTERS; ++k) {
        run->filters[k].settings = hkf_paper_settings;
        run->filters[k].calibrated = 0;
        run->scores[k].name = names[k];
        run->displays[k].name = names[k];
    }
    run->filters[0].settings.noise_mode = HKF_NOISE_CONSTANT;
    run->filters[0].settings.loop_closure = HKF_LOOP_CLOSURE_OFF;
    run->filters[1].settings.loop_closure = HKF_LOOP_CLOSURE_OFF;
    run->filters[3].settings = hkf_default_settings;
    run->filters[3].calibrated = 1;
    run->raw.name = "raw measurements";
    run->raw_display.name = "raw measurements, held";
}

static void print_tables(const demo_run_t *run, const demo_options_t *options)
{
    printf("hkf-demo: %.0f s simulated drive, %.0f fps, seed %lu, %s errors: %ld frames, %ld without a face\n\n",
           options->seconds, run->config.fps, options->seed,
           options->error_model == SIM_ERRORS_MEASURED ? "measured" : "assumed", run->n, run->missing);
    printf("%-30s %-22s %-20s %s\n", "", "RMSE vs truth, deg", "still jitter", "moving");
    printf("%-30s %6s %6s %6s   %-20s %s\n", "filter", "pitch", "yaw", "roll", "deg/frame (vs raw)",
           "RMSE deg");
    print_score(&run->raw, &run->raw);
    for (int k = 0; k < FILTERS; ++k) {
        print_score(&run->scores[k], &run->raw);
    }
    printf("\nat the display: read %.0f times a second, each frame's pose there %.0f ms after its capture\n",
           DISPLAY_HZ, 1000.0 * CAPTURE_TO_PUBLISH_S);
    printf("%-30s %-22s %-20s %s\n", "", "RMSE vs truth, deg", "", "moving");
    printf("%-30s %6s %6s %6s   %-20s %s\n", "filter", "pitch", "yaw", "roll", "", "RMSE deg");
    print_display_score(&run->raw_display);
    for (int k = 0; k < FILTERS; ++k) {
        print_display_score(&run->displays[k]);
    }
}

static void free_run(demo_run_t *run)
{
    free(run->frames);
    for (int k = 0; k < FILTERS; ++k) {
        free(run->filtered[k]);
    }
}

int main(int argc, char **argv)
{
    static demo_run_t run; /* zeroed */
    demo_options_t options;
    int status = 0;
    switch (parse_options(argc, argv, &options)) {
    case 1: return 0;
    case 2: return 2;
    default: break;
    }
    if (simulate(&run, &options) != 0) {
        fprintf(stderr, "hkf-demo: out of memory\n");
        free_run(&run);
        return 1;
    }
    set_up_filters(&run);
    score_raw(run.frames, run.n, &run.raw, &run.raw_display);
    for (int k = 0; k < FILTERS; ++k) {
        if (run_filter(&run.filters[k], run.frames, run.n, &run.scores[k], &run.displays[k], run.filtered[k]) != HKF_OK) {
            free_run(&run);
            return 1;
        }
    }
    print_tables(&run, &options);
    if (options.csv_path != NULL &&
        !write_csv(options.csv_path, run.frames, run.n, (double (*const *)[3])run.filtered, run.scores, FILTERS)) {
        status = 1;
    }
    free_run(&run);
    return status;
}

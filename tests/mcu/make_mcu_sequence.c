/*
 * make_mcu_sequence - the target tests' input and expected output: reads a raw
 * pose sequence as CSV (dt_s,valid,pitch,yaw,roll per frame; made from an LCM
 * log by raw_log_to_csv.py), runs it through libhkf built for double on this
 * machine with the two setting sets the target test runs (the paper's filter,
 * hkf_paper_settings; the defaults, hkf_default_settings with the noise
 * calibration beside, hkf_default_calibration_settings), and writes
 * sequence.h for target_test.c: the input as float and as Q16.16, and the
 * double build's angles for each (a fixed-point target is compared with the
 * double build fed the same Q16.16-rounded numbers it sees).
 * usage: make_mcu_sequence IN.csv NAME PAPER_TOLERANCE_DEG DEFAULTS_TOLERANCE_DEG OUT.h
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"

#define MAX_FRAMES 4096

/* x as Q16.16, rounded to nearest */
static long q16(double x) { return lround(x * 65536.0); }

/* How the target sees a number: as a float, or as Q16.16. */
static double to_float(double x) { return (double)(float)x; }
static double to_q16(double x) { return (double)q16(x) / 65536.0; }

/* The sequence through the double build, fed the numbers as `seen` makes them, with the noise calibration
 * beside the filter when `calibrated`; the angles after each frame (0 before the first measurement). */
static int filter_sequence(const hkf_settings_t *settings, int calibrated, int n, const double *dt, const int *valid,
                           double (*z)[3], double (*seen)(double), double (*expected)[3])
{
    hkf_filter_t filter;
    hkf_calibration_t calibration;
    int i;
    if (hkf_init(&filter, settings) != HKF_OK ||
        (calibrated && hkf_calibration_init(&calibration, &hkf_default_calibration_settings, &filter) != HKF_OK)) {
        fprintf(stderr, "make_mcu_sequence: hkf_init failed\n");
        return 1;
    }
    for (i = 0; i < n; ++i) {
        hkf_output_t o;
        const hkf_real_t zi[3] = {seen(z[i][0]), seen(z[i][1]), seen(z[i][2])};
        const int result = valid[i] ? hkf_update(&filter, zi, seen(dt[i]), &o) : hkf_predict(&filter, seen(dt[i]), &o);
        expected[i][0] = expected[i][1] = expected[i][2] = 0.0;
        if (result == HKF_OK && calibrated &&
            hkf_calibration_update(&calibration, &filter, valid[i] ? zi : NULL, seen(dt[i])) != HKF_OK) {
            fprintf(stderr, "make_mcu_sequence: frame %d: the calibration failed\n", i);
            return 1;
        }
        if (result == HKF_OK) {
            expected[i][0] = o.angle[0];
            expected[i][1] = o.angle[1];
            expected[i][2] = o.angle[2];
        } else if (!(result == HKF_ERROR_NOT_INITIALIZED && !valid[i])) {
            fprintf(stderr, "make_mcu_sequence: frame %d: %s\n", i, hkf_result_string(result));
            return 1;
        }
    }
    return 0;
}

/* The sequence, and the double build's angles for it with each settings set ([0] the paper's, [1] the defaults). */
typedef struct {
    double dt[MAX_FRAMES], z[MAX_FRAMES][3], expected[2][MAX_FRAMES][3], expected_q16[2][MAX_FRAMES][3];
    int valid[MAX_FRAMES];
    int n;
} sequence_t;

/* The frames of the CSV at path: 0, or 1 (said). */
static int read_sequence(const char *path, sequence_t *q)
{
    FILE *in = fopen(path, "r");
    if (in == NULL) {
        fprintf(stderr, "make_mcu_sequence: cannot read %s\n", path);
        return 1;
    }
    q->n = 0;
    while (q->n < MAX_FRAMES && fscanf(in, "%lf,%d,%lf,%lf,%lf", &q->dt[q->n], &q->valid[q->n], &q->z[q->n][0],
                                       &q->z[q->n][1], &q->z[q->n][2]) == 5) {
        ++q->n;
    }
    fclose(in);
    if (q->n == 0) {
        fprintf(stderr, "make_mcu_sequence: no frames in %s\n", path);
        return 1;
    }
    return 0;
}

/* The float target's part of sequence.h: its input and the double build's angles. */
static void write_float_part(FILE *out, const sequence_t *q)
{
    int i, k;
    fprintf(out, "};\n#if !defined(HKF_REAL_FIXED)\nstatic const float seq_dt[SEQ_FRAMES] = {\n");
    for (i = 0; i < q->n; ++i) {
        fprintf(out, "%.9gf,%s", q->dt[i], i % 8 == 7 ? "\n" : " ");
    }
    fprintf(out, "};\nstatic const float seq_z[SEQ_FRAMES][3] = {\n");
    for (i = 0; i < q->n; ++i) {
        fprintf(out, "{%.9gf, %.9gf, %.9gf},\n", (float)q->z[i][0], (float)q->z[i][1], (float)q->z[i][2]);
    }
    fprintf(out, "};\n/* the x86 double build's angles */\nstatic const float seq_expected[2][SEQ_FRAMES][3] = {\n");
    for (k = 0; k < 2; ++k) {
        fprintf(out, "{\n");
        for (i = 0; i < q->n; ++i) {
            fprintf(out, "{%.9gf, %.9gf, %.9gf},\n", q->expected[k][i][0], q->expected[k][i][1], q->expected[k][i][2]);
        }
        fprintf(out, "},\n");
    }
}

/* The fixed-point target's part: the input as Q16.16 and the double build's angles for that input. */
static void write_q16_part(FILE *out, const sequence_t *q, const char *paper_tolerance, const char *defaults_tolerance)
{
    int i, k;
    fprintf(out, "};\n#else\n/* Q16.16 (value * 65536): the input and the double build's angles for that input */\n");
    fprintf(out, "static const int32_t seq_dt_q16[SEQ_FRAMES] = {\n");
    for (i = 0; i < q->n; ++i) {
        fprintf(out, "%ld,%s", q16(q->dt[i]), i % 8 == 7 ? "\n" : " ");
    }
    fprintf(out, "};\nstatic const int32_t seq_z_q16[SEQ_FRAMES][3] = {\n");
    for (i = 0; i < q->n; ++i) {
        fprintf(out, "{%ld, %ld, %ld},\n", q16(q->z[i][0]), q16(q->z[i][1]), q16(q->z[i][2]));
    }
    fprintf(out, "};\nstatic const int32_t seq_expected_q16[2][SEQ_FRAMES][3] = {\n");
    for (k = 0; k < 2; ++k) {
        fprintf(out, "{\n");
        for (i = 0; i < q->n; ++i) {
            fprintf(out, "{%ld, %ld, %ld},\n", q16(q->expected_q16[k][i][0]), q16(q->expected_q16[k][i][1]),
                    q16(q->expected_q16[k][i][2]));
        }
        fprintf(out, "},\n");
    }
    fprintf(out, "};\nstatic const int32_t seq_tolerance_q16[2] = {%ld, %ld};\n#endif\n", q16(atof(paper_tolerance)),
            q16(atof(defaults_tolerance)));
}

/* sequence.h at argv[5]: 0, or 1 (said). */
static int write_header(char **argv, const sequence_t *q)
{
    FILE *out = fopen(argv[5], "w");
    int i;
    if (out == NULL) {
        fprintf(stderr, "make_mcu_sequence: cannot write %s\n", argv[5]);
        return 1;
    }
    fprintf(out, "/* Written by make_mcu_sequence from %s: do not edit. */\n", argv[1]);
    fprintf(out, "#define SEQ_NAME \"%s\"\n#define SEQ_FRAMES %d\n", argv[2], q->n);
    fprintf(out, "/* [0]: the paper's settings, [1]: the defaults */\n");
    fprintf(out, "static const float seq_tolerance_deg[2] = {%sf, %sf};\n", argv[3], argv[4]);
    fprintf(out, "static const unsigned char seq_valid[SEQ_FRAMES] = {\n");
    for (i = 0; i < q->n; ++i) {
        fprintf(out, "%d,%s", q->valid[i], i % 32 == 31 ? "\n" : "");
    }
    write_float_part(out, q);
    write_q16_part(out, q, argv[3], argv[4]);
    if (fclose(out) != 0) {
        fprintf(stderr, "make_mcu_sequence: error writing %s\n", argv[5]);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    static sequence_t q;
    const hkf_settings_t *settings[2] = {&hkf_paper_settings, &hkf_default_settings};
    int k;
    if (argc == 2 && strcmp(argv[1], "--help") == 0) {
        printf("usage: make_mcu_sequence IN.csv NAME PAPER_TOLERANCE_DEG DEFAULTS_TOLERANCE_DEG OUT.h\n"
               "Filters IN.csv (dt_s,valid,pitch,yaw,roll per frame) with libhkf in double, with the paper's\n"
               "settings and with the defaults, and writes sequence.h (the input and the expected angles, in\n"
               "float and in Q16.16) for tests/mcu/target_test.c.\n");
        return 0;
    }
    if (argc != 6) {
        fprintf(stderr, "usage: make_mcu_sequence IN.csv NAME PAPER_TOLERANCE_DEG DEFAULTS_TOLERANCE_DEG OUT.h "
                        "(see --help)\n");
        return 2;
    }
    if (read_sequence(argv[1], &q) != 0) {
        return 1;
    }
    for (k = 0; k < 2; ++k) {
        if (filter_sequence(settings[k], k == 1, q.n, q.dt, q.valid, q.z, to_float, q.expected[k]) != 0 ||
            filter_sequence(settings[k], k == 1, q.n, q.dt, q.valid, q.z, to_q16, q.expected_q16[k]) != 0) {
            return 1;
        }
    }
    if (write_header(argv, &q) != 0) {
        return 1;
    }
    printf("make_mcu_sequence: %d frames (%s) -> %s\n", q.n, argv[2], argv[5]);
    return 0;
}

/*
 * make_mcu_sequence - the target tests' input and expected output: reads a raw
 * pose sequence as CSV (dt_s,valid,pitch,yaw,roll per frame; made from an LCM
 * log by raw_log_to_csv.py), runs it through libhkf built for double on this
 * machine with the default settings, and writes sequence.h for target_test.c.
 * usage: make_mcu_sequence IN.csv NAME TOLERANCE_DEG OUT.h
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hkf/hkf.h"

#define MAX_FRAMES 4096

int main(int argc, char **argv)
{
    static double dt[MAX_FRAMES], z[MAX_FRAMES][3], expected[MAX_FRAMES][3];
    static int valid[MAX_FRAMES];
    hkf_filter_t filter;
    FILE *in, *out;
    int n = 0, i;
    if (argc == 2 && strcmp(argv[1], "--help") == 0) {
        printf("usage: make_mcu_sequence IN.csv NAME TOLERANCE_DEG OUT.h\n"
               "Filters IN.csv (dt_s,valid,pitch,yaw,roll per frame) with libhkf in double and writes\n"
               "sequence.h (the input and the expected angles) for tests/mcu/target_test.c.\n");
        return 0;
    }
    if (argc != 5) {
        fprintf(stderr, "usage: make_mcu_sequence IN.csv NAME TOLERANCE_DEG OUT.h (see --help)\n");
        return 2;
    }
    in = fopen(argv[1], "r");
    if (in == NULL) {
        fprintf(stderr, "make_mcu_sequence: cannot read %s\n", argv[1]);
        return 1;
    }
    while (n < MAX_FRAMES &&
           fscanf(in, "%lf,%d,%lf,%lf,%lf", &dt[n], &valid[n], &z[n][0], &z[n][1], &z[n][2]) == 5) {
        ++n;
    }
    fclose(in);
    if (n == 0 || hkf_init(&filter, &hkf_default_settings) != HKF_OK) {
        fprintf(stderr, "make_mcu_sequence: no frames in %s, or hkf_init failed\n", argv[1]);
        return 1;
    }
    for (i = 0; i < n; ++i) {
        hkf_output_t o;
        /* the target sees the sequence in float: filter exactly those values */
        const hkf_real_t zi[3] = {(float)z[i][0], (float)z[i][1], (float)z[i][2]};
        const int result = valid[i] ? hkf_update(&filter, zi, (float)dt[i], &o) : hkf_predict(&filter, (float)dt[i], &o);
        expected[i][0] = expected[i][1] = expected[i][2] = 0.0;
        if (result == HKF_OK) {
            expected[i][0] = o.angle[0];
            expected[i][1] = o.angle[1];
            expected[i][2] = o.angle[2];
        } else if (!(result == HKF_ERROR_NOT_INITIALIZED && !valid[i])) {
            fprintf(stderr, "make_mcu_sequence: frame %d: %s\n", i, hkf_result_string(result));
            return 1;
        }
    }
    out = fopen(argv[4], "w");
    if (out == NULL) {
        fprintf(stderr, "make_mcu_sequence: cannot write %s\n", argv[4]);
        return 1;
    }
    fprintf(out, "/* Written by make_mcu_sequence from %s: do not edit. */\n", argv[1]);
    fprintf(out, "#define SEQ_NAME \"%s\"\n#define SEQ_FRAMES %d\n#define SEQ_TOLERANCE_DEG %sf\n", argv[2], n, argv[3]);
    fprintf(out, "static const float seq_dt[SEQ_FRAMES] = {\n");
    for (i = 0; i < n; ++i) {
        fprintf(out, "%.9gf,%s", dt[i], i % 8 == 7 ? "\n" : " ");
    }
    fprintf(out, "};\nstatic const unsigned char seq_valid[SEQ_FRAMES] = {\n");
    for (i = 0; i < n; ++i) {
        fprintf(out, "%d,%s", valid[i], i % 32 == 31 ? "\n" : "");
    }
    fprintf(out, "};\nstatic const float seq_z[SEQ_FRAMES][3] = {\n");
    for (i = 0; i < n; ++i) {
        fprintf(out, "{%.9gf, %.9gf, %.9gf},\n", (float)z[i][0], (float)z[i][1], (float)z[i][2]);
    }
    fprintf(out, "};\n/* the x86 double build's angles */\nstatic const float seq_expected[SEQ_FRAMES][3] = {\n");
    for (i = 0; i < n; ++i) {
        fprintf(out, "{%.9gf, %.9gf, %.9gf},\n", expected[i][0], expected[i][1], expected[i][2]);
    }
    fprintf(out, "};\n");
    if (fclose(out) != 0) {
        fprintf(stderr, "make_mcu_sequence: error writing %s\n", argv[4]);
        return 1;
    }
    printf("make_mcu_sequence: %d frames (%s) -> %s\n", n, argv[2], argv[4]);
    return 0;
}

/*
 * position_replay - a sequence of measured head positions through libhkf's position filter with its
 * defaults and the noise calibration beside it, as hkf-filter runs them (a frame without a position
 * breaks the calibration's history), built once per numeric type: position_types_test.sh compares the
 * types' outputs on a shared clip (the libhkf issue's goal: Q16.16 within 0.05 cm of double).
 * Input: CSV lines dt_s,valid,x,y,z (cm; valid 0: no position that frame). Output: per frame with a
 * position, the filtered x y z (cm), one line each.
 * usage: position_replay IN.csv OUT.txt
 */
#include <stdio.h>

#include "hkf/hkf_calibration.h"
#include "hkf/hkf_position.h"

#if defined(HKF_REAL_FIXED)
#define REAL(x) ((hkf_real_t)((x) * 65536.0 + ((x) >= 0 ? 0.5 : -0.5)))
#define DOUBLE(x) ((double)(x) / 65536.0)
#else
#define REAL(x) ((hkf_real_t)(x))
#define DOUBLE(x) ((double)(x))
#endif

/* One frame into the filter and calibration, its position written; 0, or -1 when a call failed. */
static int step(hkf_position_filter_t *f, hkf_calibration_t *c, double dt, int valid, const double xyz[3], FILE *out)
{
    const hkf_real_t z[3] = {REAL(xyz[0]), REAL(xyz[1]), REAL(xyz[2])};
    hkf_position_output_t o;
    if (!valid) {
        return hkf_calibration_update_position(c, f, NULL, REAL(dt)) == HKF_OK ? 0 : -1;
    }
    if (hkf_position_update(f, z, REAL(1.0), REAL(dt), &o) != HKF_OK ||
        hkf_calibration_update_position(c, f, (o.flags & HKF_FLAG_GATED) ? NULL : z, REAL(dt)) != HKF_OK) {
        return -1;
    }
    return fprintf(out, "%.6f %.6f %.6f\n", DOUBLE(o.position[0]), DOUBLE(o.position[1]), DOUBLE(o.position[2])) > 0
               ? 0
               : -1;
}

int main(int argc, char **argv)
{
    hkf_position_filter_t f;
    hkf_calibration_t c;
    FILE *in, *out;
    double dt, xyz[3];
    int valid, status = 0;
    if (argc != 3) {
        fprintf(stderr, "usage: position_replay IN.csv OUT.txt\n");
        return 2;
    }
    if (hkf_position_init(&f, &hkf_position_default_settings) != HKF_OK ||
        hkf_calibration_init_position(&c, &hkf_default_calibration_settings, &f) != HKF_OK) {
        fprintf(stderr, "position_replay: init failed\n");
        return 1;
    }
    in = fopen(argv[1], "r");
    if (in == NULL) {
        perror(argv[1]);
        return 1;
    }
    out = fopen(argv[2], "w");
    if (out == NULL) {
        perror(argv[2]);
        fclose(in);
        return 1;
    }
    while (status == 0 && fscanf(in, "%lf,%d,%lf,%lf,%lf", &dt, &valid, &xyz[0], &xyz[1], &xyz[2]) == 5) {
        status = step(&f, &c, dt, valid, xyz, out);
    }
    fclose(in);
    if (fclose(out) != 0 || status != 0) {
        fprintf(stderr, "position_replay: a step or the output failed\n");
        return 1;
    }
    return 0;
}

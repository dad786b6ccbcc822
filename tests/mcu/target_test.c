/*
 * target_test.c - libhkf on a microcontroller (run under qemu-system-arm with
 * semihosting): a real raw pose sequence (hkf-estimator on a shared clip),
 * filtered with the paper's settings and then with the defaults, each against
 * the x86 double build's output of the same sequence with the same settings
 * (sequence.h, written by make_mcu_sequence). Prints the largest angle error
 * per axis and exits 0 when all are within their tolerances (the paper's
 * settings' and the defaults', tests/CMakeLists.txt). In the fixed-point build everything here is integer
 * (Q16.16 input, errors in Q16.16, printed as micro-degrees), so the
 * program links no floating-point routine at all. Also counts hkf_update's
 * instructions (instruction_counter.h).
 */
#include <stddef.h>
#include <stdint.h>

#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"
#include "instruction_counter.h"
#include "semihosting.h"
#include "sequence.h"

#if defined(HKF_REAL_FIXED)
typedef int32_t error_t; /* Q16.16 degrees */
#define SEQ_Z(i, a) seq_z_q16[i][a]
#define SEQ_DT(i) seq_dt_q16[i]
#define SEQ_EXPECTED(k, i, a) seq_expected_q16[k][i][a]
#define TOLERANCE(k) seq_tolerance_q16[k]
#define HALF_TURN ((int32_t)180 << 16)

/* The angle difference on the circle (yaw wraps at +-180). */
static error_t angle_error(int32_t a, int32_t b)
{
    int64_t d = (int64_t)a - b;
    while (d >= HALF_TURN) {
        d -= 2 * (int64_t)HALF_TURN;
    }
    while (d < -HALF_TURN) {
        d += 2 * (int64_t)HALF_TURN;
    }
    return (error_t)(d < 0 ? -d : d);
}

static long micro_degrees(error_t e) { return (long)(((int64_t)e * 15625 + 512) >> 10); } /* e 10^6 / 2^16 */
#else
typedef float error_t;
#define SEQ_Z(i, a) (hkf_real_t)seq_z[i][a]
#define SEQ_DT(i) (hkf_real_t)seq_dt[i]
#define SEQ_EXPECTED(k, i, a) seq_expected[k][i][a]
#define TOLERANCE(k) seq_tolerance_deg[k]

static float absolute(float x) { return x < 0.0f ? -x : x; }

/* The angle difference on the circle (yaw wraps at +-180). */
static error_t angle_error(float a, float b)
{
    float d = a - b;
    while (d >= 180.0f) {
        d -= 360.0f;
    }
    while (d < -180.0f) {
        d += 360.0f;
    }
    return absolute(d);
}

static long micro_degrees(error_t degrees) { return (long)(degrees * 1e6f + 0.5f); }
#endif

static void write_micro_degrees(const char *name, error_t e)
{
    semihosting_write(name);
    semihosting_write_int(micro_degrees(e));
    semihosting_write(" udeg");
}

/* One line per settings set: the largest error per axis, the tolerance, hkf_update's instructions. */
static void report(int k, const char *name, const error_t worst[3], uint32_t ticks, uint32_t updates)
{
    semihosting_write("target (");
    semihosting_write(name);
    semihosting_write("): " SEQ_NAME ", ");
    semihosting_write_int(SEQ_FRAMES);
    semihosting_write(" frames; largest error against the x86 double build: ");
    write_micro_degrees("pitch ", worst[0]);
    write_micro_degrees(", yaw ", worst[1]);
    write_micro_degrees(", roll ", worst[2]);
    semihosting_write(" (tolerance ");
    semihosting_write_int(micro_degrees(TOLERANCE(k)));
    semihosting_write(" udeg); hkf_update: ");
    semihosting_write_int((long)updates);
    semihosting_write(" calls, ");
    semihosting_write_int(counter_instructions_per_call(ticks, updates));
    semihosting_write(" instructions each (SysTick: ");
    semihosting_write_int((long)ticks);
    semihosting_write(" ticks; ");
    semihosting_write_int((long)counter_calibration_ticks());
    semihosting_write(" for 200000 instructions); sizeof(hkf_filter_t) ");
    semihosting_write_int((long)sizeof(hkf_filter_t));
    semihosting_write(" B\n");
}

/* The calibration's line: its instructions per hkf_calibration_update after an hkf_update, and its size. */
static void report_calibration(uint32_t ticks, uint32_t updates)
{
    semihosting_write("target (calibration): hkf_calibration_update: ");
    semihosting_write_int(counter_instructions_per_call(ticks, updates));
    semihosting_write(" instructions each; sizeof(hkf_calibration_t) ");
    semihosting_write_int((long)sizeof(hkf_calibration_t));
    semihosting_write(" B\n");
}

/* The sequence with settings set k (0: the paper's, 1: the defaults, with the noise calibration beside);
 * returns the failures. Not inlined: dev/benchmarks/cortex_m4_cycles.py looks for hkf_update's calls from here. */
__attribute__((noinline)) static int run_sequence(int k, const char *name, const hkf_settings_t *settings)
{
    static hkf_filter_t filter; /* static: the stack holds only the call frames */
    static hkf_calibration_t calibration;
    const int calibrated = k == 1;
    error_t worst[3] = {0, 0, 0};
    uint32_t ticks = 0, updates = 0, calibration_ticks = 0;
    int i, a, failures = 0;
    if (hkf_init(&filter, settings) != HKF_OK ||
        (calibrated && hkf_calibration_init(&calibration, &hkf_default_calibration_settings, &filter) != HKF_OK)) {
        semihosting_write("target: hkf_init failed\n");
        return 1;
    }
    for (i = 0; i < SEQ_FRAMES; ++i) {
        hkf_output_t out;
        int result;
        if (seq_valid[i]) {
            const hkf_real_t z[3] = {SEQ_Z(i, 0), SEQ_Z(i, 1), SEQ_Z(i, 2)};
            const uint32_t start = counter_now();
            result = hkf_update(&filter, z, SEQ_DT(i), &out);
            ticks += counter_ticks(start, counter_now());
            ++updates;
            if (result == HKF_OK && calibrated) {
                const uint32_t begin = counter_now();
                result = hkf_calibration_update(&calibration, &filter, z, SEQ_DT(i));
                calibration_ticks += counter_ticks(begin, counter_now());
            }
        } else {
            result = hkf_predict(&filter, SEQ_DT(i), &out);
            if (result == HKF_OK && calibrated) {
                result = hkf_calibration_update(&calibration, &filter, NULL, SEQ_DT(i));
            }
        }
        if (result != HKF_OK && !(result == HKF_ERROR_NOT_INITIALIZED && !seq_valid[i])) {
            semihosting_write("target: frame ");
            semihosting_write_int(i);
            semihosting_write(" returned ");
            semihosting_write_int(result);
            semihosting_write("\n");
            ++failures;
            continue;
        }
        if (result != HKF_OK) {
            continue; /* no track yet: nothing to compare */
        }
        for (a = 0; a < 3; ++a) {
            const error_t e = angle_error(out.angle[a], SEQ_EXPECTED(k, i, a));
            worst[a] = e > worst[a] ? e : worst[a];
        }
    }
    report(k, name, worst, ticks, updates);
    if (calibrated) {
        report_calibration(calibration_ticks, updates);
    }
    for (a = 0; a < 3; ++a) {
        failures += !(worst[a] <= TOLERANCE(k));
    }
    return failures;
}

int main(void)
{
    int failures;
    counter_start();
    failures = run_sequence(0, "paper", &hkf_paper_settings);
    failures += run_sequence(1, "defaults", &hkf_default_settings);
    return failures == 0 ? 0 : 1;
}

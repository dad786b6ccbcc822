/*
 * target_test.c - libhkf on a microcontroller (run under qemu-system-arm with
 * semihosting): a real raw pose sequence (hkf-estimator on a shared clip),
 * filtered with the default settings, against the x86 double build's output
 * of the same sequence (sequence.h, written by make_mcu_sequence). Prints the
 * largest angle error per axis and exits 0 when all are within
 * SEQ_TOLERANCE_DEG. Also counts hkf_update's instructions: under
 * qemu -icount every instruction advances the clock by the same time, so
 * SysTick ticks per instruction are calibrated on a loop of known length.
 */
#include <stdint.h>

#include "hkf/hkf.h"
#include "semihosting.h"
#include "sequence.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)

static float absolute(float x) { return x < 0.0f ? -x : x; }

/* The angle difference on the circle (yaw wraps at +-180). */
static float angle_error(float a, float b)
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

static void write_micro_degrees(const char *name, float degrees)
{
    semihosting_write(name);
    semihosting_write_int((long)(degrees * 1e6f + 0.5f));
    semihosting_write(" udeg");
}

int main(void)
{
    static hkf_filter_t filter; /* static: the stack holds only the call frames */
    float worst[3] = {0.0f, 0.0f, 0.0f};
    uint32_t ticks = 0, updates = 0, calibration_ticks;
    int i, a, failures = 0;
    if (hkf_init(&filter, &hkf_default_settings) != HKF_OK) {
        semihosting_write("target: hkf_init failed\n");
        return 1;
    }
    SYST_RVR = 0x00FFFFFFu;
    SYST_CVR = 0u;
    SYST_CSR = 0x5u; /* enabled, processor clock, no interrupt */
    {
        /* calibration: 2 instructions (subs, bne) per turn */
        uint32_t turns = 100000u;
        const uint32_t start = SYST_CVR;
        __asm__ volatile(".syntax unified\n1: subs %0, %0, #1\n\tbne 1b" : "+l"(turns));
        calibration_ticks = (start - SYST_CVR) & 0x00FFFFFFu;
    }
    for (i = 0; i < SEQ_FRAMES; ++i) {
        hkf_output_t out;
        int result;
        if (seq_valid[i]) {
            const hkf_real_t z[3] = {(hkf_real_t)seq_z[i][0], (hkf_real_t)seq_z[i][1], (hkf_real_t)seq_z[i][2]};
            const uint32_t start = SYST_CVR;
            result = hkf_update(&filter, z, (hkf_real_t)seq_dt[i], &out);
            ticks += (start - SYST_CVR) & 0x00FFFFFFu; /* counts down */
            ++updates;
        } else {
            result = hkf_predict(&filter, (hkf_real_t)seq_dt[i], &out);
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
            const float e = angle_error((float)out.angle[a], seq_expected[i][a]);
            worst[a] = e > worst[a] ? e : worst[a];
        }
    }
    semihosting_write("target: " SEQ_NAME ", ");
    semihosting_write_int(SEQ_FRAMES);
    semihosting_write(" frames; largest error against the x86 double build: ");
    write_micro_degrees("pitch ", worst[0]);
    write_micro_degrees(", yaw ", worst[1]);
    write_micro_degrees(", roll ", worst[2]);
    semihosting_write(" (tolerance ");
    semihosting_write_int((long)(SEQ_TOLERANCE_DEG * 1e6f + 0.5f));
    semihosting_write(" udeg); hkf_update: ");
    semihosting_write_int((long)updates);
    semihosting_write(" calls, ");
    semihosting_write_int((long)((float)ticks / (float)calibration_ticks * 200000.0f / (float)updates + 0.5f));
    semihosting_write(" instructions each (SysTick: ");
    semihosting_write_int((long)ticks);
    semihosting_write(" ticks; ");
    semihosting_write_int((long)calibration_ticks);
    semihosting_write(" for 200000 instructions); sizeof(hkf_filter_t) ");
    semihosting_write_int((long)sizeof(hkf_filter_t));
    semihosting_write(" B\n");
    for (a = 0; a < 3; ++a) {
        failures += !(worst[a] <= SEQ_TOLERANCE_DEG);
    }
    return failures == 0 ? 0 : 1;
}

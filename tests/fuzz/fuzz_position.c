/*
 * fuzz_position.c - libFuzzer target for libhkf's position filter
 * (hkf/hkf_position.h): arbitrary settings, then an arbitrary sequence of
 * update / predict / extrapolate / recenter / recenter_at / restart / reset /
 * set_noise / set_center, with the noise calibration beside it
 * (hkf_calibration_update_position after each update and predict), with
 * arbitrary values (NaN, infinities, huge numbers included). After every call
 * it checks:
 *   - a rejected call (negative result) left the filter bit-identical;
 *   - an accepted call wrote finite outputs, every position and centre within
 *     +-HKF_MAX_ABS_POSITION, rates within +-HKF_MAX_SPEED, variances >= 0, a
 *     known status.
 * A failed check aborts, which libFuzzer reports as a finding. Built once per
 * numeric type: fuzz_position (float) and fuzz_position_fixed (Q16.16).
 *
 * Input: [edits count][edits: field byte, 4-byte value]...[ops: op byte, operands]...
 */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hkf/hkf_calibration.h"
#include "hkf/hkf_position.h"

#if defined(HKF_REAL_FIXED)
#define FUZZ_NAME "fuzz_position_fixed"
#else
#define FUZZ_NAME "fuzz_position"
#endif

#include "fuzz_input.h"

static unsigned long long steps; /* accepted calls, for the run's summary */

static void print_steps(void) { fprintf(stderr, FUZZ_NAME ": %llu position filter steps in total\n", steps); }

/* One settings field by number, to an arbitrary value. */
static void edit_setting(hkf_position_settings_t *s, hkf_calibration_settings_t *c, uint8_t field, input_t *in)
{
    const hkf_real_t v = take_real(in);
    const int axis = field % 3;
    switch ((field / 3) % 10) {
    case 0: s->process_noise[axis] = v; break;
    case 1: s->r_const[axis] = v; break;
    case 2: axis == 0 ? (void)(s->r_min = v) : axis == 1 ? (void)(s->r_max = v) : (void)(s->p0_rate = v); break;
    case 3: s->max_dt = v; break;
    case 4: s->still_wander[axis] = v; break;
    case 5: axis == 0 ? (void)(s->start_rate = v) : (void)(s->stop_rate = v); break;
    case 6: s->max_speed = v; break;
    case 7: c->noise_time = v; break;
    case 8: c->noise_rise = v; break;
    default: s->max_gate_rejections = field % 7u; break;
    }
}

/* |x| <= limit, in the build's own numbers (Q16.16: the limit scaled) */
static int in_range(hkf_real_t x, double limit) { return isfinite((double)x) && fabs((double)x) <= (double)HKF_REAL_FROM(limit); }

static void check_output(const hkf_position_filter_t *f, const hkf_position_output_t *out)
{
    int a;
    for (a = 0; a < 3; ++a) {
        check(in_range(out->position[a], HKF_MAX_ABS_POSITION), "a position beyond +-HKF_MAX_ABS_POSITION");
        check(in_range(out->rate[a], HKF_MAX_SPEED), "a rate beyond +-HKF_MAX_SPEED");
        check(isfinite((double)out->variance[a]) && out->variance[a] >= 0, "variance not finite and >= 0");
        check(in_range(f->center[a], HKF_MAX_ABS_POSITION), "a centre beyond +-HKF_MAX_ABS_POSITION");
    }
    check(out->status >= HKF_STATUS_TRACKING && out->status <= HKF_STATUS_LOST, "unknown status");
}

/* The filter and its calibration under test, with settings edited by the input (the defaults where refused). */
static void start(input_t *in, hkf_position_filter_t *f, hkf_calibration_t *c)
{
    hkf_position_settings_t s;
    hkf_calibration_settings_t cs;
    uint8_t edits = 0, field;
    memset(&s, 0, sizeof s); /* padding too: filters are compared byte for byte */
    memset(f, 0, sizeof *f);
    s = hkf_position_default_settings;
    cs = hkf_default_calibration_settings;
    (void)take_byte(in, &edits);
    while (edits-- > 0 && take_byte(in, &field)) {
        edit_setting(&s, &cs, field, in);
    }
    if (hkf_position_init(f, &s) != HKF_OK) {
        s = hkf_position_default_settings;
        check(hkf_position_init(f, &s) == HKF_OK, "the defaults refused");
    }
    if (hkf_calibration_init_position(c, &cs, f) != HKF_OK) {
        check(hkf_calibration_init_position(c, &hkf_default_calibration_settings, f) == HKF_OK,
              "the calibration's defaults refused");
    }
}

/* A measurement (z, its R scale, dt), then the calibration, which hands n over. */
static int measurement(input_t *in, hkf_position_filter_t *f, hkf_calibration_t *c, hkf_position_output_t *out)
{
    const hkf_real_t z[3] = {take_real(in), take_real(in), take_real(in)};
    const hkf_real_t scale = take_real(in), dt = take_real(in);
    const int result = hkf_position_update(f, z, scale, dt, out);
    if (result == HKF_OK) {
        check_output(f, out);
        (void)hkf_calibration_update_position(c, f, (out->flags & HKF_FLAG_GATED) ? NULL : z, dt);
    }
    return result;
}

/* The centre set from the input: there when accepted. */
static int set_center(input_t *in, hkf_position_filter_t *f)
{
    const hkf_real_t center[3] = {take_real(in), take_real(in), take_real(in)};
    hkf_real_t got[3];
    const int result = hkf_position_set_center(f, center);
    check(result != HKF_OK || hkf_position_get_center(f, got) == HKF_OK, "a centre set but not there");
    return result;
}

/* One call chosen by op; *wrote: it wrote *out. */
static int apply(uint8_t op, input_t *in, hkf_position_filter_t *f, hkf_calibration_t *c, hkf_position_output_t *out,
                 int *wrote)
{
    int result = HKF_OK;
    *wrote = op % 9 <= 2;
    switch (op % 9) {
    case 0: return measurement(in, f, c, out);
    case 1:
        result = hkf_position_predict(f, take_real(in), out);
        check(result != HKF_OK || hkf_calibration_update_position(c, f, NULL, 0) == HKF_OK,
              "the calibration refused a gap");
        return result;
    case 2: {
        const hkf_position_filter_t kept = *f;
        result = hkf_position_extrapolate(f, take_real(in), out);
        check(memcmp(&kept, f, sizeof *f) == 0, "hkf_position_extrapolate changed the filter");
        return result;
    }
    case 3: return hkf_position_recenter(f);
    case 4: return hkf_position_recenter_at(f, take_real(in));
    case 5: hkf_position_restart(f); return HKF_OK;
    case 6: {
        const hkf_real_t n[3] = {take_real(in), take_real(in), take_real(in)};
        return hkf_position_set_noise(f, n);
    }
    case 7: return set_center(in, f);
    default: hkf_position_reset(f); return HKF_OK;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static int registered;
    input_t in = {data, size};
    hkf_position_filter_t f, before;
    hkf_calibration_t c;
    uint8_t op;
    if (!registered) {
        registered = atexit(print_steps) == 0;
    }
    start(&in, &f, &c);
    while (take_byte(&in, &op)) {
        hkf_position_output_t out;
        int wrote, result;
        before = f;
        result = apply(op, &in, &f, &c, &out, &wrote);
        if (result < 0) {
            check(memcmp(&before, &f, sizeof f) == 0, "a rejected call changed the filter");
            continue;
        }
        ++steps;
        if (wrote) {
            check_output(&f, &out);
        }
    }
    return 0;
}

/*
 * fuzz_libhkf.c - libFuzzer target for libhkf's whole API: arbitrary settings,
 * then an arbitrary sequence of init / update / update_pair (with a second
 * model's settings edited, perhaps to nonsense) / predict / extrapolate /
 * set_center / recenter / reset / get_output / set_noise / set_wander with arbitrary values
 * (NaN, infinities, denormals, huge numbers included), with the noise
 * calibration (its settings edited too) beside the filter when its settings
 * pass, and the player's rest (hkf_rest.h), stepped after each update and predict (a rest measured:
 * its values finite and in range, its wander one hkf_set_wander takes). It checks, after every call:
 *   - a rejected call (negative result) left the filter bit-identical;
 *   - an accepted call wrote only finite outputs, the yaw in [-180, 180),
 *     variances positive and bounded, R within its clamp. (Pitch and roll are
 *     not bounded: measurements of +-3600 deg a microsecond apart give rates,
 *     and so predictions, far beyond any head; finite is what is promised.)
 * A failed check aborts, which libFuzzer reports as a finding.
 *
 * Built once per numeric type: fuzz_libhkf (float) and fuzz_libhkf_fixed
 * (Q16.16: every value is any int32 bit pattern, INT32_MIN included, so the
 * saturating arithmetic and its range limits meet every extreme).
 *
 * Input: [edits count][edits: field byte, 4-byte value]...[ops: op byte, operands]...
 */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hkf/hkf.h"
#include "hkf/hkf_calibration.h"
#include "hkf/hkf_rest.h"

/* The largest angle variance any accepted call may report (deg^2). */
#define VARIANCE_BOUND 1e12

#if defined(HKF_REAL_FIXED)
#define FUZZ_NAME "fuzz_libhkf_fixed"
#define MIN_VARIANCE 0                 /* Q16.16 may round a variance to 0 (q = 0) */
#else
#define FUZZ_NAME "fuzz_libhkf"
#define MIN_VARIANCE 0 + 1e-300        /* float and double: strictly positive */
#endif
#define SETTINGS_OF(f) (&(f)->settings) /* hkf_init's copy, in every build */

#include "fuzz_input.h"

/* The noise calibration beside the filter, and whether its settings passed (calibrating). */
static hkf_calibration_settings_t calibration_settings;
static hkf_calibration_t calibration;
static int calibrating;

/* The player's rest beside the filter (hkf_rest.h), asked for at the start and by op 11. */
static hkf_rest_t rest;

/* A rest measured: every value finite and within its range, the wander one hkf_set_wander takes. */
static void check_rest(hkf_filter_t *f)
{
    hkf_rest_result_t found;
    int a;
    check(hkf_rest_get_result(&rest, &found) == HKF_OK, "a rest measured has no result");
    for (a = 0; a < 3; ++a) {
        check(found.noise[a] >= 0 && found.drift[a] >= 0 && found.spread[a] >= 0, "a rest's measure is negative");
#if !defined(HKF_REAL_FIXED)
        check(isfinite(found.noise[a]) && isfinite(found.drift[a]) && isfinite(found.spread[a]) &&
                  isfinite(found.center[a]), "a rest's measure is not finite");
#endif
        check(found.center[HKF_AXIS_YAW] >= HKF_REAL_FROM(-180) && found.center[HKF_AXIS_YAW] < HKF_REAL_FROM(180),
              "a rest's yaw not wrapped");
    }
    check(found.wander >= 0, "a rest's wander is negative");
    if (found.wander <= HKF_REAL_FROM(HKF_MAX_VARIANCE)) {
        check(hkf_set_wander(f, found.wander) == HKF_OK, "hkf_set_wander refused a rest's wander");
    }
}

/* After a call that stepped the filter (result HKF_OK): the calibration's and the rest's step with the raw
 * measurement z (NULL: none); n stays within what R may be scaled by (checked through R by after_call). */
static void calibrate(hkf_filter_t *f, int result, const hkf_real_t *z, hkf_real_t dt)
{
    if (calibrating && result == HKF_OK && hkf_calibration_update(&calibration, f, z, dt) != HKF_OK) {
        abort();
    }
    if (result == HKF_OK && hkf_rest_update(&rest, z, dt) == HKF_REST_MEASURED) {
        check_rest(f);
    }
}

/* One settings field by number, to an arbitrary value; field 16 is the calibration's (cal: NULL for a
 * second model's settings, which have none: the edit is then lost). */
static void edit_setting(hkf_settings_t *s, hkf_calibration_settings_t *cal, uint8_t field, input_t *in)
{
    const hkf_real_t v = take_real(in);
    const int axis = field % 3;
    switch ((field / 3) % 19) {
    case 0: s->process_noise[axis] = v; break;
    case 1: s->r_const[axis] = v; break;
#if defined(HKF_REAL_FIXED)
    case 2: s->noise[axis].floor = v; break;
    case 3: s->noise[axis].curvature_q24 = v; break;
#else
    case 2: s->noise[axis].tau = v; break;
    case 3: s->noise[axis].lambda = v; break;
#endif
    case 4: s->noise[axis].mu = v; break;
    case 5: s->noise[axis].sigma = v; break;
    case 6: s->r_min = v; break;
    case 7: s->r_max = v; break;
    case 8: s->lc_xi = v; break;
    case 9: s->lc_theta = v; break;
    case 10: axis == 0 ? (void)(s->p0_angle = v) : (void)(s->p0_rate = v); break;
    case 11: s->gate_sigma = v; break;
    case 12: s->coast_time = v; break;
    case 13: s->max_dt = v; break;
    case 14: s->noise_mode = (hkf_noise_mode_t)(int)(field % 5) - 1; break;
    case 15: /* the motion adaptation */
        axis == 0 ? (void)(s->start_rate = v) : axis == 1 ? (void)(s->stop_rate = v) : (void)(s->still_wander = v);
        break;
    case 16: /* the noise calibration's */
        if (cal != NULL) {
            axis == 0 ? (void)(cal->noise_time = v) : (void)(cal->noise_rise = v);
        }
        break;
    case 17: s->start_rate = v >= 0 ? v : -(v + 1); break; /* the adaptation on more often (-(v + 1): INT32_MIN too) */
    default: s->loop_closure = (int)(field % 5) - 1; s->max_gate_rejections = field % 4u; break;
    }
}

/* What R may be: [r_min, r_max] of the filter's settings, widened once hkf_update_pair has run
 * to the second model's clamp and half the smaller r_min (R of both: R1 R2 / (R1 + R2)). */
static hkf_real_t r_low, r_high;

static void allow_r(hkf_real_t low, hkf_real_t high)
{
    r_low = low < r_low ? low : r_low;
    r_high = high > r_high ? high : r_high;
}

static void check_output(const hkf_filter_t *f, const hkf_output_t *out)
{
    int a;
    for (a = 0; a < 3; ++a) {
        check(isfinite((double)out->angle[a]) && isfinite((double)out->rate[a]), "non-finite angle or rate");
        check(isfinite((double)out->variance[a]) && isfinite((double)out->r[a]), "non-finite variance or R");
        if (!((double)out->variance[a] >= MIN_VARIANCE && (double)out->variance[a] <= VARIANCE_BOUND * HKF_REAL(1.0))) {
            fprintf(stderr, FUZZ_NAME ": axis %d variance %g, status %d\n", a, (double)out->variance[a], out->status);
            check(0, "angle variance not in (0, bound]");
        }
        check(out->r[a] == 0 || (out->r[a] >= SETTINGS_OF(f)->r_min && out->r[a] <= SETTINGS_OF(f)->r_max) ||
                  (out->r[a] >= r_low && out->r[a] <= r_high),
              "R outside [r_min, r_max]");
    }
    check(out->angle[HKF_AXIS_YAW] >= HKF_REAL(-180.0) && out->angle[HKF_AXIS_YAW] < HKF_REAL(180.0),
          "yaw outside [-180, 180)");
}

/* A call on a mutable filter: rejected -> bit-identical; accepted -> sound outputs. */
static void after_call(const hkf_filter_t *before, const hkf_filter_t *f, int result, const hkf_output_t *out)
{
    if (result < 0) {
        check(memcmp(before, f, sizeof *f) == 0, "a rejected call changed the filter");
    } else if (out != NULL) {
        check(result == HKF_OK, "an unknown non-negative result");
        check_output(f, out);
    }
}

static unsigned long long steps; /* update and predict calls, for the run's summary */

static void print_steps(void)
{
    fprintf(stderr, FUZZ_NAME ": %llu filter steps in total\n", steps);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* op 7: two estimators' measurements, the second's settings edited once (maybe to nonsense; the pair
 * takes their noise, hkf_model_noise_of); either measurement may be missing (that model found no face);
 * both missing is an error. */
static void pair_step(hkf_filter_t *f, hkf_filter_t *before, const hkf_settings_t *s, input_t *in)
{
    hkf_settings_t second = *s;
    hkf_model_noise_t noise;
    hkf_output_t out;
    hkf_real_t v[3], v2[3], dt;
    uint8_t field, missing = 0;
    int result;
    memset(&out, 0, sizeof out);
    if (take_byte(in, &field)) {
        edit_setting(&second, NULL, field, in);
    }
    noise = hkf_model_noise_of(&second);
    second = *s; /* what the pair checks: the filter's settings with the second model's noise */
    second.noise_mode = noise.noise_mode;
    memcpy(second.noise, noise.noise, sizeof second.noise);
    memcpy(second.r_const, noise.r_const, sizeof second.r_const);
    second.r_min = noise.r_min;
    second.r_max = noise.r_max;
    v[0] = take_real(in), v[1] = take_real(in), v[2] = take_real(in);
    v2[0] = take_real(in), v2[1] = take_real(in), v2[2] = take_real(in);
    if (hkf_init(before, &second) == HKF_OK) { /* (before is rewritten below) */
        const hkf_real_t low = second.r_min < s->r_min ? second.r_min : s->r_min;
#if defined(HKF_REAL_FIXED)
        allow_r(low / 2 - 1, second.r_max); /* less a unit for the quotient's rounding */
#else
        allow_r(low * HKF_REAL(0.4999), second.r_max);
#endif
    }
    *before = *f;
    (void)take_byte(in, &missing);
    dt = take_real(in);
    result = hkf_update_pair(f, missing % 4 == 1 ? NULL : v, missing % 4 == 2 ? NULL : v2, &noise, dt, &out);
    after_call(before, f, result, &out);
    calibrate(f, result, missing % 4 == 1 ? v2 : v, dt);
    if (missing % 4 == 3) {
        *before = *f;
        result = hkf_update_pair(f, NULL, NULL, &noise, dt, &out);
        if (result != HKF_ERROR_NULL_ARGUMENT) {
            abort();
        }
        after_call(before, f, result, &out);
    }
    ++steps;
}

/* op 0 and 1: a measurement, or a frame without one; the calibration's step after either. */
static void step(hkf_filter_t *f, hkf_filter_t *before, input_t *in, int measured)
{
    hkf_output_t out;
    hkf_real_t v[3], dt;
    int result;
    memset(&out, 0, sizeof out);
    if (measured) {
        v[0] = take_real(in), v[1] = take_real(in), v[2] = take_real(in);
    }
    dt = take_real(in);
    result = measured ? hkf_update(f, v, dt, &out) : hkf_predict(f, dt, &out);
    ++steps;
    after_call(before, f, result, &out);
    calibrate(f, result, measured ? v : NULL, dt);
}

/* op 3, 8 and 10: a value from outside, arbitrary: a centre, a noise level (refused, or R scaled within its
 * clamp), a wander (refused with the filter untouched, or taken). */
static void set_step(hkf_filter_t *f, const hkf_filter_t *before, input_t *in, int op)
{
    hkf_real_t v[3];
    int result;
    if (op == 10) {
        result = hkf_set_wander(f, take_real(in));
    } else {
        v[0] = take_real(in), v[1] = take_real(in), v[2] = take_real(in);
        result = op == 3 ? hkf_set_center(f, v) : hkf_set_noise(f, v);
    }
    after_call(before, f, result, NULL);
}

/* One API call on the filter, chosen by op, its arguments from the input. */
static void api_step(hkf_filter_t *f, hkf_filter_t *before, const hkf_settings_t *s, input_t *in, uint8_t op)
{
    hkf_output_t out;
    int result;
    *before = *f;
    memset(&out, 0, sizeof out);
    switch (op % 12) {
    case 0:
    case 1:
        step(f, before, in, op % 12 == 0);
        break;
    case 3:
    case 8:
    case 10:
        set_step(f, before, in, op % 12);
        break;
    case 11:
        check(hkf_rest_start(&rest) == HKF_OK, "hkf_rest_start failed");
        break;
    case 2:
        result = hkf_extrapolate(f, take_real(in), &out);
        check(memcmp(before, f, sizeof *f) == 0, "hkf_extrapolate changed the filter");
        after_call(before, f, result, result == HKF_OK ? &out : NULL);
        break;
    case 4:
        result = hkf_recenter(f);
        after_call(before, f, result, NULL);
        break;
    case 5:
        hkf_reset(f);
        if (calibrating && hkf_calibration_reset(&calibration, f) != HKF_OK) {
            abort();
        }
        break;
    case 6:
        result = hkf_get_output(f, &out);
        check(memcmp(before, f, sizeof *f) == 0, "hkf_get_output changed the filter");
        after_call(before, f, result, result == HKF_OK ? &out : NULL);
        break;
    case 7:
        pair_step(f, before, s, in);
        break;
    default:
        result = hkf_init(f, s);
        after_call(before, f, result, NULL);
        if (calibrating && result == HKF_OK && hkf_calibration_init(&calibration, &calibration_settings, f) != HKF_OK) {
            abort();
        }
        break;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static hkf_filter_t f, before;
    input_t in = {data, size};
    hkf_settings_t s = hkf_default_settings;
    uint8_t count = 0, op, field;
    int result, i;

    static int registered;
    if (!registered) {
        registered = atexit(print_steps) == 0;
    }
    memset(&f, 0, sizeof f);
    calibration_settings = hkf_default_calibration_settings;
    if (take_byte(&in, &count)) {
        for (i = 0; i < count % 8 && take_byte(&in, &field); ++i) {
            edit_setting(&s, &calibration_settings, field, &in);
        }
    }
    before = f;
    result = hkf_init(&f, &s);
    after_call(&before, &f, result, NULL);
    if (result != HKF_OK) {
        return 0; /* rejected settings: nothing more to run */
    }
    r_low = s.r_min;
    r_high = s.r_max;
    calibrating = hkf_calibration_init(&calibration, &calibration_settings, &f) == HKF_OK;
    if (hkf_rest_init(&rest, &hkf_default_rest_settings) != HKF_OK || hkf_rest_start(&rest) != HKF_OK) {
        abort();
    }
    while (take_byte(&in, &op)) {
        api_step(&f, &before, &s, &in, op);
    }
    return 0;
}

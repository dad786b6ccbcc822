/*
 * test_support.h - what the libhkf cmocka tests share: conversions between
 * doubles and hkf_real_t, a tolerance-aware comparison, and small settings
 * helpers. Each test file is built once per numeric type (float, double,
 * Q16.16 fixed point), as libfixmath tests its variants; TEST_TOL is the
 * absolute tolerance in degrees for that build.
 */
#ifndef HKF_TEST_SUPPORT_H
#define HKF_TEST_SUPPORT_H

#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "hkf/hkf.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifndef TEST_TOL
#error "TEST_TOL (degrees) must be defined by the build"
#endif

/* R(x): a double as hkf_real_t (rounded; in fixed point saturated, and NaN,
 * which fixed point cannot hold, as 0). D(x): back to double. */
#if defined(HKF_REAL_FIXED)
#define TEST_HAS_NON_FINITE 0 /* fixed point has no NaN or infinity to reject */
static inline hkf_real_t R(double x)
{
    const double scaled = x * 65536.0;
    if (!(scaled == scaled)) {
        return 0;
    }
    return scaled >= 2147483647.0 ? INT32_MAX : scaled <= -2147483647.0 ? -INT32_MAX : (hkf_real_t)lround(scaled);
}
static inline double D(hkf_real_t x) { return (double)x / 65536.0; }
#else
#define TEST_HAS_NON_FINITE 1
#define R(x) ((hkf_real_t)(x))
static inline double D(hkf_real_t x) { return (double)x; }
#endif
/* A value under test as a double: hkf_real_t through D, anything else as is. */
static inline double plain_double(double x) { return x; }
#define TO_DOUBLE(x) _Generic((x), hkf_real_t: D, default: plain_double)(x)

/* hkf_update_pair with the second model's noise as a settings set gives it (second may be NULL). */
static inline int update_pair(hkf_filter_t *f, const hkf_real_t *z, const hkf_real_t *z2, const hkf_settings_t *second,
                              hkf_real_t dt, hkf_output_t *out)
{
    hkf_model_noise_t noise;
    if (second == NULL) {
        return hkf_update_pair(f, z, z2, NULL, dt, out);
    }
    noise = hkf_model_noise_of(second);
    return hkf_update_pair(f, z, z2, &noise, dt, out);
}

/* A noise curve from Table I's (tau, lambda, mu, sigma), in every build. */
static inline hkf_noise_curve_t table_curve(double tau, double lambda, double mu, double sigma)
{
    hkf_noise_curve_t c;
#if defined(HKF_REAL_FIXED)
    const double q24 = lambda / (2.0 * sigma * sigma) * 16777216.0;
    c.floor = R(tau - lambda);
    c.curvature_q24 = q24 >= 2147483647.0 ? INT32_MAX : q24 <= -2147483647.0 ? -INT32_MAX : (int32_t)lround(q24);
#else
    c.tau = R(tau);
    c.lambda = R(lambda);
#endif
    c.mu = R(mu);
    c.sigma = R(sigma);
    return c;
}

static inline void assert_near_at(double actual, double expected, double tol, const char *what,
                                  const char *file, int line)
{
    if (!(fabs(actual - expected) <= tol)) {
        print_error("%s = %.9g, expected %.9g (tolerance %.3g)\n", what, actual, expected, tol);
        _fail(file, line);
    }
}
/* actual may be hkf_real_t or double; expected and tol are in degrees (double) */
#define assert_near(actual, expected, tol) \
    assert_near_at(TO_DOUBLE(actual), (double)(expected), (double)(tol), #actual, __FILE__, __LINE__)

/* Plain settings that make hand arithmetic easy: constant R, constant q (no
 * motion adaptation), no loop closure, no gate, unit-ish numbers, no coasting limit
 * within 10 s. */
static inline hkf_settings_t plain_settings(void)
{
    hkf_settings_t s = hkf_default_settings;
    int a;
    for (a = 0; a < HKF_AXES; ++a) {
        s.process_noise[a] = R(12);
        s.r_const[a] = R(2);
    }
    s.noise_mode = HKF_NOISE_CONSTANT;
    s.loop_closure = HKF_LOOP_CLOSURE_OFF;
    s.start_rate = 0; /* no motion adaptation */
    s.p0_angle = R(4);
    s.p0_rate = R(8);
    s.coast_time = R(10);
    s.max_dt = R(2);
    return s;
}

static inline void set3(hkf_real_t v[3], double pitch, double yaw, double roll)
{
    v[0] = R(pitch);
    v[1] = R(yaw);
    v[2] = R(roll);
}

/* A yaw difference, wrapped to [-180, 180). */
static inline double yaw_diff(double a, double b)
{
    double d = fmod(a - b + 180.0, 360.0);
    return (d < 0.0 ? d + 360.0 : d) - 180.0;
}

#ifdef __cplusplus
}
#endif

#endif /* HKF_TEST_SUPPORT_H */

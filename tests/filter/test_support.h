/*
 * test_support.h - what the libhkf cmocka tests share: a tolerance-aware
 * comparison for float and double builds, and small settings helpers.
 * Each test file is built once per numeric type (float, double); TEST_TOL
 * is the absolute tolerance in degrees for that build.
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

#ifndef TEST_TOL
#error "TEST_TOL (degrees) must be defined by the build"
#endif

static inline void assert_near_at(double actual, double expected, double tol, const char *what,
                                  const char *file, int line)
{
    if (!(fabs(actual - expected) <= tol)) {
        print_error("%s = %.9g, expected %.9g (tolerance %.3g)\n", what, actual, expected, tol);
        _fail(file, line);
    }
}
#define assert_near(actual, expected, tol) \
    assert_near_at((double)(actual), (double)(expected), (double)(tol), #actual, __FILE__, __LINE__)

/* Plain settings that make hand arithmetic easy: constant R, no loop
 * closure, no gate, unit-ish numbers, no coasting limit within 10 s. */
static inline hkf_settings_t plain_settings(void)
{
    hkf_settings_t s = hkf_default_settings;
    int a;
    for (a = 0; a < HKF_AXES; ++a) {
        s.process_noise[a] = (hkf_real_t)12;
        s.r_const[a] = (hkf_real_t)2;
    }
    s.noise_mode = HKF_NOISE_CONSTANT;
    s.loop_closure = HKF_LOOP_CLOSURE_OFF;
    s.p0_angle = (hkf_real_t)4;
    s.p0_rate = (hkf_real_t)8;
    s.coast_time = (hkf_real_t)10;
    s.max_dt = (hkf_real_t)2;
    return s;
}

static inline void set3(hkf_real_t v[3], double pitch, double yaw, double roll)
{
    v[0] = (hkf_real_t)pitch;
    v[1] = (hkf_real_t)yaw;
    v[2] = (hkf_real_t)roll;
}

/* A yaw difference, wrapped to [-180, 180). */
static inline double yaw_diff(double a, double b)
{
    double d = fmod(a - b + 180.0, 360.0);
    return (d < 0.0 ? d + 360.0 : d) - 180.0;
}

#endif /* HKF_TEST_SUPPORT_H */

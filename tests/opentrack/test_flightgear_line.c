/* hkf-opentrack --flightgear's line: FlightGear's view conventions, the eye point, the text. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include <cmocka.h>

#include "flightgear_line.h"

/* The bridge's values of a head turned right (yaw 20), nose up (pitch 10), right ear down (hkf roll 30:
 * opentrack's roll -30), moved to the image's right 5 cm, up 2 cm and back 10 cm: FlightGear looks right
 * (heading -20), up (pitch 10), tilts the right ear down (roll 30), and the eye moves left, up and aft of
 * the aircraft's eye point. */
static void test_view_conventions(void **state)
{
    const double values[OPENTRACK_FIELDS] = {5.0, 2.0, 10.0, 20.0, 10.0, -30.0}; /* x, y, z (cm), yaw, pitch, roll */
    const double eye[3] = {-0.2, 0.6, -3.5};
    double view[6];
    (void)state;
    flightgear_view_values(values, eye, view);
    assert_float_equal(view[0], -20.0, 1e-12);
    assert_float_equal(view[1], 10.0, 1e-12);
    assert_float_equal(view[2], 30.0, 1e-12);
    assert_float_equal(view[3], -0.25, 1e-12);
    assert_float_equal(view[4], 0.62, 1e-12);
    assert_float_equal(view[5], -3.4, 1e-12);
}

/* The text: six comma-separated numbers and a newline, read back to 0.0001 deg and 0.01 mm. */
static void test_line_text(void **state)
{
    const double view[6] = {-20.123456, 10.5, 0.0, -0.25, 0.62, -3.4};
    double back[6];
    char line[FLIGHTGEAR_LINE_MAX], end;
    int n, i;
    (void)state;
    n = flightgear_line(view, line, sizeof line);
    assert_true(n > 0 && (size_t)n == strlen(line));
    assert_int_equal(line[n - 1], '\n');
    assert_int_equal(sscanf(line, "%lf,%lf,%lf,%lf,%lf,%lf%c", &back[0], &back[1], &back[2], &back[3], &back[4],
                            &back[5], &end), 7);
    assert_int_equal(end, '\n');
    for (i = 0; i < 6; ++i) {
        assert_float_equal(back[i], view[i], i < 3 ? 1e-4 : 1e-5);
    }
}

/* A value that is not finite is never sent, and a line that does not fit is not cut short. */
static void test_refused(void **state)
{
    double view[6] = {1.0, 2.0, 3.0, 0.1, 0.2, 0.3};
    char line[FLIGHTGEAR_LINE_MAX];
    (void)state;
    view[4] = NAN;
    assert_int_equal(flightgear_line(view, line, sizeof line), -1);
    view[4] = 0.2;
    view[0] = INFINITY;
    assert_int_equal(flightgear_line(view, line, sizeof line), -1);
    view[0] = -179.9999;
    assert_int_equal(flightgear_line(view, line, 20), -1);
    assert_true(flightgear_line(view, line, sizeof line) > 20);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_view_conventions),
        cmocka_unit_test(test_line_text),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

/*
 * test_errors.c - every error path: bad settings give their specific code,
 * bad input gives its code and leaves the filter byte-for-byte untouched.
 */
#include "test_support.h"

static const hkf_real_t frame_dt = HKF_REAL_FROM(1.0 / 30.0);

typedef struct {
    const char *what;
    void (*spoil)(hkf_settings_t *s);
    int expected;
} bad_setting_t;

#if TEST_HAS_NON_FINITE
static void nan_q(hkf_settings_t *s) { s->process_noise[1] = R(NAN); }
static void inf_tau(hkf_settings_t *s) { s->noise[2] = table_curve(INFINITY, 1, 0, 10); }
static void nan_r_max(hkf_settings_t *s) { s->r_max = R(NAN); }
static void nan_max_dt(hkf_settings_t *s) { s->max_dt = R(NAN); }
#endif
static void bad_mode(hkf_settings_t *s) { s->noise_mode = (hkf_noise_mode_t)7; }
static void zero_sigma(hkf_settings_t *s) { s->noise[0].sigma = 0; }
static void negative_sigma(hkf_settings_t *s) { s->noise[2].sigma = R(-1); }
static void zero_r_min(hkf_settings_t *s) { s->r_min = 0; }
static void r_min_above_max(hkf_settings_t *s) { s->r_min = R(10); s->r_max = R(5); }
static void zero_r_const(hkf_settings_t *s) { s->r_const[2] = 0; }
static void negative_q(hkf_settings_t *s) { s->process_noise[0] = R(-1); }
static void bad_loop_closure(hkf_settings_t *s) { s->loop_closure = 3; }
static void negative_xi(hkf_settings_t *s) { s->lc_xi = R(-0.1); }
static void xi_above_one(hkf_settings_t *s) { s->lc_xi = R(1.01); }
static void negative_theta(hkf_settings_t *s) { s->lc_theta = R(-1); }
static void zero_p0_angle(hkf_settings_t *s) { s->p0_angle = 0; }
static void zero_p0_rate(hkf_settings_t *s) { s->p0_rate = 0; }
static void negative_gate(hkf_settings_t *s) { s->gate_sigma = R(-1); }
static void gate_without_rejections(hkf_settings_t *s) { s->gate_sigma = R(3); s->max_gate_rejections = 0; }
static void zero_coast(hkf_settings_t *s) { s->coast_time = 0; }
static void zero_max_dt(hkf_settings_t *s) { s->max_dt = 0; }
/* beyond the ranges hkf.h states (found by tests/fuzz/fuzz_libhkf.c: p0_angle 2.7e36 was accepted) */
static void huge_p0_angle(hkf_settings_t *s) { s->p0_angle = R(2.7e36); }
static void huge_p0_rate(hkf_settings_t *s) { s->p0_rate = R(2 * HKF_MAX_VARIANCE); }
static void huge_q(hkf_settings_t *s) { s->process_noise[2] = R(2 * HKF_MAX_PROCESS_NOISE); }
static void huge_r_max(hkf_settings_t *s) { s->r_max = R(2 * HKF_MAX_VARIANCE); }
static void tiny_r_min(hkf_settings_t *s) { s->r_min = R(1e-30); }
static void huge_r_const(hkf_settings_t *s) { s->r_const[1] = R(1e20); }
static void tiny_sigma(hkf_settings_t *s) { s->noise[1].sigma = R(1e-30); }
static void huge_tau(hkf_settings_t *s) { s->noise[0] = table_curve(1e20, 1, 0, 10); }
static void huge_mu(hkf_settings_t *s) { s->noise[2].mu = R(2 * HKF_MAX_ABS_ANGLE); }
static void huge_theta(hkf_settings_t *s) { s->lc_theta = R(HKF_MAX_LC_THETA + 40); }
static void huge_gate(hkf_settings_t *s) { s->gate_sigma = R(1e10); }
static void long_coast(hkf_settings_t *s) { s->coast_time = R(HKF_MAX_TIME + 1); }
static void long_max_dt(hkf_settings_t *s) { s->max_dt = R(1e30); }
static void negative_still_wander(hkf_settings_t *s) { s->still_wander = R(-1); }
static void start_rate_below_min(hkf_settings_t *s) { s->start_rate = R(HKF_MIN_RATE / 2); }
static void huge_start_rate(hkf_settings_t *s) { s->start_rate = R(2 * HKF_MAX_RATE); }
static void negative_stop_rate(hkf_settings_t *s) { s->stop_rate = R(-1); }
#if defined(HKF_REAL_FIXED)
/* the fixed-point build's own limits (hkf.h) */
static void narrow_sigma(hkf_settings_t *s) { s->noise[1] = table_curve(7.64, 4.11, -0.35, 0.5); }
static void curvature_100(hkf_settings_t *s) { s->noise[1] = table_curve(300, 200, 0, 1); }
static void curvature_200(hkf_settings_t *s) { s->noise[1] = table_curve(500, 400, 0, 1); }
static void deep_floor(hkf_settings_t *s) { s->noise[1] = table_curve(10, 2000, 0, 100); }
#endif

/* hkf_init on the defaults spoiled by each row gives the row's result. */
static void check_settings_table(const bad_setting_t *table, size_t rows)
{
    size_t i;
    for (i = 0; i < rows; ++i) {
        hkf_settings_t s = hkf_default_settings;
        hkf_filter_t f;
        int result;
        table[i].spoil(&s);
        result = hkf_init(&f, &s);
        if (result != table[i].expected) {
            print_error("%s: hkf_init gave %d (%s), expected %d (%s)\n", table[i].what, result,
                        hkf_result_string(result), table[i].expected, hkf_result_string(table[i].expected));
            fail();
        }
        assert_string_not_equal(hkf_result_string(result), "unknown hkf result code");
    }
}

static void test_init_rejects_each_bad_setting(void **state)
{
    static const bad_setting_t table[] = {
#if TEST_HAS_NON_FINITE
        {"NaN q", nan_q, HKF_ERROR_SETTING_NON_FINITE},
        {"infinite tau", inf_tau, HKF_ERROR_SETTING_NON_FINITE},
        {"NaN r_max", nan_r_max, HKF_ERROR_SETTING_NON_FINITE},
        {"NaN max_dt", nan_max_dt, HKF_ERROR_SETTING_NON_FINITE},
#endif
        {"noise mode 7", bad_mode, HKF_ERROR_SETTING_NOISE_MODE},
        {"sigma 0", zero_sigma, HKF_ERROR_SETTING_SIGMA},
        {"sigma -1", negative_sigma, HKF_ERROR_SETTING_SIGMA},
        {"r_min 0", zero_r_min, HKF_ERROR_SETTING_R_RANGE},
        {"r_min > r_max", r_min_above_max, HKF_ERROR_SETTING_R_RANGE},
        {"r_const 0", zero_r_const, HKF_ERROR_SETTING_R_CONST},
        {"q < 0", negative_q, HKF_ERROR_SETTING_PROCESS_NOISE},
        {"loop closure 3", bad_loop_closure, HKF_ERROR_SETTING_LOOP_CLOSURE},
        {"xi < 0", negative_xi, HKF_ERROR_SETTING_LC_XI},
        {"xi > 1", xi_above_one, HKF_ERROR_SETTING_LC_XI},
        {"theta < 0", negative_theta, HKF_ERROR_SETTING_LC_THETA},
        {"p0_angle 0", zero_p0_angle, HKF_ERROR_SETTING_P0},
        {"p0_rate 0", zero_p0_rate, HKF_ERROR_SETTING_P0},
        {"gate < 0", negative_gate, HKF_ERROR_SETTING_GATE},
        {"gate on, 0 rejections", gate_without_rejections, HKF_ERROR_SETTING_GATE},
        {"coast_time 0", zero_coast, HKF_ERROR_SETTING_COAST_TIME},
        {"max_dt 0", zero_max_dt, HKF_ERROR_SETTING_MAX_DT},
        {"p0_angle 2.7e36", huge_p0_angle, HKF_ERROR_SETTING_P0},
        {"p0_rate > max", huge_p0_rate, HKF_ERROR_SETTING_P0},
        {"q > max", huge_q, HKF_ERROR_SETTING_PROCESS_NOISE},
        {"r_max > max", huge_r_max, HKF_ERROR_SETTING_R_RANGE},
        {"r_min 1e-30", tiny_r_min, HKF_ERROR_SETTING_R_RANGE},
        {"r_const 1e20", huge_r_const, HKF_ERROR_SETTING_R_CONST},
        {"sigma 1e-30", tiny_sigma, HKF_ERROR_SETTING_SIGMA},
        {"tau 1e20", huge_tau, HKF_ERROR_SETTING_CURVE},
        {"mu beyond the angle range", huge_mu, HKF_ERROR_SETTING_CURVE},
        {"theta beyond the maximum", huge_theta, HKF_ERROR_SETTING_LC_THETA},
        {"gate 1e10", huge_gate, HKF_ERROR_SETTING_GATE},
        {"coast_time > max", long_coast, HKF_ERROR_SETTING_COAST_TIME},
        {"max_dt 1e30", long_max_dt, HKF_ERROR_SETTING_MAX_DT},
        {"still_wander < 0", negative_still_wander, HKF_ERROR_SETTING_MOTION},
        {"start_rate above 0 but below HKF_MIN_RATE", start_rate_below_min, HKF_ERROR_SETTING_MOTION},
        {"start_rate > max", huge_start_rate, HKF_ERROR_SETTING_MOTION},
        {"stop_rate < 0", negative_stop_rate, HKF_ERROR_SETTING_MOTION},
#if defined(HKF_REAL_FIXED)
        {"sigma 0.5 (fixed point: >= 1)", narrow_sigma, HKF_ERROR_SETTING_SIGMA},
        {"curvature 100 (fixed point: <= 127)", curvature_100, HKF_OK},
        {"curvature 200 (fixed point: <= 127)", curvature_200, HKF_ERROR_SETTING_CURVE},
        {"floor -1990 (fixed point: |floor| <= 1024)", deep_floor, HKF_ERROR_SETTING_CURVE},
#endif
    };
    (void)state;
    check_settings_table(table, sizeof table / sizeof table[0]);
}

/* Every documented range endpoint (hkf.h) is accepted: a range check one
 * comparison too strict refuses a value the documentation promises. */
static void edge_xi_0(hkf_settings_t *s) { s->lc_xi = 0; }
static void edge_xi_1(hkf_settings_t *s) { s->lc_xi = R(1); }
static void edge_theta_0(hkf_settings_t *s) { s->lc_theta = 0; }
static void edge_theta_max(hkf_settings_t *s) { s->lc_theta = R(HKF_MAX_LC_THETA); }
static void edge_q_0(hkf_settings_t *s) { s->process_noise[0] = s->process_noise[1] = s->process_noise[2] = 0; }
static void edge_q_max(hkf_settings_t *s) { s->process_noise[1] = R(HKF_MAX_PROCESS_NOISE); }
static void edge_r_range(hkf_settings_t *s) { s->r_min = R(HKF_MIN_VARIANCE); s->r_max = R(HKF_MAX_VARIANCE); }
static void edge_r_equal(hkf_settings_t *s) { s->r_min = s->r_max = R(3); }
static void edge_r_const_max(hkf_settings_t *s) { s->r_const[0] = R(HKF_MAX_VARIANCE); }
static void edge_p0_max(hkf_settings_t *s) { s->p0_angle = s->p0_rate = R(HKF_MAX_VARIANCE); }
static void edge_gate_max(hkf_settings_t *s) { s->gate_sigma = R(HKF_MAX_GATE_SIGMA); s->max_gate_rejections = 1u; }
static void edge_gate_off(hkf_settings_t *s) { s->gate_sigma = 0; s->max_gate_rejections = 0u; }
static void edge_coast_max(hkf_settings_t *s) { s->coast_time = R(HKF_MAX_TIME); }
static void edge_max_dt_max(hkf_settings_t *s) { s->max_dt = R(HKF_MAX_TIME); }
static void edge_motion_max(hkf_settings_t *s)
{
    s->still_wander = R(HKF_MAX_VARIANCE);
    s->start_rate = R(HKF_MAX_RATE);
    s->stop_rate = R(HKF_MAX_RATE);
}
static void edge_motion_0(hkf_settings_t *s) { s->still_wander = 0; s->start_rate = 0; s->stop_rate = 0; }
static void edge_rates_min(hkf_settings_t *s) { s->start_rate = R(HKF_MIN_RATE); s->stop_rate = R(HKF_MIN_RATE); }
static void edge_sigma_min(hkf_settings_t *s) { s->noise[1] = table_curve(8, 4, 0, HKF_MIN_SIGMA); }
static void edge_sigma_max(hkf_settings_t *s) { s->noise[1] = table_curve(8, 4, 0, HKF_MAX_SIGMA); }
static void edge_mu_max(hkf_settings_t *s) { s->noise[1] = table_curve(8, 4, -HKF_MAX_ABS_ANGLE, 30); }

static void test_init_accepts_every_endpoint(void **state)
{
    static const bad_setting_t table[] = {
        {"lc_xi 0", edge_xi_0, HKF_OK},
        {"lc_xi 1", edge_xi_1, HKF_OK},
        {"lc_theta 0", edge_theta_0, HKF_OK},
        {"lc_theta HKF_MAX_LC_THETA", edge_theta_max, HKF_OK},
        {"process_noise 0", edge_q_0, HKF_OK},
        {"process_noise HKF_MAX_PROCESS_NOISE", edge_q_max, HKF_OK},
        {"r_min HKF_MIN_VARIANCE, r_max HKF_MAX_VARIANCE", edge_r_range, HKF_OK},
        {"r_min = r_max", edge_r_equal, HKF_OK},
        {"r_const HKF_MAX_VARIANCE", edge_r_const_max, HKF_OK},
        {"p0 HKF_MAX_VARIANCE", edge_p0_max, HKF_OK},
        {"gate HKF_MAX_GATE_SIGMA, 1 rejection", edge_gate_max, HKF_OK},
        {"gate off, 0 rejections", edge_gate_off, HKF_OK},
        {"coast_time HKF_MAX_TIME", edge_coast_max, HKF_OK},
        {"max_dt HKF_MAX_TIME", edge_max_dt_max, HKF_OK},
        {"still_wander, start_rate, stop_rate at their maxima", edge_motion_max, HKF_OK},
        {"still_wander, start_rate, stop_rate 0", edge_motion_0, HKF_OK},
        {"start_rate, stop_rate at HKF_MIN_RATE", edge_rates_min, HKF_OK},
        {"sigma HKF_MIN_SIGMA", edge_sigma_min, HKF_OK},
        {"sigma HKF_MAX_SIGMA", edge_sigma_max, HKF_OK},
        {"mu -HKF_MAX_ABS_ANGLE", edge_mu_max, HKF_OK},
    };
    (void)state;
    check_settings_table(table, sizeof table / sizeof table[0]);
}

#if TEST_HAS_NON_FINITE
/* The error names what is wrong with a measurement: with one axis at the
 * largest angle accepted and another NaN, it is the NaN (not the angle). */
static void test_error_names_the_bad_axis(void **state)
{
    hkf_settings_t s = hkf_default_settings;
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3];
    (void)state;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    z[0] = R(HKF_MAX_ABS_ANGLE);
    z[1] = R(NAN);
    z[2] = 0;
    assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_ERROR_NON_FINITE);
    z[1] = R(HKF_MAX_ABS_ANGLE + 1);
    assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_ERROR_ANGLE_RANGE);
}
#endif

static void test_defaults_and_presets_are_valid(void **state)
{
    hkf_settings_t s = hkf_default_settings;
    hkf_filter_t f;
    (void)state;
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    memcpy(s.noise, hkf_noise_hopenet, sizeof s.noise);
    assert_int_equal(hkf_init(&f, &s), HKF_OK);
    /* Hopenet yaw at its centre: 10.74 - 7.017 */
    assert_near(hkf_observation_noise(&f, HKF_AXIS_YAW, R(-5.57)), 3.723, 1e-3);
    assert_string_equal(hkf_result_string(12345), "unknown hkf result code");
    {
        int code;
        for (code = HKF_ERROR_SETTING_CALIBRATION; code <= HKF_OK; ++code) { /* limits in numbers, not macro names */
            assert_null(strstr(hkf_result_string(code), "HKF_"));
        }
    }
}

static void test_null_arguments(void **state)
{
    hkf_filter_t f;
    hkf_output_t out;
    hkf_real_t z[3] = {0, 0, 0};
    (void)state;
    assert_int_equal(hkf_init(NULL, &hkf_default_settings), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_init(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    assert_int_equal(hkf_update(NULL, z, frame_dt, &out), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_update(&f, NULL, frame_dt, &out), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_predict(NULL, frame_dt, &out), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_extrapolate(NULL, 0, &out), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_extrapolate(&f, 0, NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_get_output(NULL, &out), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_get_output(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_set_center(NULL, z), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_set_center(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_recenter(NULL), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_get_center(NULL, z), HKF_ERROR_NULL_ARGUMENT);
    assert_int_equal(hkf_get_center(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
    hkf_reset(NULL); /* harmless */
    assert_near(hkf_observation_noise(NULL, 0, 0), 0, 0);
    /* out may be NULL for update and predict */
    assert_int_equal(hkf_update(&f, z, 0, NULL), HKF_OK);
    assert_int_equal(hkf_predict(&f, frame_dt, NULL), HKF_OK);
    {
        hkf_state_t st;
        assert_int_equal(hkf_get_state(NULL, &st), HKF_ERROR_NULL_ARGUMENT);
        assert_int_equal(hkf_get_state(&f, NULL), HKF_ERROR_NULL_ARGUMENT);
        z[1] = R(3.0);
        assert_int_equal(hkf_update(&f, z, frame_dt, &out), HKF_OK);
        assert_int_equal(hkf_get_state(&f, &st), HKF_OK); /* the whole state: what the output shows of it */
        assert_true(st.angle[1] == out.angle[1] && st.rate[1] == out.rate[1] && st.p00[1] == out.variance[1]);
        assert_true(D(st.p01[1]) > 0.0 && D(st.p11[1]) > 0.0);
    }
}

static void test_before_first_measurement(void **state)
{
    hkf_filter_t f;
    hkf_output_t out;
    (void)state;
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    assert_int_equal(hkf_predict(&f, frame_dt, &out), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_extrapolate(&f, 0, &out), HKF_ERROR_NOT_INITIALIZED);
    assert_int_equal(hkf_recenter(&f), HKF_ERROR_NOT_INITIALIZED);
}

/* Bad input on a running filter: the code, and not one byte changed. */
static void test_bad_input_leaves_state_untouched(void **state)
{
    hkf_filter_t f, copy;
    hkf_output_t out;
    hkf_real_t z[3] = {1, 2, 3};
    hkf_real_t bad[3];
    const hkf_real_t dt = frame_dt;
    const hkf_real_t max_dt = hkf_default_settings.max_dt;
    int i;
    (void)state;
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    for (i = 0; i < 10; ++i) {
        assert_int_equal(hkf_update(&f, z, dt, &out), HKF_OK);
    }
    copy = f;

    for (i = 0; i < 3; ++i) {
        memcpy(bad, z, sizeof bad);
#if TEST_HAS_NON_FINITE
        bad[i] = R(NAN);
        assert_int_equal(hkf_update(&f, bad, dt, &out), HKF_ERROR_NON_FINITE);
        bad[i] = R(-INFINITY);
        assert_int_equal(hkf_update(&f, bad, dt, &out), HKF_ERROR_NON_FINITE);
#else
        bad[i] = INT32_MIN; /* fixed point's most negative value: beyond every limit, and |x| overflows */
        assert_int_equal(hkf_update(&f, bad, dt, &out), HKF_ERROR_ANGLE_RANGE);
#endif
        bad[i] = R(HKF_MAX_ABS_ANGLE + 1);
        assert_int_equal(hkf_update(&f, bad, dt, &out), HKF_ERROR_ANGLE_RANGE);
        assert_int_equal(hkf_set_center(&f, bad), HKF_ERROR_ANGLE_RANGE);
    }
#if TEST_HAS_NON_FINITE
    assert_int_equal(hkf_update(&f, z, R(NAN), &out), HKF_ERROR_NON_FINITE);
    assert_int_equal(hkf_update(&f, z, R(INFINITY), &out), HKF_ERROR_NON_FINITE);
    assert_int_equal(hkf_predict(&f, R(NAN), &out), HKF_ERROR_NON_FINITE);
    assert_int_equal(hkf_extrapolate(&f, R(NAN), &out), HKF_ERROR_NON_FINITE);
#endif
    assert_int_equal(hkf_update(&f, z, 0, &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_update(&f, z, -dt, &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_update(&f, z, R(D(max_dt) * 1.001), &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_predict(&f, 0, &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_predict(&f, -dt, &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_predict(&f, max_dt * 2, &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_extrapolate(&f, -dt, &out), HKF_ERROR_DT_RANGE);
    assert_int_equal(hkf_extrapolate(&f, max_dt * 2, &out), HKF_ERROR_DT_RANGE);
    assert_memory_equal(&f, &copy, sizeof f);

    /* the largest dt allowed is accepted */
    assert_int_equal(hkf_predict(&f, max_dt, &out), HKF_OK);
    /* and a bad first measurement does not start a track */
    assert_int_equal(hkf_init(&f, &hkf_default_settings), HKF_OK);
    bad[0] = R(HKF_MAX_ABS_ANGLE + 1);
    assert_int_equal(hkf_update(&f, bad, 0, &out), HKF_ERROR_ANGLE_RANGE);
    assert_int_equal(hkf_predict(&f, dt, &out), HKF_ERROR_NOT_INITIALIZED);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_init_rejects_each_bad_setting),
        cmocka_unit_test(test_defaults_and_presets_are_valid),
        cmocka_unit_test(test_init_accepts_every_endpoint),
#if TEST_HAS_NON_FINITE
        cmocka_unit_test(test_error_names_the_bad_axis),
#endif
        cmocka_unit_test(test_null_arguments),
        cmocka_unit_test(test_before_first_measurement),
        cmocka_unit_test(test_bad_input_leaves_state_untouched),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}

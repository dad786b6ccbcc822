/* hkf_result.c - descriptions of the hkf_result_t codes. */
#include "hkf/hkf.h"
#include "hkf/hkf_rest.h"
#include "hkf/hkf_position.h"

/* A limit's value as this build defines it (float, double and Q16.16 differ), in the text. */
#define HKF_TEXT(x) HKF_TEXT_OF(x)
#define HKF_TEXT_OF(x) #x

const char *hkf_result_string(int result)
{
    switch (result) {
    case HKF_OK: return "ok";
    case HKF_ERROR_NULL_ARGUMENT: return "a pointer argument is NULL";
    case HKF_ERROR_NON_FINITE: return "a measurement or dt is NaN or infinite";
    case HKF_ERROR_DT_RANGE: return "dt is not in (0, max_dt]";
    case HKF_ERROR_ANGLE_RANGE: return "an angle is beyond +-" HKF_TEXT(HKF_MAX_ABS_ANGLE) " degrees";
    case HKF_ERROR_POSITION_RANGE: return "a position is beyond +-" HKF_TEXT(HKF_MAX_ABS_POSITION) " cm";
    case HKF_ERROR_SCALE_RANGE: return "a position's R scale is not in [1, " HKF_TEXT(HKF_MAX_POSITION_SCALE) "]";
    case HKF_ERROR_NOISE_RANGE: return "a noise level is not above 0";
    case HKF_ERROR_NOT_INITIALIZED: return "no measurement has started a track yet";
    case HKF_ERROR_SETTING_NON_FINITE: return "a setting is NaN or infinite";
    case HKF_ERROR_SETTING_NOISE_MODE: return "noise_mode is not a hkf_noise_mode_t";
    case HKF_ERROR_SETTING_SIGMA: return "a noise curve's sigma is not in [" HKF_TEXT(HKF_MIN_SIGMA) ", " HKF_TEXT(HKF_MAX_SIGMA) "] deg";
    case HKF_ERROR_SETTING_R_RANGE: return "r_min and r_max do not satisfy " HKF_TEXT(HKF_MIN_VARIANCE) " <= r_min <= r_max <= " HKF_TEXT(HKF_MAX_VARIANCE);
    case HKF_ERROR_SETTING_R_CONST: return "an r_const is not in (0, " HKF_TEXT(HKF_MAX_VARIANCE) "]";
    case HKF_ERROR_SETTING_PROCESS_NOISE: return "a process_noise is not in [0, " HKF_TEXT(HKF_MAX_PROCESS_NOISE) "]";
    case HKF_ERROR_SETTING_LOOP_CLOSURE: return "loop_closure is not a hkf_loop_closure_t";
    case HKF_ERROR_SETTING_LC_XI: return "lc_xi is not in [0, 1]";
    case HKF_ERROR_SETTING_LC_THETA: return "lc_theta is not in [0, " HKF_TEXT(HKF_MAX_LC_THETA) "] deg";
    case HKF_ERROR_SETTING_P0: return "p0_angle or p0_rate is not in (0, " HKF_TEXT(HKF_MAX_VARIANCE) "]";
    case HKF_ERROR_SETTING_GATE:
        return "gate_sigma is not in [0, " HKF_TEXT(HKF_MAX_GATE_SIGMA) "] (a position's max_speed: [0, " HKF_TEXT(HKF_MAX_SPEED) "] cm/s), "
               "or the gate is on with max_gate_rejections 0";
    case HKF_ERROR_SETTING_COAST_TIME: return "coast_time is not in (0, " HKF_TEXT(HKF_MAX_TIME) "] s";
    case HKF_ERROR_SETTING_MAX_DT: return "max_dt is not in (0, " HKF_TEXT(HKF_MAX_TIME) "] s";
    case HKF_ERROR_SETTING_CURVE: return "a noise curve's tau, lambda or mu is beyond its range";
    case HKF_ERROR_SETTING_MOTION:
        return "still_wander is not in [0, " HKF_TEXT(HKF_MAX_VARIANCE) "] deg^2 (the position's: cm^2), start_rate or stop_rate "
               "neither 0 nor in [" HKF_TEXT(HKF_MIN_RATE) ", " HKF_TEXT(HKF_MAX_RATE) "] 1/s";
    case HKF_ERROR_SETTING_CALIBRATION:
        return "noise_time is not in [0, " HKF_TEXT(HKF_MAX_TIME) "] s or noise_rise not in [0, "
               HKF_TEXT(HKF_MAX_NOISE_RISE) "] 1/s";
    case HKF_ERROR_SETTING_REST:
        return "rest_time is not in [0, " HKF_TEXT(HKF_MAX_TIME) "] s, rest_reach not in (0, " HKF_TEXT(HKF_MAX_LC_THETA)
               "] deg or stillness not in [0, " HKF_TEXT(HKF_MAX_STILLNESS) "]";
    default: return "unknown hkf result code";
    }
}

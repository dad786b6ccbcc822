// reference_reals.hpp - hkf_real_t <-> double for the Eigen reference tests: the identity in float and
// double, Q16.16 in fixed point (rounded to nearest).
#ifndef HKF_TEST_REFERENCE_REALS_HPP
#define HKF_TEST_REFERENCE_REALS_HPP

#include <cmath>

#include "hkf/hkf_real.h"

#if defined(HKF_REAL_FIXED)
inline double D(hkf_real_t x) { return static_cast<double>(x) / 65536.0; }
inline hkf_real_t R(double x) { return static_cast<hkf_real_t>(std::lround(x * 65536.0)); }
#else
inline double D(hkf_real_t x) { return static_cast<double>(x); }
inline hkf_real_t R(double x) { return static_cast<hkf_real_t>(x); }
#endif

#endif // HKF_TEST_REFERENCE_REALS_HPP

/*
 * hkf_real.h - the one numeric type of libhkf.
 *
 * The filter is written once against hkf_real_t. The build picks the type:
 *   default            float
 *   HKF_REAL_DOUBLE    double   (CMake: -DHKF_REAL=double)
 *   HKF_REAL_FIXED     Q16.16 fixed point in an int32_t (CMake: -DHKF_REAL=fixed)
 * The definition is PUBLIC on the hkf::hkf target and written into hkf.pc, so
 * every user compiles against the same type as the library.
 *
 * Only the math layer (src/hkf_math.h, src/hkf_math_fixed.c) differs between
 * the three: the filter itself is one source (see hkf_math.h for the
 * fixed-point range analysis).
 */
#ifndef HKF_REAL_H
#define HKF_REAL_H

#if defined(HKF_REAL_DOUBLE)
typedef double hkf_real_t;
#define HKF_REAL(c) (c)
#define HKF_REAL_FROM(x) ((double)(x))
#elif defined(HKF_REAL_FIXED)
#include <stdint.h>
/* Q16.16: value = integer / 65536. Range +-32768, resolution 1.5e-5. */
typedef int32_t hkf_real_t;
/* A constant in Q16.16, rounded to nearest. Use it on constant expressions
 * only: the compiler then folds it, and no floating point reaches the target. */
#define HKF_REAL_FROM(x) ((hkf_real_t)((x) * 65536.0 + ((x) >= 0 ? 0.5 : -0.5)))
#define HKF_REAL(c) HKF_REAL_FROM(c)
#else
typedef float hkf_real_t;
/* Writes a literal constant in the library's type: HKF_REAL(0.5) is 0.5f. */
#define HKF_REAL(c) (c##f)
/* Any constant expression in the library's type. */
#define HKF_REAL_FROM(x) ((float)(x))
#endif

#endif /* HKF_REAL_H */

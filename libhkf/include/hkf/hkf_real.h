/*
 * hkf_real.h - the one numeric type of libhkf.
 *
 * The filter is written once against hkf_real_t. The build picks the type:
 *   default            float
 *   HKF_REAL_DOUBLE    double   (CMake: -DHKF_REAL=double)
 * The definition is PUBLIC on the hkf::hkf target and written into hkf.pc, so
 * every user compiles against the same type as the library.
 *
 * A fixed-point build is meant to add a third branch here and in
 * src/hkf_math.h (mul, div, exp, sqrt) - never a second copy of the filter.
 */
#ifndef HKF_REAL_H
#define HKF_REAL_H

#if defined(HKF_REAL_DOUBLE)
typedef double hkf_real_t;
#define HKF_REAL(c) (c)
#else
typedef float hkf_real_t;
/* Writes a literal constant in the library's type: HKF_REAL(0.5) is 0.5f. */
#define HKF_REAL(c) (c##f)
#endif

#endif /* HKF_REAL_H */

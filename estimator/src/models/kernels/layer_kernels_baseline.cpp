// layer_kernels_baseline.cpp - the layers' loops for what every CPU of the architecture has (see
// layer_kernels_impl.hpp): SSE2 on x86-64, 4 x 3 tiles of 4 floats (12 sums, the 2 x 3 inputs and a
// product in 16 xmm registers; 6 x 2 ran as fast); NEON on aarch64, 8 x 2 tiles of 4 floats (16 sums of
// 32 registers, fused multiply-adds).
#if defined(__aarch64__)
#define HKF_KERNELS_NAME "neon"
#define HKF_TILE_ROWS 8
#define HKF_TILE_VECTORS 2
#else
#define HKF_KERNELS_NAME "sse2"
#define HKF_TILE_ROWS 4
#define HKF_TILE_VECTORS 3
#endif
#define HKF_KERNELS_NAMESPACE baseline_kernels
#define HKF_KERNELS_TABLE kBaselineKernels
#define HKF_KERNELS_LEVEL SimdLevel::baseline
#define HKF_LANES 4
#include "layer_kernels_impl.hpp"

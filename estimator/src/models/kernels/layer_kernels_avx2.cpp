// layer_kernels_avx2.cpp - the layers' loops for AVX2 with FMA (built with -mavx2 -mfma; see
// layer_kernels_impl.hpp): 6 x 2 tiles of 8 floats (12 sums, 2 inputs and a broadcast weight in 16 ymm
// registers; 4 x 3 ran as fast).
#define HKF_KERNELS_NAMESPACE avx2_kernels
#define HKF_KERNELS_TABLE kAvx2Kernels
#define HKF_KERNELS_LEVEL SimdLevel::avx2
#define HKF_KERNELS_NAME "avx2"
#define HKF_LANES 8
#define HKF_TILE_ROWS 6
#define HKF_TILE_VECTORS 2
#include "layer_kernels_impl.hpp"

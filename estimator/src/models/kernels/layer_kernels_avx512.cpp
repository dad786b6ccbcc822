// layer_kernels_avx512.cpp - the layers' loops for AVX-512F (built with -mavx512f -mfma; see
// layer_kernels_impl.hpp): 8 x 3 tiles of 16 floats.
#define HKF_KERNELS_NAMESPACE avx512_kernels
#define HKF_KERNELS_TABLE kAvx512Kernels
#define HKF_KERNELS_LEVEL SimdLevel::avx512
#define HKF_KERNELS_NAME "avx512"
#define HKF_LANES 16
#define HKF_TILE_ROWS 8
#define HKF_TILE_VECTORS 3
#include "layer_kernels_impl.hpp"

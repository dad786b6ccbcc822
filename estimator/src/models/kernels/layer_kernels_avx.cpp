// layer_kernels_avx.cpp - the layers' loops for AVX without FMA or AVX2 (built with -mavx; see
// layer_kernels_impl.hpp): the CPUs of 2011-2013 (Intel Sandy and Ivy Bridge, AMD Bulldozer to Piledriver), which
// would otherwise run SSE2's. 6 x 2 tiles of 8 floats as at AVX2, each multiply-add a multiply and an add (AVX's
// three operands need no copies); the exp polynomial in Estrin's form, as at SSE2.
#define HKF_KERNELS_NAMESPACE avx_kernels
#define HKF_KERNELS_TABLE kAvxKernels
#define HKF_KERNELS_LEVEL SimdLevel::avx
#define HKF_KERNELS_NAME "avx"
#define HKF_LANES 8
#define HKF_TILE_ROWS 6
#define HKF_TILE_VECTORS 2
#include "layer_kernels_impl.hpp"

// simd_level.hpp - which instruction-set level the estimator's own layers (layers/) run at:
// the best this CPU runs, or the one HKF_SIMD names (avx512, avx2, avx, sse2 on x86-64; neon on aarch64;
// default: the best), so that any machine can measure and test the levels below its own. The CPU's
// features are read through OpenCV, so OPENCV_CPU_DISABLE (for example AVX512_SKX) lowers OpenCV's own
// layers and ours alike: a machine can play a CPU with fewer features.
#pragma once

#include <vector>

#include "kernels/layer_kernels.hpp"

namespace hkf_estimator {

// The levels this CPU and this build run, best first.
std::vector<SimdLevel> simd_levels_supported();

// The table of a level (layer_kernels.hpp), whether or not this CPU runs it.
const LayerKernels &layer_kernels_of(SimdLevel level);

// The table the layers made from now on use: at the first call, HKF_SIMD's level or the best.
// Throws EstimatorError for an HKF_SIMD this program does not know or this CPU cannot run.
const LayerKernels &layer_kernels_in_use();

// Sets the level for layers made from now on (the tests and benchmarks, one level after another).
// Throws EstimatorError for a level this CPU cannot run.
void use_simd_level(SimdLevel level);

}  // namespace hkf_estimator

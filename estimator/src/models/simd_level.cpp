// simd_level.cpp - see simd_level.hpp.
#include "simd_level.hpp"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <string>

#include <opencv2/core/utility.hpp>

#include "model_spec.hpp"  // EstimatorError

namespace hkf_estimator {

namespace {

// The levels this build has, best first.
#if defined(__x86_64__)
constexpr SimdLevel kLevels[] = {SimdLevel::avx512, SimdLevel::avx2, SimdLevel::avx, SimdLevel::baseline};
#else
constexpr SimdLevel kLevels[] = {SimdLevel::baseline};
#endif

bool cpu_runs(SimdLevel level)
{
    switch (level) {
    case SimdLevel::baseline:
        return true;
#if defined(__x86_64__)
    case SimdLevel::avx:
        return cv::checkHardwareSupport(CV_CPU_AVX);
    case SimdLevel::avx2:
        return cv::checkHardwareSupport(CV_CPU_AVX2) && cv::checkHardwareSupport(CV_CPU_FMA3);
    case SimdLevel::avx512:
        return cv::checkHardwareSupport(CV_CPU_AVX_512F) && cv::checkHardwareSupport(CV_CPU_FMA3);
#endif
    default:
        return false;
    }
}

std::string level_names()
{
    std::string names;
    for (SimdLevel level : kLevels) names += std::string(names.empty() ? "" : ", ") + layer_kernels_of(level).name;
    return names + " or default";
}

SimdLevel level_from_environment()
{
    const char *text = std::getenv("HKF_SIMD");
    if (text == nullptr || *text == '\0' || std::strcmp(text, "default") == 0) return simd_levels_supported().front();
    for (SimdLevel level : kLevels) {
        if (std::strcmp(text, layer_kernels_of(level).name) == 0) {
            if (!cpu_runs(level))
                throw EstimatorError(std::string("HKF_SIMD=") + text + ": this CPU cannot run it (it runs " +
                                     layer_kernels_of(simd_levels_supported().front()).name + " and below)");
            return level;
        }
    }
    throw EstimatorError(std::string("HKF_SIMD='") + text + "' is not a level (" + level_names() + ")");
}

std::atomic<const LayerKernels *> in_use{nullptr};

}  // namespace

std::vector<SimdLevel> simd_levels_supported()
{
    std::vector<SimdLevel> levels;
    for (SimdLevel level : kLevels)
        if (cpu_runs(level)) levels.push_back(level);
    return levels;
}

const LayerKernels &layer_kernels_of(SimdLevel level)
{
#if defined(__x86_64__)
    if (level == SimdLevel::avx512) return kAvx512Kernels;
    if (level == SimdLevel::avx2) return kAvx2Kernels;
    if (level == SimdLevel::avx) return kAvxKernels;
#endif
    (void)level;
    return kBaselineKernels;
}

const LayerKernels &layer_kernels_in_use()
{
    const LayerKernels *kernels = in_use.load();
    if (kernels == nullptr) {
        const LayerKernels *chosen = &layer_kernels_of(level_from_environment());
        in_use.compare_exchange_strong(kernels, chosen);  // the first caller's choice stands
        kernels = in_use.load();
    }
    return *kernels;
}

void use_simd_level(SimdLevel level)
{
    if (!cpu_runs(level))
        throw EstimatorError(std::string("this CPU cannot run the ") + layer_kernels_of(level).name + " level");
    in_use.store(&layer_kernels_of(level));
}

}  // namespace hkf_estimator

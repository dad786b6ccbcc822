// fuzz_onnx_model.cpp - libFuzzer target for the models' loading path: the bytes of a model file are
// checked as hkf-estimator checks them (estimator/src/models/onnx_check.cpp) and, when the check takes
// them, given to OpenCV's ONNX importer with the estimator's own layers registered, as load_onnx_network
// gives them. Seeds: the shipped models and small graphs (run_fuzz.sh, make_onnx_seeds.py).
// Checks: nothing crashes or reads out of bounds (ASan + UBSan on our code); a refused file is refused
// with a reason; the check gives the same answer twice.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/dnn.hpp>

#include "fast_layers.hpp"
#include "onnx_check.hpp"

namespace {
long checked, accepted, loaded;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const bool ready = [] {
        cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
        hkf_estimator::register_fast_layers();
        std::atexit([] {
            std::printf("fuzz_onnx_model: %ld files checked, %ld accepted, %ld loaded by OpenCV in total\n", checked,
                        accepted, loaded);
        });
        return true;
    }();
    (void)ready;
    ++checked;
    const std::string problem = hkf_estimator::onnx_model_problem(data, size);
    if (problem != hkf_estimator::onnx_model_problem(data, size)) std::abort();  // no state between calls
    if (!problem.empty()) return 0;
    ++accepted;
    try {
        cv::dnn::Net net = cv::dnn::readNetFromONNX(reinterpret_cast<const char *>(data), size);
        if (!net.empty()) ++loaded;
    } catch (const cv::Exception &) {  // refused by OpenCV with an error: what the estimator reports
    } catch (const std::exception &) {
    }
    return 0;
}

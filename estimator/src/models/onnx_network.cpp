// onnx_network.cpp - see onnx_network.hpp.
#include "onnx_network.hpp"

#include <cstdint>
#include <fstream>
#include <vector>

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>

#include "fast_layers.hpp"
#include "onnx_check.hpp"
#include "safe_files.h"

namespace hkf_estimator {

namespace {
constexpr std::streamoff kMaxModelBytes = 2LL << 30;  // protobuf's own limit
}  // namespace

cv::dnn::Net load_onnx_network(const std::string &file, const std::vector<std::string> &outputs)
{
    std::ifstream in(file, std::ios::binary);
    if (!in) throw EstimatorError("model file " + file + " is missing (" + kModelsHint + ")");
    safe_note_read(file.c_str());  // an input: no output of this run may be it (safe_files.h)
    // The bytes read once, checked (onnx_check.hpp), and the same bytes given to OpenCV: no second read
    // of a file that could have changed in between.
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    if (size < 0 || size > kMaxModelBytes)
        throw EstimatorError("cannot load model file " + file + ": " +
                             (size < 0 ? std::string("not a readable file") : "larger than 2 GiB, the most a protobuf holds"));
    std::vector<char> bytes(static_cast<size_t>(size));
    in.seekg(0);
    if (!in.read(bytes.data(), size)) throw EstimatorError("cannot load model file " + file + ": a read error");
    const std::string problem =
        onnx_model_problem(reinterpret_cast<const std::uint8_t *>(bytes.data()), bytes.size());
    if (!problem.empty()) throw EstimatorError("cannot load model file " + file + ": " + problem);
    cv::dnn::Net net;
    register_fast_layers();  // the op types a rewritten graph uses (dev/models/fast_layers.py)
    // OpenCV warns once per node of a domain it has no importer for (the "hkf" one of those layers), and logs
    // an error line of its own before it throws: its log is quietened while reading (hkf's message says why)
    const auto log_level = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
    try {
        net = cv::dnn::readNetFromONNX(bytes.data(), bytes.size());
    } catch (const cv::Exception &e) {
        cv::utils::logging::setLogLevel(log_level);
        throw EstimatorError("cannot load model file " + file + ": not a readable ONNX model (" + e.err + ")");
    }
    cv::utils::logging::setLogLevel(log_level);
    if (net.empty()) throw EstimatorError("cannot load model file " + file + ": empty network");
    for (const auto &name : outputs)
        if (net.getLayerId(name) < 0) throw EstimatorError("model file " + file + " has no output '" + name + "'");
    return net;
}

cv::Mat network_input(const ModelSpec &spec, const cv::Mat &bgr)
{
    if (bgr.empty() || bgr.type() != CV_8UC3) throw EstimatorError("a network input must be a non-empty 8-bit BGR image");
    cv::Mat resized, color, scaled;
    if (bgr.cols == spec.input_width && bgr.rows == spec.input_height) {
        resized = bgr;
    } else {
        cv::resize(bgr, resized, cv::Size(spec.input_width, spec.input_height), 0, 0, cv::INTER_LINEAR);
    }
    if (spec.rgb) {
        cv::cvtColor(resized, color, cv::COLOR_BGR2RGB);
    } else {
        color = resized;
    }
    color.convertTo(scaled, CV_32FC3, spec.scale);
    scaled -= cv::Scalar(spec.mean[0], spec.mean[1], spec.mean[2]);
    cv::divide(scaled, cv::Scalar(spec.std[0], spec.std[1], spec.std[2]), scaled);
    return cv::dnn::blobFromImage(scaled);  // HWC -> NCHW, no further change
}

}  // namespace hkf_estimator

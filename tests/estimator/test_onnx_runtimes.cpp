// Runs an ONNX model with OpenCV DNN on given inputs and compares every named
// output with the values onnxruntime gave (written by test_onnx_runtimes.py).
// usage: test_onnx_runtimes CASE_FILE
// CASE_FILE: model path line, input shape line "n c h w", output count line,
// then per output a line "name size"; then binary float32: the input, then
// each output's expected values.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include <opencv2/dnn.hpp>

int main(int argc, char **argv)
{
    if (argc != 2) return 2;
    std::ifstream in(argv[1], std::ios::binary);
    std::string model;
    int shape[4], outputs = 0;
    std::getline(in, model);
    in >> shape[0] >> shape[1] >> shape[2] >> shape[3] >> outputs;
    std::vector<std::string> names(static_cast<size_t>(outputs));
    std::vector<size_t> sizes(static_cast<size_t>(outputs));
    for (int i = 0; i < outputs; ++i) in >> names[static_cast<size_t>(i)] >> sizes[static_cast<size_t>(i)];
    in.get();  // the newline before the binary part
    cv::Mat input(4, shape, CV_32F);
    in.read(reinterpret_cast<char *>(input.ptr<float>()), static_cast<std::streamsize>(input.total() * sizeof(float)));
    cv::dnn::Net net = cv::dnn::readNetFromONNX(model);
    net.setInput(input);
    std::vector<cv::Mat> out;
    net.forward(out, names);
    int failures = 0;
    for (size_t k = 0; k < names.size(); ++k) {
        std::vector<float> expected(sizes[k]);
        in.read(reinterpret_cast<char *>(expected.data()), static_cast<std::streamsize>(sizes[k] * sizeof(float)));
        if (!in || out[k].total() != sizes[k]) {
            std::printf("%s: %s has %zu values, expected %zu\n", model.c_str(), names[k].c_str(), out[k].total(), sizes[k]);
            ++failures;
            continue;
        }
        double worst = 0.0, scale = 1e-6;
        for (size_t i = 0; i < sizes[k]; ++i) {
            worst = std::max(worst, static_cast<double>(std::fabs(out[k].ptr<float>()[i] - expected[i])));
            scale = std::max(scale, static_cast<double>(std::fabs(expected[i])));
        }
        const bool ok = worst <= 1e-3 * scale;  // relative to the output's magnitude
        failures += !ok;
        std::printf("%s %s: %zu values, largest |opencv - onnxruntime| %.2e (output magnitude %.2e)\n", ok ? "ok  " : "FAIL",
                    names[k].c_str(), sizes[k], worst, scale);
    }
    return failures == 0 ? 0 : 1;
}

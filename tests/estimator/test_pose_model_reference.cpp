// Feeds given input tensors to the estimator's AngleBinsModel (OpenCV DNN) and
// compares its decoded angles with the expected ones (from onnxruntime).
// usage: test_pose_model_reference FILE MODELS_DIR SPEC_DIR
// FILE: int32 n, c, h, w; then n times: c*h*w float32 input, 3 float32 pitch yaw roll (hkf convention).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <vector>

#include "model_spec.hpp"
#include "angle_bins_model.hpp"
#include "simd_level.hpp"

int main(int argc, char **argv)
{
    using namespace hkf_estimator;
    if (argc != 4) {
        std::fprintf(stderr, "usage: test_pose_model_reference FILE MODELS_DIR SPEC_DIR\n");
        return 2;
    }
    std::ifstream in(argv[1], std::ios::binary);
    int header[4];
    if (!in.read(reinterpret_cast<char *>(header), sizeof header)) {
        std::fprintf(stderr, "cannot read %s\n", argv[1]);
        return 2;
    }
    try {
        std::printf("the estimator's layers at %s\n", layer_kernels_in_use().name);  // HKF_SIMD, or the best
    } catch (const EstimatorError &e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    AngleBinsModel model(load_model_spec(argv[3], "whenet", argv[2]));
    const int n = header[0], sizes[4] = {1, header[1], header[2], header[3]};
    int failures = 0;
    double worst = 0.0;
    for (int i = 0; i < n; ++i) {
        cv::Mat input(4, sizes, CV_32F);
        float expected[3];
        in.read(reinterpret_cast<char *>(input.ptr<float>()), static_cast<std::streamsize>(input.total() * sizeof(float)));
        in.read(reinterpret_cast<char *>(expected), sizeof expected);
        if (!in) {
            std::fprintf(stderr, "%s is truncated\n", argv[1]);
            return 2;
        }
        const HeadPose p = model.estimate_input(input);
        const double diff = std::max({std::fabs(p.pitch - expected[0]), std::fabs(p.yaw - expected[1]), std::fabs(p.roll - expected[2])});
        worst = std::max(worst, diff);
        failures += diff > 0.01;
        std::printf("opencv sample %d: pitch %8.3f yaw %8.3f roll %8.3f (expected %8.3f %8.3f %8.3f) diff %.5f\n", i, p.pitch,
                    p.yaw, p.roll, expected[0], expected[1], expected[2], diff);
    }
    std::printf("opencv vs onnxruntime: %d samples, worst difference %.5f deg\n", n, worst);
    return failures == 0 && n > 0 ? 0 : 1;
}

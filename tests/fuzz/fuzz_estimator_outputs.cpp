// fuzz_estimator_outputs.cpp - libFuzzer target for reading the networks'
// outputs (estimator/src/models/network_outputs.cpp): the face detector's scores and
// regressors, an angle-bins head, the mesh's face flag and landmarks, each of
// any size and element type the input chooses (a model file that does not
// match its description) and with any values (NaN, infinities, huge).
// Checks: a wrong size or type is refused with an EstimatorError, never read;
// a right one gives only finite faces with positive boxes and scores in
// [min score, 1], an angle within its bins' range or NaN, a flag in [0, 1].
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "network_outputs.hpp"

namespace {

using hkf_estimator::EstimatorError;

void check(bool condition, const char *what)
{
    if (!condition) {
        std::fprintf(stderr, "fuzz_estimator_outputs: %s\n", what);
        std::abort();
    }
}

// Reads the fuzzer's bytes in order; zeros once they run out.
struct Bytes {
    const uint8_t *data;
    size_t size, at = 0;
    uint8_t byte() { return at < size ? data[at++] : 0; }
    float value()
    {
        switch (byte() % 8) {  // the special values often, else the input's own bits
        case 0: return std::nanf("");
        case 1: return INFINITY;
        case 2: return -INFINITY;
        case 3: return 3e38f;
        default: {
            uint32_t bits = 0;
            for (int i = 0; i < 4; ++i) bits = (bits << 8) | byte();
            float v;
            std::memcpy(&v, &bits, sizeof v);
            return v;
        }
        }
    }
    // A size near `right` (often exactly it), or anything up to 4 * right + 8.
    size_t size_near(size_t right)
    {
        const uint8_t b = byte();
        if (b < 160) return right;
        if (b < 240) return right + (b % 5) - 2 <= 4 * right + 8 ? right + (b % 5) - 2 : right;
        return static_cast<size_t>(byte()) * (4 * right + 8) / 255;
    }
    // An output of n values: float as the networks give, sometimes double (the wrong type).
    cv::Mat output(size_t n)
    {
        const bool as_double = byte() >= 250;
        cv::Mat m(1, static_cast<int>(n), as_double ? CV_64F : CV_32F);
        for (size_t i = 0; i < n; ++i) {
            const float v = value();
            if (as_double) m.at<double>(0, static_cast<int>(i)) = v;
            else m.at<float>(0, static_cast<int>(i)) = v;
        }
        return n == 0 ? cv::Mat() : m;
    }
};

unsigned long decoded, refused;

void print_totals() { std::printf("fuzz_estimator_outputs: %lu outputs read, %lu refused in total\n", decoded, refused); }

void detector(Bytes &in)
{
    static const std::vector<cv::Point2f> anchors = hkf_estimator::ssd_anchors(128, {8, 16, 16, 16}, 2);
    const size_t n_scores = in.size_near(anchors.size()), n_regress = in.size_near(16 * anchors.size());
    const cv::Mat scores = in.output(n_scores), regress = in.output(n_regress);
    const bool right = n_scores == anchors.size() && n_regress == 16 * anchors.size() && scores.depth() == CV_32F &&
                       regress.depth() == CV_32F;
    const float min_score = 0.5f;
    try {
        const auto faces = hkf_estimator::decode_face_detections(scores, regress, anchors, 128,
                                                                 hkf_estimator::Letterbox{640.f, 0.f, 80.f}, min_score);
        check(right, "a detector output of the wrong size or type was read");
        for (const auto &f : faces) {
            check(std::isfinite(f.box.x) && std::isfinite(f.box.y) && f.box.width > 0 && f.box.height > 0 &&
                      std::isfinite(f.box.width) && std::isfinite(f.box.height),
                  "a face without a finite, positive box");
            check(f.score >= min_score && f.score <= 1.f, "a face score outside [min_score, 1]");
            for (const auto &k : f.keypoints) check(std::isfinite(k.x) && std::isfinite(k.y), "a non-finite keypoint");
        }
        ++decoded;
    } catch (const EstimatorError &) {
        check(!right, "a detector output of the right size and type was refused");
        ++refused;
    }
}

void angle_bins(Bytes &in)
{
    hkf_estimator::AngleBins bins;
    bins.output = "yaw";
    bins.bins = 2 + in.byte() % 199;
    bins.step = 0.5f + static_cast<float>(in.byte() % 8);
    bins.offset = -static_cast<float>(in.byte());
    const size_t n = in.size_near(static_cast<size_t>(bins.bins));
    const cv::Mat logits = in.output(n);
    const bool right = n == static_cast<size_t>(bins.bins) && logits.depth() == CV_32F;
    try {
        const float angle = hkf_estimator::decode_angle_bins(logits, bins);
        check(right, "an angle-bins output of the wrong size or type was read");
        const float low = bins.offset, high = bins.offset + bins.step * static_cast<float>(bins.bins - 1);
        check(std::isnan(angle) || (angle >= low - 1e-3f && angle <= high + 1e-3f), "an angle outside its bins");
        bool all_finite = true;
        for (int i = 0; i < bins.bins; ++i) all_finite = all_finite && std::isfinite(logits.at<float>(0, i));
        check(all_finite == !std::isnan(angle), "NaN from finite logits, or a number from non-finite ones");
        ++decoded;
    } catch (const EstimatorError &) {
        check(!right, "an angle-bins output of the right size and type was refused");
        ++refused;
    }
}

void mesh(Bytes &in)
{
    const int landmarks = 6 + in.byte() % 470;
    const size_t n_flag = in.size_near(1), n_points = in.size_near(3 * static_cast<size_t>(landmarks));
    const cv::Mat flag = in.output(n_flag), points = in.output(n_points);
    try {
        const float p = hkf_estimator::decode_face_flag(flag, "flag");
        check(n_flag == 1 && flag.depth() == CV_32F, "a face flag of the wrong size or type was read");
        check(p >= 0.f && p <= 1.f, "a face flag outside [0, 1]");
        ++decoded;
    } catch (const EstimatorError &) {
        check(!(n_flag == 1 && flag.depth() == CV_32F), "a right face flag was refused");
        ++refused;
    }
    try {
        const float *xyz = hkf_estimator::mesh_landmarks(points, landmarks, "landmarks");
        check(n_points == 3 * static_cast<size_t>(landmarks) && points.depth() == CV_32F,
              "landmarks of the wrong size or type were read");
        volatile float last = xyz[3 * landmarks - 1];  // ASan: the whole array is there
        (void)last;
        ++decoded;
    } catch (const EstimatorError &) {
        check(!(n_points == 3 * static_cast<size_t>(landmarks) && points.depth() == CV_32F), "right landmarks refused");
        ++refused;
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static bool registered = std::atexit(print_totals) == 0;
    (void)registered;
    Bytes in{data, size};
    switch (in.byte() % 3) {
    case 0: detector(in); break;
    case 1: angle_bins(in); break;
    default: mesh(in); break;
    }
    return 0;
}

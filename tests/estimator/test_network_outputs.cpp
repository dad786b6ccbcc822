// test_network_outputs.cpp - reading the networks' outputs
// (estimator/src/models/network_outputs.cpp) on outputs whose right answer is known
// by hand: sizes and types refused, anchors laid out as BlazeFace's, a box and
// keypoints decoded into the frame, a score threshold, the bins' expectation,
// the face flag's sigmoid.
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>

#include <cmath>
#include <vector>

#include "network_outputs.hpp"

extern "C" {  // last: cmocka's fail() macro would break the C++ headers
#include <cmocka.h>
}

using hkf_estimator::EstimatorError;

namespace {

cv::Mat floats(const std::vector<float> &v) { return cv::Mat(v, true).reshape(1, 1); }

bool refuses(void (*call)())
{
    try {
        call();
    } catch (const EstimatorError &) {
        return true;
    }
    return false;
}

// BlazeFace short range: 16x16 cells of stride 8 with 2 anchors, then 8x8 of stride 16 with 6 (3 layers x 2).
void test_anchors(void **)
{
    const auto anchors = hkf_estimator::ssd_anchors(128, {8, 16, 16, 16}, 2);
    assert_int_equal(anchors.size(), 896);
    assert_true(std::fabs(anchors[0].x - 0.5f / 16) < 1e-6f && std::fabs(anchors[0].y - 0.5f / 16) < 1e-6f);
    assert_true(anchors[1].x == anchors[0].x);                                   // two per cell
    assert_true(std::fabs(anchors[2].x - 1.5f / 16) < 1e-6f);                    // then the next cell
    assert_true(std::fabs(anchors[512].x - 0.5f / 8) < 1e-6f && anchors[517].x == anchors[512].x);  // 6 per cell
    assert_true(std::fabs(anchors[518].x - 1.5f / 8) < 1e-6f);
    assert_true(std::fabs(anchors.back().x - 7.5f / 8) < 1e-6f && std::fabs(anchors.back().y - 7.5f / 8) < 1e-6f);
    const auto full = hkf_estimator::ssd_anchors(192, {4}, 1);
    assert_int_equal(full.size(), 48 * 48);
}

// One anchor scores; its box and keypoints come out in frame px through the letterbox.
void test_one_detection(void **)
{
    const std::vector<cv::Point2f> anchors = {{0.25f, 0.25f}, {0.5f, 0.5f}, {0.75f, 0.75f}};
    std::vector<float> scores = {-5.f, 2.f, 0.f}, regress(48, 0.f);
    float *r = regress.data() + 16;  // anchor 1: centre moved by (+12.8, -6.4) input px, 32x64 px, keypoints
    r[0] = 12.8f;
    r[1] = -6.4f;
    r[2] = 32.f;
    r[3] = 64.f;
    for (int k = 0; k < 6; ++k) {
        r[4 + 2 * k] = static_cast<float>(k);
        r[5 + 2 * k] = -static_cast<float>(k);
    }
    const hkf_estimator::Letterbox box{640.f, 0.f, 80.f};  // a 640x480 frame letterboxed to 640x640
    const auto faces = hkf_estimator::decode_face_detections(floats(scores), floats(regress), anchors, 128, box, 0.5f);
    assert_int_equal(faces.size(), 1u);  // anchor 0 scores too low; anchor 2 scores 0.5 but has no box (0 wide)
    const auto &f = faces[0];
    assert_true(std::fabs(f.score - 1.f / (1.f + std::exp(-2.f))) < 1e-6f);
    const float cx = (0.5f + 12.8f / 128) * 640, cy = (0.5f - 6.4f / 128) * 640 - 80, w = 32.f / 128 * 640, h = 64.f / 128 * 640;
    assert_true(std::fabs(f.box.x - (cx - w / 2)) < 1e-3f && std::fabs(f.box.y - (cy - h / 2)) < 1e-3f);
    assert_true(std::fabs(f.box.width - w) < 1e-3f && std::fabs(f.box.height - h) < 1e-3f);
    assert_true(std::fabs(f.keypoints[3].x - (0.5f + 3.f / 128) * 640) < 1e-3f);
    assert_true(std::fabs(f.keypoints[3].y - ((0.5f - 3.f / 128) * 640 - 80)) < 1e-3f);
}

// The threshold is inclusive; a candidate with a non-finite value or no size is no face.
void test_threshold_and_bad_values(void **)
{
    const std::vector<cv::Point2f> anchors = {{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}};
    std::vector<float> scores = {0.f, NAN, 3.f}, regress(48, 10.f);
    regress[32 + 1] = NAN;  // anchor 2's centre
    const hkf_estimator::Letterbox box{128.f, 0.f, 0.f};
    auto faces = hkf_estimator::decode_face_detections(floats(scores), floats(regress), anchors, 128, box, 0.5f);
    assert_int_equal(faces.size(), 1u);  // anchor 0 at exactly 0.5; anchor 1 NaN score; anchor 2 NaN box
    assert_true(faces[0].score == 0.5f);
    faces = hkf_estimator::decode_face_detections(floats(scores), floats(regress), anchors, 128, box, 0.51f);
    assert_int_equal(faces.size(), 0u);
    regress.assign(48, 0.f);  // zero-sized boxes
    scores = {5.f, 5.f, 5.f};
    faces = hkf_estimator::decode_face_detections(floats(scores), floats(regress), anchors, 128, box, 0.5f);
    assert_int_equal(faces.size(), 0u);
}

// An output of another size or type than the description implies is refused before it is read.
void test_sizes_refused(void **)
{
    assert_true(refuses([] {
        const std::vector<cv::Point2f> anchors(4);
        hkf_estimator::decode_face_detections(floats(std::vector<float>(3)), floats(std::vector<float>(64)), anchors, 128, {},
                                              0.5f);
    }));
    assert_true(refuses([] {
        const std::vector<cv::Point2f> anchors(4);
        hkf_estimator::decode_face_detections(floats(std::vector<float>(4)), floats(std::vector<float>(63)), anchors, 128, {},
                                              0.5f);
    }));
    assert_true(refuses([] {
        const std::vector<cv::Point2f> anchors(1);
        cv::Mat wide(1, 16, CV_64F, cv::Scalar(0));
        hkf_estimator::decode_face_detections(floats({0.f}), wide, anchors, 128, {}, 0.5f);
    }));
    assert_true(refuses([] {
        hkf_estimator::AngleBins bins{"yaw", 66, 3.f, -99.f};
        hkf_estimator::decode_angle_bins(floats(std::vector<float>(120)), bins);
    }));
    assert_true(refuses([] { hkf_estimator::decode_face_flag(cv::Mat(), "flag"); }));
    assert_true(refuses([] { hkf_estimator::decode_face_flag(floats({1.f, 2.f}), "flag"); }));
    assert_true(refuses([] { hkf_estimator::mesh_landmarks(floats(std::vector<float>(3 * 468 - 1)), 468, "mesh"); }));
    std::vector<float> mesh(3 * 468, 1.f);
    assert_true(hkf_estimator::mesh_landmarks(floats(mesh), 468, "mesh") != nullptr);
}

// The softmax expectation: all mass on one bin gives that bin's angle; two equal bins their middle.
void test_angle_bins(void **)
{
    const hkf_estimator::AngleBins bins{"yaw", 120, 3.f, -180.f};
    std::vector<float> logits(120, -50.f);
    logits[70] = 50.f;
    assert_true(std::fabs(hkf_estimator::decode_angle_bins(floats(logits), bins) - (70 * 3.f - 180.f)) < 1e-3f);
    logits[71] = 50.f;
    assert_true(std::fabs(hkf_estimator::decode_angle_bins(floats(logits), bins) - (70.5f * 3.f - 180.f)) < 1e-3f);
    std::vector<float> flat(120, 7.f);  // uniform: the middle of the range
    assert_true(std::fabs(hkf_estimator::decode_angle_bins(floats(flat), bins) - (59.5f * 3.f - 180.f)) < 1e-3f);
    flat[5] = INFINITY;
    assert_true(std::isnan(hkf_estimator::decode_angle_bins(floats(flat), bins)));
    std::vector<float> huge(120, 3e38f);  // finite but huge: shifted by the peak, still exact
    assert_true(std::fabs(hkf_estimator::decode_angle_bins(floats(huge), bins) - (59.5f * 3.f - 180.f)) < 1e-3f);
}

void test_face_flag(void **)
{
    assert_true(std::fabs(hkf_estimator::decode_face_flag(floats({0.f}), "f") - 0.5f) < 1e-6f);
    assert_true(std::fabs(hkf_estimator::decode_face_flag(floats({2.f}), "f") - 1.f / (1.f + std::exp(-2.f))) < 1e-6f);
    assert_true(hkf_estimator::decode_face_flag(floats({NAN}), "f") == 0.f);
    assert_true(hkf_estimator::decode_face_flag(floats({-1e30f}), "f") >= 0.f);
}

}  // namespace

int main()
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_anchors),       cmocka_unit_test(test_one_detection), cmocka_unit_test(test_threshold_and_bad_values),
        cmocka_unit_test(test_sizes_refused), cmocka_unit_test(test_angle_bins),    cmocka_unit_test(test_face_flag),
    };
    return cmocka_run_group_tests(tests, nullptr, nullptr);
}

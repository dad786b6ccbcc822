// A mirrored face mirrors the pose: on real AFLW2000 faces turned well to one
// side, found by BlazeFace in the image and in its mirror image, the
// estimator's yaw and roll change sign and pitch stays. Models are not exactly
// symmetric, so medians are compared.
// usage: test_flip_symmetry DATA_DIR MODELS_DIR SPEC_DIR MODEL
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "face_detector.hpp"
#include "head_pose_estimator.hpp"
#include "model_spec.hpp"
#include "angle_bins_model.hpp"
#include "face_crop.hpp"

static double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 1e9 : v[v.size() / 2];
}

// One labels.csv row: the image's name and its seven numbers (yaw pitch roll, then the face box x0 y0 x1 y1).
static bool read_row(std::istream &labels, std::string *image, float v[7])
{
    std::string line, cell;
    if (!std::getline(labels, line)) return false;
    std::stringstream fields(line);
    std::getline(fields, *image, ',');
    for (int k = 0; k < 7; ++k) {
        std::getline(fields, cell, ',');
        v[k] = std::stof(cell);
    }
    return true;
}

// The model and BlazeFace: the pose of the largest face found in an image.
struct PoseOfImage {
    std::unique_ptr<hkf_estimator::HeadPoseEstimator> model;
    std::unique_ptr<hkf_estimator::FaceDetector> detector;
    std::optional<hkf_estimator::HeadPose> operator()(const cv::Mat &image) const
    {
        std::optional<hkf_estimator::Face> best;
        for (const hkf_estimator::Face &f : detector->detect(image))
            if (!best || f.box.area() > best->box.area()) best = f;
        return best ? model->estimate(image, *best) : std::nullopt;
    }
};

// The differences a mirror should cancel, per face.
struct FlipSums {
    std::vector<double> yaw_sum, roll_sum, pitch_diff;
    int same_sign = 0, faces = 0;
};

// The face of one row and its mirror image, estimated; false when either has no pose.
static bool measure_face(const PoseOfImage &pose_of, const std::string &data, const std::string &image, const float v[7],
                         FlipSums *sums)
{
    const cv::Mat img = cv::imread(data + "/images/" + image);
    const cv::Rect crop = hkf_estimator::face_crop_rect(cv::Rect2f(v[3], v[4], v[5] - v[3], v[6] - v[4]), 0.5f, img.size());
    if (crop.empty()) return false;
    cv::Mat face = img(crop).clone(), mirrored;
    cv::flip(face, mirrored, 1);
    const std::optional<hkf_estimator::HeadPose> pa = pose_of(face), pb = pose_of(mirrored);
    if (!pa || !pb) return false;  // not found in one of them
    const hkf_estimator::HeadPose a = *pa, b = *pb;
    sums->yaw_sum.push_back(std::fabs(a.yaw + b.yaw));
    sums->roll_sum.push_back(std::fabs(a.roll + b.roll));
    sums->pitch_diff.push_back(std::fabs(a.pitch - b.pitch));
    sums->same_sign += (a.yaw > 0) == (v[0] > 0);  // and the estimate agrees with the label's side
    ++sums->faces;
    std::printf("%s: label yaw %7.2f | yaw %7.2f mirrored %7.2f | roll %7.2f mirrored %7.2f | pitch %7.2f mirrored %7.2f\n",
                image.c_str(), v[0], a.yaw, b.yaw, a.roll, b.roll, a.pitch, b.pitch);
    return true;
}

int main(int argc, char **argv)
{
    using namespace hkf_estimator;
    if (argc != 5) return 2;
    const std::string data = argv[1];
    PoseOfImage pose_of;
    try {
        pose_of.model = make_estimator(load_model_spec(argv[3], argv[4], argv[2]));
        pose_of.detector = std::make_unique<FaceDetector>(argv[2], DetectorRange::Short);
    } catch (const EstimatorError &e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    std::ifstream labels(data + "/labels.csv");
    std::string header, image;
    std::getline(labels, header);
    FlipSums sums;
    float v[7];
    while (sums.faces < 24 && read_row(labels, &image, v)) {
        if (std::fabs(v[0]) < 25.f || std::fabs(v[0]) > 80.f) continue;  // clearly turned faces only
        measure_face(pose_of, data, image, v, &sums);
    }
    const int faces = sums.faces;
    const double my = median(sums.yaw_sum), mr = median(sums.roll_sum), mp = median(sums.pitch_diff);
    std::printf("%d faces: median |yaw + yaw'| %.2f, |roll + roll'| %.2f, |pitch - pitch'| %.2f deg; yaw on the label's side %d/%d\n",
                faces, my, mr, mp, sums.same_sign, faces);
    // 5 deg: the faces are turned 25-80 deg, so a yaw that did not change sign
    // would give |yaw + yaw'| of 50 deg or more
    const int checks[] = {faces >= 20, my < 5.0, mr < 5.0, mp < 5.0, sums.same_sign >= faces - 1};
    int passed = 0;
    for (int c : checks) passed += c;
    std::printf("%d passed, %d failed\n", passed, 5 - passed);
    return passed == 5 ? 0 : 1;
}

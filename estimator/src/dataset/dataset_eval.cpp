// dataset_eval.cpp - see dataset_eval.hpp.
#include "dataset_eval.hpp"

#include <chrono>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "face_crop.hpp"
#include "face_tracker.hpp"
#include "frame_source.hpp"
#include "safe_files.h"

namespace hkf_estimator {
namespace {

struct LabelRow {
    std::string image;
    float yaw, pitch, roll;  // the dataset's convention
    cv::Rect2f box;
};

// AFLW2000-3D's labels (Pose_Para) have pitch > 0 up and yaw > 0 nose to the
// subject's right, as hkf; roll > 0 is the left ear down, the opposite of hkf.
HeadPose label_in_hkf_convention(const LabelRow &r) { return HeadPose{r.pitch, r.yaw, -r.roll}; }

std::vector<LabelRow> read_labels(const std::string &path)
{
    if (!safe_is_regular_file(path.c_str()))  // a named pipe would block the read for ever
        throw EstimatorError("cannot read " + path + ": not a regular file");
    std::ifstream in(path);
    if (!in) throw EstimatorError("cannot read " + path);
    std::string line;
    if (!std::getline(in, line) || line.rfind("image,yaw_deg,pitch_deg,roll_deg,x_min,y_min,x_max,y_max", 0) != 0)
        throw EstimatorError(path + ": the header must be image,yaw_deg,pitch_deg,roll_deg,x_min,y_min,x_max,y_max");
    std::vector<LabelRow> rows;
    for (int number = 2; std::getline(in, line); ++number) {
        if (line.empty()) continue;
        std::istringstream fields(line);
        LabelRow r;
        std::string cell;
        float v[7];
        std::getline(fields, r.image, ',');
        for (float &x : v) {
            if (!std::getline(fields, cell, ',')) throw EstimatorError(path + ":" + std::to_string(number) + ": too few fields");
            try {
                x = std::stof(cell);
            } catch (const std::exception &) {
                throw EstimatorError(path + ":" + std::to_string(number) + ": '" + cell + "' is not a number");
            }
        }
        r.yaw = v[0];
        r.pitch = v[1];
        r.roll = v[2];
        r.box = cv::Rect2f(v[3], v[4], v[5] - v[3], v[6] - v[4]);
        rows.push_back(r);
    }
    return rows;
}

// The face to give the estimator: the labelled box, or for a model that needs
// keypoints the detected face nearest it (searched around the box).
std::optional<Face> labelled_face(const HeadPoseEstimator &model, FaceDetector &detector, const cv::Mat &image,
                                  const cv::Rect2f &box)
{
    if (!model.needs_keypoints()) {
        Face face;
        face.box = box;
        return face;
    }
    const cv::Rect around = face_crop_rect(box, 0.5f, image.size());
    std::optional<Face> best;
    const cv::Point2f centre(box.x + box.width / 2, box.y + box.height / 2);
    float best_distance = std::max(box.width, box.height) / 2;
    for (Face f : detector.detect(image(around))) {
        f.box.x += static_cast<float>(around.x);
        f.box.y += static_cast<float>(around.y);
        for (auto &k : f.keypoints) k += cv::Point2f(static_cast<float>(around.x), static_cast<float>(around.y));
        const cv::Point2f d = cv::Point2f(f.box.x + f.box.width / 2, f.box.y + f.box.height / 2) - centre;
        if (std::hypot(d.x, d.y) < best_distance) {
            best_distance = std::hypot(d.x, d.y);
            best = f;
        }
    }
    return best;
}

// still_face, and `wrong` set when that face is not the labelled one (its centre more than
// half the labelled box's size from the box's).
std::optional<Face> live_face(HeadPoseEstimator &model, TrackerDetectors detectors, const cv::Mat &image, const cv::Rect2f &box,
                              bool &wrong)
{
    std::optional<Face> face = still_face(model, detectors, image);
    wrong = false;
    if (!face) return face;
    const cv::Point2f d = cv::Point2f(face->box.x + face->box.width / 2, face->box.y + face->box.height / 2) -
                          cv::Point2f(box.x + box.width / 2, box.y + box.height / 2);
    if (std::hypot(d.x, d.y) > std::max(box.width, box.height) / 2) {
        wrong = true;
        return std::nullopt;
    }
    return face;
}

}  // namespace

std::optional<Face> still_face(HeadPoseEstimator &model, TrackerDetectors detectors, const cv::Mat &image)
{
    FaceTracker tracker(detectors, TrackerSettings{});
    std::optional<Face> face = tracker.track(image, 0);
    if (face && model.follows_faces()) (void)model.estimate(image, *face);  // the searched frame, then the followed one
    return face ? tracker.track(image, 33333) : face;
}

namespace {

// One model on one image, its face found as the run's crop says; `wrong` as live_face sets it.
std::optional<HeadPose> estimate_image(HeadPoseEstimator &model, const DatasetRun &run, const cv::Mat &image,
                                       const LabelRow &row, bool &wrong)
{
    wrong = false;
    const std::optional<Face> face = run.crop == DatasetCrop::Live ? live_face(model, run.detectors, image, row.box, wrong)
                                                                   : labelled_face(model, *run.detectors.region, image, row.box);
    return face ? model.estimate(image, *face) : std::nullopt;
}

// The run's pose for one image: the first model's, or with a second the pipeline's.
std::optional<HeadPose> run_image(const DatasetRun &run, const cv::Mat &image, const LabelRow &row, bool &wrong)
{
    const std::optional<HeadPose> first = estimate_image(*run.first, run, image, row, wrong);
    if (run.second == nullptr || !run.fusion->wants_second(first)) return first;
    bool second_wrong = false;
    const std::optional<HeadPose> second = estimate_image(*run.second, run, image, row, second_wrong);
    wrong = wrong || second_wrong;
    return run.fusion->fuse(first, second);
}

int yaw_bin(float yaw)
{
    int bin = 0;
    while (bin < EvalResult::kYawBins - 1 && std::fabs(yaw) >= EvalResult::kYawBinEdges[bin + 1]) ++bin;
    return bin;
}

// Adds a found pose's errors against the label (within the protocol) to the sums.
void add_errors(EvalResult &result, double sum[3], int bin, const HeadPose &pose, const LabelRow &row)
{
    const HeadPose truth = label_in_hkf_convention(row);
    const double error[3] = {std::fabs(pose.pitch - truth.pitch), std::fabs(pose.yaw - truth.yaw),
                             std::fabs(pose.roll - truth.roll)};
    for (int a = 0; a < 3; ++a) {
        sum[a] += error[a];
        result.bin_mae[bin][a] += error[a];
    }
    ++result.evaluated;
}

void finish_means(EvalResult &result, const double sum[3])
{
    for (int a = 0; a < 3; ++a) result.mae[a] = result.evaluated > 0 ? sum[a] / static_cast<double>(result.evaluated) : 0.0;
    for (int b = 0; b < EvalResult::kYawBins; ++b) {
        const long found = result.bin_images[b] - result.bin_no_face[b];
        for (int a = 0; a < 3; ++a) result.bin_mae[b][a] = found > 0 ? result.bin_mae[b][a] / static_cast<double>(found) : 0.0;
    }
}

}  // namespace

EvalResult evaluate_dataset(const DatasetRun &run, std::ostream &predictions, const std::function<void(long, long)> &progress)
{
    const std::vector<LabelRow> rows = read_labels(run.dir + "/labels.csv");
    const long total = run.limit > 0 ? std::min<long>(run.limit, static_cast<long>(rows.size())) : static_cast<long>(rows.size());
    EvalResult result;
    double sum[3] = {0, 0, 0};
    predictions << "image,pitch_deg,yaw_deg,roll_deg\n" << std::fixed << std::setprecision(4);
    for (long i = 0; i < total; ++i) {
        const LabelRow &row = rows[static_cast<size_t>(i)];
        ++result.images;
        const std::string path = run.dir + "/images/" + row.image;
        const cv::Mat image = read_image_file(path);  // none for a named pipe, damage, or beyond the size cap

        if (image.empty() || face_crop_rect(row.box, 0.f, image.size()).empty()) {
            ++result.unreadable;
            std::cerr << "hkf-estimator: cannot read " << run.dir << "/images/" << row.image << " or its face box; skipped\n";
            continue;
        }
        const bool in_protocol = std::fabs(row.yaw) <= 99.f && std::fabs(row.pitch) <= 99.f && std::fabs(row.roll) <= 99.f;
        const int bin = yaw_bin(row.yaw);
        if (in_protocol) ++result.bin_images[bin];
        const auto start = std::chrono::steady_clock::now();
        bool wrong = false;
        const std::optional<HeadPose> pose = run_image(run, image, row, wrong);
        result.wrong_face += wrong && !pose;
        result.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!pose) {
            ++result.no_face;
            if (in_protocol) ++result.bin_no_face[bin];
            continue;
        }
        predictions << row.image << ',' << pose->pitch << ',' << pose->yaw << ',' << pose->roll << '\n';
        if (in_protocol) add_errors(result, sum, bin, *pose, row);
        progress(i + 1, total);
    }
    finish_means(result, sum);
    return result;
}

}  // namespace hkf_estimator

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

}  // namespace

EvalResult evaluate_dataset(PoseModel &model, const std::string &dir, long limit, std::ostream &predictions,
                            const std::function<void(long, long)> &progress)
{
    const std::vector<LabelRow> rows = read_labels(dir + "/labels.csv");
    const long total = limit > 0 ? std::min<long>(limit, static_cast<long>(rows.size())) : static_cast<long>(rows.size());
    EvalResult result;
    double sum[3] = {0, 0, 0};
    predictions << "image,pitch_deg,yaw_deg,roll_deg\n" << std::fixed << std::setprecision(4);
    for (long i = 0; i < total; ++i) {
        const LabelRow &row = rows[static_cast<size_t>(i)];
        ++result.images;
        const cv::Mat image = cv::imread(dir + "/images/" + row.image, cv::IMREAD_COLOR);
        const cv::Rect crop = image.empty() ? cv::Rect() : face_crop_rect(row.box, model.spec().crop_margin, image.size());
        if (crop.empty()) {
            ++result.unreadable;
            std::cerr << "hkf-estimator: cannot read " << dir << "/images/" << row.image << " or its face box; skipped\n";
            continue;
        }
        const auto start = std::chrono::steady_clock::now();
        const HeadPose pose = model.estimate(image(crop));
        result.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        predictions << row.image << ',' << pose.pitch << ',' << pose.yaw << ',' << pose.roll << '\n';
        if (std::fabs(row.yaw) <= 99.f && std::fabs(row.pitch) <= 99.f && std::fabs(row.roll) <= 99.f) {
            const HeadPose truth = label_in_hkf_convention(row);
            sum[0] += std::fabs(pose.pitch - truth.pitch);
            sum[1] += std::fabs(pose.yaw - truth.yaw);
            sum[2] += std::fabs(pose.roll - truth.roll);
            ++result.evaluated;
        }
        progress(i + 1, total);
    }
    for (int a = 0; a < 3; ++a) result.mae[a] = result.evaluated > 0 ? sum[a] / static_cast<double>(result.evaluated) : 0.0;
    return result;
}

}  // namespace hkf_estimator

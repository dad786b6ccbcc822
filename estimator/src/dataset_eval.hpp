// dataset_eval.hpp - a head-pose model on a labelled image set laid out like
// ../shared/data/aflw2000: labels.csv (image,yaw_deg,pitch_deg,roll_deg,x_min,
// y_min,x_max,y_max) and images/. Each face is cropped from its label's box
// enlarged by the model's crop margin.
#pragma once

#include <functional>
#include <ostream>
#include <string>

#include "face_detector.hpp"
#include "head_pose_estimator.hpp"

namespace hkf_estimator {

struct EvalResult {
    long images = 0;        // rows handled
    long unreadable = 0;    // images that could not be read (reported, skipped)
    long no_face = 0;       // the estimator (or, for keypoints, the detector) found no face: skipped
    long evaluated = 0;     // rows whose three label angles are within +-99 deg (the standard protocol)
    double mae[3] = {0, 0, 0};  // pitch, yaw, roll, deg
    double seconds = 0;     // time spent in the model
    // The same by labelled |yaw| (issue 8's bins: 0-30, 30-60, 60-99 deg), over
    // the images within +-99 deg: found faces, and MAE per axis of those found.
    static constexpr int kYawBins = 3;
    static constexpr float kYawBinEdges[kYawBins + 1] = {0.f, 30.f, 60.f, 99.f};
    long bin_images[kYawBins] = {0, 0, 0};
    long bin_no_face[kYawBins] = {0, 0, 0};
    double bin_mae[kYawBins][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

// Runs the model over DIR's labels (at most limit rows when limit > 0); a model
// that needs keypoints gets the detector's face nearest the labelled box. Writes
// "image,pitch_deg,yaw_deg,roll_deg" (hkf convention) to predictions, and
// reports progress through progress(done, total). Throws EstimatorError on a
// missing or malformed labels.csv.
EvalResult evaluate_dataset(HeadPoseEstimator &model, FaceDetector &detector, const std::string &dir, long limit, std::ostream &predictions,
                            const std::function<void(long, long)> &progress);

}  // namespace hkf_estimator

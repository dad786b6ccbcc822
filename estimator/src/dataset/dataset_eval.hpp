// dataset_eval.hpp - a head-pose model on a labelled image set laid out like
// ../shared/data/aflw2000: labels.csv (image,yaw_deg,pitch_deg,roll_deg,x_min,
// y_min,x_max,y_max) and images/. By default each image goes through the path
// live video takes (the face tracker on the whole image, then the model), and a
// face found away from the labelled one counts as not found; with
// DatasetCrop::Labels the model gets the labelled box instead (a model that needs
// keypoints: the detected face nearest it), as the paper's benchmark does.
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>

#include "face_detector.hpp"
#include "face_tracker.hpp"
#include "frame_fusion.hpp"
#include "head_pose_estimator.hpp"

namespace hkf_estimator {

// The live path on one image, as a fresh tracker sees a still face: its first frame (the
// whole image searched, the largest face scoring at least the acquire score taken), then
// its second (that face followed in the region around it, as on every frame after; the
// whole image again if the region's detector misses it). A model that follows faces
// (HeadPoseEstimator::follows_faces) has estimated the first; the caller estimates the second.
std::optional<Face> still_face(HeadPoseEstimator &model, TrackerDetectors detectors, const cv::Mat &image);

enum class DatasetCrop {
    Live,    // the live path: FaceTracker on the image as on a still face's first two frames
             // (the whole image searched, then the face followed in its region), then the model
    Labels,  // the labelled face box (or the detected face nearest it, for a model that needs keypoints)
};

struct EvalResult {
    long images = 0;        // rows handled
    long unreadable = 0;    // images that could not be read (reported, skipped)
    long no_face = 0;       // no face found (or, live, only a face other than the labelled one): skipped
    long wrong_face = 0;    // of those: live, the tracker took a face other than the labelled one
    long evaluated = 0;     // rows whose three label angles are within +-99 deg (the standard protocol)
    double mae[3] = {0, 0, 0};  // pitch, yaw, roll, deg
    double seconds = 0;     // time spent in the model
    // The same by labelled |yaw| (bins 0-30, 30-60, 60-99 deg: near frontal, turned, profile), over
    // the images within +-99 deg: found faces, and MAE per axis of those found.
    static constexpr int kYawBins = 3;
    static constexpr float kYawBinEdges[kYawBins + 1] = {0.f, 30.f, 60.f, 99.f};
    long bin_images[kYawBins] = {0, 0, 0};
    long bin_no_face[kYawBins] = {0, 0, 0};
    double bin_mae[kYawBins][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
};

// What a dataset run measures: one model, or the default pipeline (the first model, the second
// where the live pipeline runs it, the two joined as hkf-filter joins one frame: frame_fusion.hpp).
struct DatasetRun {
    HeadPoseEstimator *first = nullptr;
    HeadPoseEstimator *second = nullptr;    // nullptr: the first model alone
    const FrameFusion *fusion = nullptr;    // with a second model: how the two join
    TrackerDetectors detectors;
    DatasetCrop crop = DatasetCrop::Live;
    std::string dir;                        // labels.csv and images/
    long limit = 0;                         // at most this many rows (0: all)
};

// Runs over the run's labels, each face found as its crop says. Writes
// "image,pitch_deg,yaw_deg,roll_deg" (hkf convention) to predictions, and
// reports progress through progress(done, total). Throws EstimatorError on a
// missing or malformed labels.csv.
EvalResult evaluate_dataset(const DatasetRun &run, std::ostream &predictions, const std::function<void(long, long)> &progress);

}  // namespace hkf_estimator

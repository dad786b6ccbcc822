// pose_drawing.hpp - draws a face box, its keypoints and head-pose axes.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "face_detector.hpp"
#include "head_pose.hpp"

namespace hkf_estimator {

// Axes of a head pose (hkf convention) at centre, length px long: the nose
// direction (blue), the head's up (green) and the subject's right ear (red),
// projected orthographically onto the image.
void draw_pose_axes(cv::Mat &image, const HeadPose &pose, cv::Point2f centre, float length, int thickness);

void draw_face(cv::Mat &image, const Face &face);

// A frame's raw and filtered poses: the face box, the raw axes thin and the filtered axes thick
// at the box's centre, and both as numbers at the top left ("no face" without a raw pose).
void draw_annotation(cv::Mat &image, const std::optional<cv::Rect2f> &box, const std::optional<HeadPose> &raw,
                     const std::optional<HeadPose> &filtered);

struct TraceSample {
    double t;  // s
    std::optional<HeadPose> raw, filtered;
};

// A strip chart over the bottom of the image: pitch, yaw and roll over [t0, t1], one row each,
// raw poses as dots and filtered ones as lines, each row scaled to its values (at least 10 deg).
void draw_pose_trace(cv::Mat &image, const std::vector<TraceSample> &samples, double t0, double t1);

}  // namespace hkf_estimator

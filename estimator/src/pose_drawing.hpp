// pose_drawing.hpp - draws a face box, its keypoints and head-pose axes.
#pragma once

#include <opencv2/core.hpp>

#include "face_detector.hpp"
#include "angle_bins_model.hpp"

namespace hkf_estimator {

// Axes of a head pose (hkf convention) at centre, length px long: the nose
// direction (blue), the head's up (green) and the subject's right ear (red),
// projected orthographically onto the image.
void draw_pose_axes(cv::Mat &image, const HeadPose &pose, cv::Point2f centre, float length, int thickness);

void draw_face(cv::Mat &image, const Face &face);

}  // namespace hkf_estimator

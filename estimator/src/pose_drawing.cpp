// pose_drawing.cpp - see pose_drawing.hpp.
#include "pose_drawing.hpp"

#include <opencv2/imgproc.hpp>

#include "head_rotation.hpp"

namespace hkf_estimator {

void draw_pose_axes(cv::Mat &image, const HeadPose &pose, cv::Point2f centre, float length, int thickness)
{
    const cv::Matx33d R = rotation_from_pose(pose);
    const cv::Vec3d nose = R * cv::Vec3d(0, 0, -1), up = R * cv::Vec3d(0, -1, 0), right_ear = R * cv::Vec3d(-1, 0, 0);
    auto tip = [&](const cv::Vec3d &v) { return cv::Point2f(centre.x + length * static_cast<float>(v[0]), centre.y + length * static_cast<float>(v[1])); };
    cv::line(image, centre, tip(right_ear), cv::Scalar(0, 0, 255), thickness, cv::LINE_AA);
    cv::line(image, centre, tip(up), cv::Scalar(0, 200, 0), thickness, cv::LINE_AA);
    cv::arrowedLine(image, centre, tip(nose), cv::Scalar(255, 80, 0), thickness, cv::LINE_AA, 0, 0.2);
}

void draw_face(cv::Mat &image, const Face &face)
{
    cv::rectangle(image, face.box, cv::Scalar(0, 255, 255), 2, cv::LINE_AA);
    for (const auto &k : face.keypoints) cv::circle(image, k, 3, cv::Scalar(0, 255, 255), -1, cv::LINE_AA);
}

}  // namespace hkf_estimator

// head_rotation.cpp - see head_rotation.hpp.
#include "head_rotation.hpp"

#include <cmath>

namespace hkf_estimator {

namespace {
constexpr double kDeg = M_PI / 180.0;
}

cv::Matx33d rotation_from_pose(const HeadPose &pose)
{
    const double p = pose.pitch * kDeg, y = pose.yaw * kDeg, r = pose.roll * kDeg;
    const cv::Matx33d yaw_m(std::cos(y), 0, std::sin(y), 0, 1, 0, -std::sin(y), 0, std::cos(y));
    const cv::Matx33d pitch_m(1, 0, 0, 0, std::cos(p), std::sin(p), 0, -std::sin(p), std::cos(p));
    const cv::Matx33d roll_m(std::cos(r), std::sin(r), 0, -std::sin(r), std::cos(r), 0, 0, 0, 1);
    return yaw_m * pitch_m * roll_m;
}

// For R = Ry Rx Rz as above: R(1,2) = sin pitch; R(1,0) = -cos pitch sin roll,
// R(1,1) = cos pitch cos roll; R(0,2) = sin yaw cos pitch, R(2,2) = cos yaw cos pitch.
HeadPose pose_from_rotation(const cv::Matx33d &R)
{
    HeadPose pose;
    pose.pitch = static_cast<float>(std::asin(std::max(-1.0, std::min(1.0, R(1, 2)))) / kDeg);
    pose.roll = static_cast<float>(std::atan2(-R(1, 0), R(1, 1)) / kDeg);
    pose.yaw = static_cast<float>(std::atan2(R(0, 2), R(2, 2)) / kDeg);
    return pose;
}

}  // namespace hkf_estimator

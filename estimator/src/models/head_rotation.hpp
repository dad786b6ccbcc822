// head_rotation.hpp - the hkf angle convention as a rotation, both ways.
//
// Camera coordinates: x right, y down (in the image), z away from the camera.
// A face looking into the camera has its nose along (0,0,-1), its up along
// (0,-1,0) and the subject's right ear along (-1,0,0). A head pose rotates
// those axes by R = Ry(yaw) Rx(pitch) Rz(roll), each in the head's own terms:
// yaw > 0 turns the nose to the subject's right (image -x), pitch > 0 lifts it
// (image -y), roll > 0 lowers the right ear (image +y).
#pragma once

#include <opencv2/core.hpp>

#include "head_pose.hpp"

namespace hkf_estimator {

cv::Matx33d rotation_from_pose(const HeadPose &pose);
HeadPose pose_from_rotation(const cv::Matx33d &rotation);

}  // namespace hkf_estimator

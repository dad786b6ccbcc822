// pose_drawing.cpp - see pose_drawing.hpp.
#include "pose_drawing.hpp"

#include <cmath>

#include <opencv2/imgproc.hpp>

namespace hkf_estimator {

void draw_pose_axes(cv::Mat &image, const HeadPose &pose, cv::Point2f centre, float length, int thickness)
{
    constexpr double deg = M_PI / 180.0;
    const double p = pose.pitch * deg, y = pose.yaw * deg, r = pose.roll * deg;
    // Head axes in camera coordinates (x right, y down in the image, z away
    // from the camera) for a face looking into the camera: nose (0,0,-1),
    // up (0,-1,0), the subject's right ear (-1,0,0). R = Ry(yaw) Rx(pitch) Rz(roll)
    // in the head's own terms: yaw turns the nose to the subject's right,
    // pitch lifts it, roll lowers the right ear.
    // (checks: yaw > 0 moves the nose to -x, pitch > 0 to -y, roll > 0 the right ear to +y)
    const cv::Matx33d yaw_m(std::cos(y), 0, std::sin(y), 0, 1, 0, -std::sin(y), 0, std::cos(y));
    const cv::Matx33d pitch_m(1, 0, 0, 0, std::cos(p), std::sin(p), 0, -std::sin(p), std::cos(p));
    const cv::Matx33d roll_m(std::cos(r), std::sin(r), 0, -std::sin(r), std::cos(r), 0, 0, 0, 1);
    const cv::Matx33d R = yaw_m * pitch_m * roll_m;
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

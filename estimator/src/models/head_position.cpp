// head_position.cpp - see head_position.hpp.
#include "head_position.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/calib3d.hpp>

namespace hkf_estimator {

double focal_from_fov(const cv::Size &frame, double fov_deg)
{
    const double half_diagonal = 0.5 * std::hypot(static_cast<double>(frame.width), static_cast<double>(frame.height));
    return half_diagonal / std::tan(0.5 * fov_deg * M_PI / 180.0);
}

std::vector<int> rigid_points(const std::vector<cv::Point3f> &canonical)
{
    if (canonical.empty()) return {};
    // the nose tip: the front-most point
    const auto tip = std::max_element(canonical.begin(), canonical.end(),
                                      [](const cv::Point3f &a, const cv::Point3f &b) { return a.z < b.z; });
    std::vector<int> rigid;
    for (size_t i = 0; i < canonical.size(); ++i)
        if (canonical[i].y >= tip->y - 1.5f) rigid.push_back(static_cast<int>(i));
    return rigid;
}

HeadPosition position_from_fit(const cv::Vec3d &rvec, const cv::Vec3d &tvec, float front_z_cm, double pivot_cm)
{
    cv::Matx33d rotation;
    cv::Rodrigues(rvec, rotation);
    const cv::Vec3d pivot = rotation * cv::Vec3d(0.0, 0.0, static_cast<double>(front_z_cm) - pivot_cm) + tvec;
    // OpenCV's camera axes (x right, y down, z forward) -> hkf's (y up)
    return HeadPosition{static_cast<float>(pivot[0]), static_cast<float>(-pivot[1]), static_cast<float>(pivot[2])};
}

std::optional<PositionFit> fit_position(const std::vector<cv::Point3f> &rigid_canonical,
                                        const std::vector<cv::Point2f> &rigid_landmarks, const cv::Size &frame,
                                        const PositionSettings &settings, float front_z_cm)
{
    const double f = focal_from_fov(frame, settings.fov_deg);
    const cv::Matx33d camera(f, 0, frame.width / 2.0, 0, f, frame.height / 2.0, 0, 0, 1);
    cv::Vec3d rvec, tvec;
    if (rigid_canonical.size() < 4 || rigid_canonical.size() != rigid_landmarks.size() ||
        !cv::solvePnP(rigid_canonical, rigid_landmarks, camera, cv::noArray(), rvec, tvec, false, cv::SOLVEPNP_SQPNP))
        return std::nullopt;
    PositionFit fit;
    fit.position = position_from_fit(rvec, tvec, front_z_cm, settings.pivot_cm);
    const HeadPosition &p = fit.position;
    if (!(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) && p.z > 0.f)) return std::nullopt;
    const double front = position_from_fit(rvec, tvec, front_z_cm, 0.0).z;
    if (std::isfinite(front) && front > 0.0) fit.px_per_cm = f / front;
    return fit;
}

HeadPosition position_from_box(const cv::Rect2f &box, const cv::Size &frame, double focal_px, double face_width_cm,
                               const cv::Vec3d &nose_cv, double pivot_cm)
{
    const double z = focal_px * face_width_cm / std::max(1.0, static_cast<double>(box.width));
    const double u = box.x + box.width / 2.0 - frame.width / 2.0, v = box.y + box.height / 2.0 - frame.height / 2.0;
    const cv::Vec3d pivot = cv::Vec3d(u * z / focal_px, v * z / focal_px, z) - pivot_cm * nose_cv;
    return HeadPosition{static_cast<float>(pivot[0]), static_cast<float>(-pivot[1]), static_cast<float>(pivot[2])};
}

}  // namespace hkf_estimator

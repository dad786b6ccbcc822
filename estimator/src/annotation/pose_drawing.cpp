// pose_drawing.cpp - see pose_drawing.hpp.
#include "pose_drawing.hpp"

#include <algorithm>
#include <cstdio>

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

void draw_annotation(cv::Mat &image, const std::optional<cv::Rect2f> &box, const std::optional<HeadPose> &raw,
                     const std::optional<HeadPose> &filtered)
{
    char text[96];
    if (raw) {
        std::snprintf(text, sizeof text, "raw       pitch %+.1f  yaw %+.1f  roll %+.1f", raw->pitch, raw->yaw, raw->roll);
        cv::putText(image, text, {10, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 255, 255), 2);
    } else {
        cv::putText(image, "no face", {10, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 255), 2);
    }
    if (filtered) {
        std::snprintf(text, sizeof text, "filtered  pitch %+.1f  yaw %+.1f  roll %+.1f", filtered->pitch, filtered->yaw,
                      filtered->roll);
        cv::putText(image, text, {10, 50}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 2);
    }
    // the head's position, when measured (cm, camera frame)
    if (raw && raw->has_position) {
        std::snprintf(text, sizeof text, "raw       x %+.1f  y %+.1f  z %.1f cm", raw->position.x, raw->position.y,
                      raw->position.z);
        cv::putText(image, text, {10, 75}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 255, 255), 2);
    }
    if (filtered && filtered->has_position) {
        std::snprintf(text, sizeof text, "filtered  x %+.1f  y %+.1f  z %.1f cm", filtered->position.x,
                      filtered->position.y, filtered->position.z);
        cv::putText(image, text, {10, 100}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 2);
    }
    if (!box || !(box->width > 0.f && box->height > 0.f)) return;
    cv::rectangle(image, *box, cv::Scalar(0, 255, 255), 2, cv::LINE_AA);
    const cv::Point2f centre(box->x + box->width / 2, box->y + box->height / 2);
    if (raw) draw_pose_axes(image, *raw, centre, 0.8f * box->width, 2);
    if (filtered) draw_pose_axes(image, *filtered, centre, 0.8f * box->width, 5);
}

void draw_pose_trace(cv::Mat &image, const std::vector<TraceSample> &samples, double t0, double t1)
{
    if (samples.empty() || !(t1 > t0)) return;
    const int band = std::max(60, image.rows / 4), top = image.rows - band, row_height = band / 3;
    cv::Mat area = image(cv::Rect(0, top, image.cols, band));
    area *= 0.35;  // darken what is behind the chart
    const char *names[3] = {"pitch", "yaw", "roll"};
    const cv::Scalar raw_colour(0, 255, 255), filtered_colour(255, 255, 255);
    auto angle = [](const HeadPose &p, int axis) { return axis == 0 ? p.pitch : axis == 1 ? p.yaw : p.roll; };
    for (int axis = 0; axis < 3; ++axis) {
        float lo = 1e9f, hi = -1e9f;
        for (const auto &s : samples)
            for (const auto *p : {&s.raw, &s.filtered})
                if (*p) {
                    lo = std::min(lo, angle(**p, axis));
                    hi = std::max(hi, angle(**p, axis));
                }
        if (lo > hi) continue;
        const float mid = (lo + hi) / 2, half = std::max(5.f, (hi - lo) / 2 * 1.1f);
        const int y0 = top + axis * row_height;
        auto to_point = [&](double t, float value) {
            return cv::Point(static_cast<int>((t - t0) / (t1 - t0) * (image.cols - 1)),
                             y0 + static_cast<int>((0.5f - (value - mid) / (2 * half)) * static_cast<float>(row_height - 1)));
        };
        char label[48];
        std::snprintf(label, sizeof label, "%s %+.0f..%+.0f", names[axis], mid - half, mid + half);
        cv::putText(image, label, {5, y0 + 14}, cv::FONT_HERSHEY_SIMPLEX, 0.4, cv::Scalar(200, 200, 200), 1);
        for (const auto &s : samples)
            if (s.raw) cv::circle(image, to_point(s.t, angle(*s.raw, axis)), 1, raw_colour, -1);
        std::optional<cv::Point> last;  // then the filtered line over the dots
        for (const auto &s : samples) {
            if (s.filtered) {
                const cv::Point p = to_point(s.t, angle(*s.filtered, axis));
                if (last) cv::line(image, *last, p, filtered_colour, 2, cv::LINE_AA);
                last = p;
            } else {
                last.reset();
            }
        }
    }
}

}  // namespace hkf_estimator

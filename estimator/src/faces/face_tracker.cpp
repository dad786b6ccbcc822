// face_tracker.cpp - see face_tracker.hpp.
#include "face_tracker.hpp"

#include <cmath>

namespace hkf_estimator {

namespace {
cv::Point2f centre(const cv::Rect2f &r) { return {r.x + r.width / 2, r.y + r.height / 2}; }
}

std::optional<Face> FaceTracker::nearest(const std::vector<Face> &faces, float max_distance) const
{
    std::optional<Face> best;
    float best_distance = max_distance;
    for (const Face &f : faces) {
        const cv::Point2f d = centre(f.box) - centre(last_.box);
        const float distance = std::hypot(d.x, d.y);
        if (distance <= best_distance) {
            best_distance = distance;
            best = f;
        }
    }
    return best;
}

// The face in `roi` nearest the last one, within half a face size of it.
std::optional<Face> FaceTracker::search_region(FaceDetector &detector, const cv::Mat &frame, const cv::Rect &roi, float size) const
{
    std::vector<Face> faces = detector.detect(frame(roi));
    for (Face &f : faces) {
        f.box.x += static_cast<float>(roi.x);
        f.box.y += static_cast<float>(roi.y);
        for (auto &k : f.keypoints) k += cv::Point2f(static_cast<float>(roi.x), static_cast<float>(roi.y));
    }
    return nearest(faces, 0.5f * size);
}

std::optional<Face> FaceTracker::track(const cv::Mat &frame, int64_t utime)
{
    const cv::Rect2f whole(0.f, 0.f, static_cast<float>(frame.cols), static_cast<float>(frame.rows));
    const float size = std::max(last_.box.width, last_.box.height);
    std::optional<Face> found;
    if (locked_) {
        // search around the locked face only
        const cv::Point2f c = centre(last_.box);
        const float half = size * settings_.search_scale / 2;
        const cv::Rect2f roi_f = cv::Rect2f(c.x - half, c.y - half, 2 * half, 2 * half) & whole;
        const cv::Rect roi(cv::Point(static_cast<int>(roi_f.x), static_cast<int>(roi_f.y)),
                           cv::Point(static_cast<int>(roi_f.br().x), static_cast<int>(roi_f.br().y)));
        if (roi.width > 8 && roi.height > 8) found = search_region(*detectors_.region, frame, roi, size);
        if (found) found->followed = true;
    }
    if (!found) {
        ++full_frame_searches_;
        std::vector<Face> faces = detectors_.search->detect(frame);
        if (!settings_.region.empty()) {
            std::vector<Face> inside;
            for (const Face &f : faces)
                if (settings_.region.contains(centre(f.box))) inside.push_back(f);
            faces.swap(inside);
        }
        const bool recently_seen = locked_ && static_cast<double>(utime - last_seen_utime_) * 1e-6 < settings_.reacquire_any_after;
        if (recently_seen) {
            found = nearest(faces, size);  // the same face, not another one
        } else {
            for (const Face &f : faces)
                if (f.score >= settings_.acquire_score && (!found || f.box.area() > found->box.area())) found = f;
        }
    }
    if (found) {
        locked_ = true;
        last_ = *found;
        last_seen_utime_ = utime;
    } else if (locked_ && static_cast<double>(utime - last_seen_utime_) * 1e-6 >= settings_.reacquire_any_after) {
        locked_ = false;
    }
    return found;
}

}  // namespace hkf_estimator

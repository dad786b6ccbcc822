// face_tracker.hpp - locks onto one face (the driver) and follows it.
//
// With no track, the whole frame is searched and the largest face (inside the
// optional region) is taken. With a track, only a region around the face is
// searched, and the face there nearest the last one is kept. The tracker
// never hops: a face far from the locked one is ignored, and once the locked
// face is lost only a face near its last place is taken, until
// reacquire_any_after has passed without it.
#pragma once

#include <cstdint>
#include <optional>

#include "face_detector.hpp"

namespace hkf_estimator {

struct TrackerSettings {
    cv::Rect2f region;                  // px; empty: the whole frame
    double reacquire_any_after = 2.0;   // s without the locked face before any face may be taken
    float search_scale = 2.2f;          // the tracked search region, in face sizes
    float acquire_score = 0.75f;        // detection score needed to start a track
};

class FaceTracker {
public:
    FaceTracker(FaceDetector &detector, TrackerSettings settings) : detector_(detector), settings_(settings) {}

    std::optional<Face> track(const cv::Mat &frame, int64_t utime);

    long full_frame_searches() const { return full_frame_searches_; }

private:
    std::optional<Face> nearest(const std::vector<Face> &faces, float max_distance) const;

    FaceDetector &detector_;
    TrackerSettings settings_;
    bool locked_ = false;
    Face last_;
    int64_t last_seen_utime_ = 0;
    long full_frame_searches_ = 0;
};

}  // namespace hkf_estimator

// face_tracker.hpp - locks onto one face (the driver) and follows it.
//
// With no track, the whole frame is searched and the largest face (inside the
// optional region) is taken. With a track, only a region around the face is
// searched (BlazeFace follows a face there to profile: turn_sequence_test.py),
// and the face there nearest the last one is kept. The tracker
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

// The detectors a tracker uses (not owned; one may serve in several places).
struct TrackerDetectors {
    FaceDetector *search;  // the whole frame: at the start and to re-acquire
    FaceDetector *region;  // the region around the tracked face, every frame
};

class FaceTracker {
public:
    FaceTracker(TrackerDetectors detectors, TrackerSettings settings) : detectors_(detectors), settings_(settings) {}
    // one detector everywhere
    FaceTracker(FaceDetector &detector, TrackerSettings settings) : FaceTracker(TrackerDetectors{&detector, &detector}, settings) {}

    std::optional<Face> track(const cv::Mat &frame, int64_t utime);

    long full_frame_searches() const { return full_frame_searches_; }

private:
    std::optional<Face> nearest(const std::vector<Face> &faces, float max_distance) const;
    std::optional<Face> search_region(FaceDetector &detector, const cv::Mat &frame, const cv::Rect &roi, float size) const;

    TrackerDetectors detectors_;
    TrackerSettings settings_;
    bool locked_ = false;
    Face last_;
    int64_t last_seen_utime_ = 0;
    long full_frame_searches_ = 0;
};

}  // namespace hkf_estimator

// pipeline.hpp - the estimator process: frames -> face -> head pose -> LCM.
//
// A capture thread reads frames into a one-frame slot; the processing thread
// always takes the newest frame. From a camera, or a file with --realtime, a
// frame not yet taken when the next arrives is dropped (and counted): no
// queue ever grows. A file without --realtime is read as fast as processing
// goes, every frame. Every frame is published on HEAD_POSE_RAW, valid = false
// when no face was found.
#pragma once

#include <string>

#include "face_tracker.hpp"
#include "head_pose_estimator.hpp"

namespace hkf_estimator {

struct PipelineOptions {
    std::string source;
    double fps_for_images = 30.0;
    bool realtime = false;             // pace files at their frame rate
    std::string lcm_url = "udpm://239.255.76.67:7667?ttl=0";
    std::string channel = "HEAD_POSE_RAW";
    std::string filtered_channel = "HEAD_POSE";  // drawn in --annotate when received
    std::string annotate_path;         // write an annotated video here
    bool show = false;                 // a window, when there is a display
    long max_frames = 0;               // stop after this many (0: all)
    TrackerSettings tracker;
    // A second model (run_pipeline's `second`) measures the frames where the
    // first finds no pose on the tracked face or measures |yaw| >= this (deg;
    // 0: every frame), on its own thread (second_model.hpp).
    float second_from_yaw = 10.f;  // chosen on AFLW2000's even images (docs/programs.md: "Two models on one channel")
    // From a camera or a --realtime file, the first model is not run on a frame where the second's newest
    // answer reads |yaw| >= this (deg; 0: never): the second measures it alone (first_model_set_aside).
    float second_alone_from_yaw = 60.f;
};

// The estimator's exit statuses beyond 0 (ran), 1 (an error) and 2 (bad arguments).
constexpr int kExitSourceEnded = 3;  // a camera or stream stopped delivering frames by itself (unplugged)
constexpr int kExitDamagedFile = 4;  // a video file ended well short of its frame count (the decoder gave up)

// Runs until the source ends (or SIGINT / SIGTERM / SIGHUP); prints a summary.
// second: nullptr, or a second model whose measurements go on the same
// channel with the frame's seq and utime (hkf-filter fuses them).
// Returns the process exit status; throws EstimatorError on set-up errors.
int run_pipeline(HeadPoseEstimator &model, TrackerDetectors detectors, const PipelineOptions &options,
                 HeadPoseEstimator *second = nullptr);

}  // namespace hkf_estimator

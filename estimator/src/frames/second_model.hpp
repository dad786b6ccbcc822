// second_model.hpp - a second head-pose model on its own thread, for large turns:
// the face mesh keeps the frame rate, and WHENet, ~30 ms a frame, measures the
// frames where the mesh is weak - at large turns, or where it finds no face -
// as fast as it can, on the other core. Its measurement carries the frame's
// seq and capture time and its own model id, so hkf-filter fuses it into that
// frame (two models on one channel; see filter_node/filter_node.h).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "face_detector.hpp"
#include "head_pose_estimator.hpp"

namespace hkf_estimator {

// One frame for the second model: the image, the face the tracker found, and
// the frame's identity on the channel.
struct SecondModelJob {
    cv::Mat image;
    Face face;
    int64_t utime = 0, seq = 0;
    int64_t taken_utime = 0;  // wall clock when the frame was taken (for its latency)
    int64_t asked_utime = 0;  // wall clock when it was handed to the worker (submit sets it)
};

// What the second model made of a job (pose nullopt: no face there).
struct SecondModelResult {
    SecondModelJob job;
    std::optional<HeadPose> pose;
    double inference_ms = 0;
    double waited_ms = 0;  // from the hand-over to the worker's start on it (the job before still in hand)
};

class SecondModelWorker {
public:
    // publish is called on the worker's thread for every job done.
    SecondModelWorker(HeadPoseEstimator &model, std::function<void(const SecondModelResult &)> publish);
    ~SecondModelWorker();  // finishes the job in hand, then stops
    SecondModelWorker(const SecondModelWorker &) = delete;
    SecondModelWorker &operator=(const SecondModelWorker &) = delete;

    // Hands over a frame. With drop_old (a camera, --realtime) a frame still
    // waiting is replaced by the newer one and counted as skipped; without,
    // the call waits until the worker has taken the waiting one (every frame
    // asked for is measured, as a file is read).
    void submit(SecondModelJob job, bool drop_old);
    void stop();  // finishes the job in hand and the one waiting, then returns

    // Why the worker stopped by itself ("" while it runs): the model threw.
    std::string error() const;
    long asked() const;
    long skipped() const;
    long done() const;
    std::vector<double> inference_ms() const;

private:
    static constexpr int kNiceness = 10;  // the worker thread's nice value (the frame loop's: 0)
    void run();

    HeadPoseEstimator &model_;
    std::function<void(const SecondModelResult &)> publish_;
    mutable std::mutex mutex_;
    std::condition_variable changed_;
    std::optional<SecondModelJob> waiting_;
    bool stopping_ = false;
    long asked_ = 0, skipped_ = 0;
    std::string error_;
    std::vector<double> inference_ms_;  // one per job done
    std::thread thread_;
};

}  // namespace hkf_estimator

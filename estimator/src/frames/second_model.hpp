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

// The second model's newest answer with a pose: its frame's capture time and the yaw it read.
struct SecondAnswer {
    int64_t utime = 0;
    float yaw = 0.f;
};

// How recent (us before a frame's capture) the second's newest answer must be of for the frame's first
// model to be set aside on it: hkf-filter's prompt time (0.8 of its default coast_time), within which an
// answered frame makes the next ones wait for the second's answers. A fast CPU's answers are a frame or two
// old; a slow one's (WHENet at sse2: 130-150 ms behind) are where leaving the cores to the second helps most.
constexpr int64_t kSetAsideRecentUs = 200000;

// true where a frame captured at frame_utime is left to the second model alone: its newest answer, of a
// frame at most kSetAsideRecentUs before, read |yaw| >= from_yaw (> 0; 0: never). There the first model's
// reading would be set aside by hkf-filter (pair_second_alone_from_yaw), or it has none (beyond its reach);
// not running it leaves the cores to the second, which then keeps up with a 60 fps camera.
bool first_model_set_aside(const std::optional<SecondAnswer> &newest, int64_t frame_utime, float from_yaw);

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
    std::optional<SecondAnswer> newest_answer() const;  // nullopt: none yet, or the newest found no pose

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
    std::optional<SecondAnswer> newest_;
    std::thread thread_;
};

}  // namespace hkf_estimator

// frame_capture.hpp - the capture side of hkf-estimator's run: a thread reads the source's frames (a file
// paced at its frame rate with --realtime) into a one-frame slot, from which the frame loop takes the
// newest; a source that stops delivering frames is reported.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "frame_source.hpp"
#include "pipeline.hpp"

namespace hkf_estimator {

// The one-frame slot between the capture and the processing thread.
class LatestFrame {
public:
    // Puts a frame in. When the slot is full: with drop_old, the old frame is
    // replaced (and counted); without, the call waits until it is taken.
    void put(Frame frame, bool drop_old);
    // The newest frame, waiting up to `timeout`; nullopt when none came in that
    // time, or (ended = true) once the source has ended and the slot is empty.
    std::optional<Frame> take(std::chrono::milliseconds timeout, bool &ended);
    void close();
    long dropped() const;

private:
    mutable std::mutex mutex_;
    std::condition_variable arrived_, taken_;
    Frame frame_;
    bool full_ = false, closed_ = false;
    long dropped_ = 0;
};

// The capture thread: frames from the source into the slot (a file paced at its
// frame rate with --realtime) until it ends, fails, or `stop_requested` is set.
class Capture {
public:
    Capture(FrameSource &source, LatestFrame &slot, const PipelineOptions &options, bool drop_old,
            const std::atomic<bool> &stop_requested);
    // Closes the slot and joins the thread; false when it does not stop within a second (a
    // thread blocked inside a hung camera or stream cannot be interrupted: it is left).
    bool stop();
    ~Capture();
    bool failed() const { return failed_; }
    const std::string &error() const { return error_; }

private:
    void run(FrameSource &source, const PipelineOptions &options, bool drop_old);

    LatestFrame &slot_;
    const std::atomic<bool> &stop_requested_;
    std::atomic<bool> failed_{false}, done_{false};
    std::string error_;
    std::thread thread_;  // last: started once the rest is in place
};

// A source that stops delivering frames (a camera unplugged or hung, a stream
// stalled) is reported after kStallWarning; the loop keeps waiting for it.
class StallWatch {
public:
    static constexpr std::chrono::seconds kStallWarning{2};
    void no_frame(const FrameSource &source);
    void frame();
    long stalls() const { return stalls_; }

private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
    bool stalled_ = false;
    long stalls_ = 0;
};

}  // namespace hkf_estimator

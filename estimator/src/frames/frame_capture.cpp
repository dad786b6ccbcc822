// frame_capture.cpp - see frame_capture.hpp.
#include "frame_capture.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>

namespace hkf_estimator {

void LatestFrame::put(Frame frame, bool drop_old)
{
    std::unique_lock<std::mutex> lock(mutex_);
    if (!drop_old) taken_.wait(lock, [&] { return !full_ || closed_; });
    if (full_) ++dropped_;
    frame_ = std::move(frame);
    full_ = true;
    arrived_.notify_one();
}

std::optional<Frame> LatestFrame::take(std::chrono::milliseconds timeout, bool &ended)
{
    std::unique_lock<std::mutex> lock(mutex_);
    arrived_.wait_for(lock, timeout, [&] { return full_ || closed_; });
    ended = !full_ && closed_;
    if (!full_) return std::nullopt;
    full_ = false;
    taken_.notify_one();
    return std::move(frame_);
}

void LatestFrame::close()
{
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    arrived_.notify_all();
    taken_.notify_all();
}

long LatestFrame::dropped() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return dropped_;
}

Capture::Capture(FrameSource &source, LatestFrame &slot, const PipelineOptions &options, bool drop_old,
                 const std::atomic<bool> &stop_requested)
    : slot_(slot), stop_requested_(stop_requested),
      thread_([this, &source, &options, drop_old] { run(source, options, drop_old); })
{
}

bool Capture::stop()
{
    slot_.close();  // a capture waiting to hand over a frame gives up
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (!done_ && std::chrono::steady_clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    if (!done_) return false;
    thread_.join();
    return true;
}

Capture::~Capture()
{
    if (thread_.joinable()) thread_.detach();  // only a hung one; the process leaves with _Exit
}

void Capture::run(FrameSource &source, const PipelineOptions &options, bool drop_old)
{
    try {
        const int64_t start = wall_utime();
        for (long n = 0; !stop_requested_ && (options.max_frames == 0 || n < options.max_frames); ++n) {
            Frame frame;
            if (!source.read(frame)) break;
            if (options.realtime && !source.live()) {  // pace a file at its frame rate
                const int64_t due = start + static_cast<int64_t>(1e6 * static_cast<double>(frame.index) / source.fps());
                std::this_thread::sleep_for(std::chrono::microseconds(std::max<int64_t>(0, due - wall_utime())));
                frame.utime = wall_utime();
            }
            slot_.put(std::move(frame), drop_old);
        }
    } catch (const std::exception &e) {  // EstimatorError, or OpenCV's own on a broken source
        error_ = e.what();
        failed_ = true;
    }
    slot_.close();
    done_ = true;
}

void StallWatch::no_frame(const FrameSource &source)
{
    const auto now = std::chrono::steady_clock::now();
    if (!stalled_ && now - last_ >= kStallWarning) {
        stalled_ = true;
        ++stalls_;
        std::fprintf(stderr, "hkf-estimator: no frame from %s for %.1f s (camera unplugged or stalled?); waiting\n",
                     source.description().c_str(), std::chrono::duration<double>(now - last_).count());
    }
}

void StallWatch::frame()
{
    const auto now = std::chrono::steady_clock::now();
    if (stalled_) {
        std::fprintf(stderr, "hkf-estimator: frames again after %.1f s\n", std::chrono::duration<double>(now - last_).count());
        stalled_ = false;
    }
    last_ = now;
}

}  // namespace hkf_estimator

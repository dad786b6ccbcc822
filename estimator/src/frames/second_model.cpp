// second_model.cpp - see second_model.hpp.
#include "second_model.hpp"

#include "frame_source.hpp"

#include <chrono>
#include <cmath>

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

namespace hkf_estimator {

SecondModelWorker::SecondModelWorker(HeadPoseEstimator &model, std::function<void(const SecondModelResult &)> publish)
    : model_(model), publish_(std::move(publish)), thread_([this] { run(); })
{
}

SecondModelWorker::~SecondModelWorker() { stop(); }

void SecondModelWorker::submit(SecondModelJob job, bool drop_old)
{
    std::unique_lock<std::mutex> lock(mutex_);
    if (!drop_old) changed_.wait(lock, [&] { return !waiting_ || stopping_; });
    if (stopping_) return;
    if (waiting_) ++skipped_;
    ++asked_;
    job.asked_utime = wall_utime();
    waiting_ = std::move(job);
    changed_.notify_all();
}

void SecondModelWorker::stop()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
        changed_.notify_all();
    }
    if (thread_.joinable()) thread_.join();
}

void SecondModelWorker::run()
{
    // below the frame loop in the scheduler: on a busy machine the first model's
    // frames keep their pace and the second's measurements come later (Linux: per thread)
    setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), kNiceness);
    for (;;) {
        SecondModelJob job;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait(lock, [&] { return waiting_ || stopping_; });
            if (!waiting_) return;  // stopping, nothing left
            job = std::move(*waiting_);
            waiting_.reset();
            changed_.notify_all();  // a submit waiting for the slot may go on
        }
        SecondModelResult result;
        result.waited_ms = static_cast<double>(wall_utime() - job.asked_utime) / 1000.0;
        const auto t0 = std::chrono::steady_clock::now();
        try {
            result.pose = model_.estimate(job.image, job.face);
        } catch (const std::exception &e) {  // e.g. a model file that does not match its description
            std::lock_guard<std::mutex> lock(mutex_);
            error_ = model_.spec().name + ": " + e.what();
            stopping_ = true;
            waiting_.reset();
            changed_.notify_all();
            return;
        }
        result.inference_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        result.job = std::move(job);
        {
            std::lock_guard<std::mutex> lock(mutex_);  // before its publish: an answer out is an answer in hand
            newest_.reset();
            if (result.pose) newest_ = SecondAnswer{result.job.utime, result.pose->yaw};
        }
        publish_(result);
        std::lock_guard<std::mutex> lock(mutex_);
        inference_ms_.push_back(result.inference_ms);
    }
}

std::string SecondModelWorker::error() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return error_;
}

long SecondModelWorker::asked() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return asked_;
}

long SecondModelWorker::skipped() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return skipped_;
}

long SecondModelWorker::done() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return static_cast<long>(inference_ms_.size());
}

std::optional<SecondAnswer> SecondModelWorker::newest_answer() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return newest_;
}

bool first_model_set_aside(const std::optional<SecondAnswer> &newest, int64_t frame_utime, float from_yaw)
{
    return from_yaw > 0.f && newest && frame_utime - newest->utime <= kSetAsideRecentUs &&
           std::fabs(newest->yaw) >= from_yaw;
}

std::vector<double> SecondModelWorker::inference_ms() const
{
    std::lock_guard<std::mutex> lock(mutex_);
    return inference_ms_;
}

}  // namespace hkf_estimator

// camera_pictures.hpp - small camera pictures for the live view (hkf-view): while a view asks for them
// (picture_request_t on HEAD_POSE_PICTURE_REQUEST, twice a second), a frame at the rate it asks is scaled to
// the width it asks, drawn with the face's box, the landmarks the first model used and the head's axes, and
// published as JPEG (camera_picture_t on HEAD_POSE_PICTURE). The scaling, drawing and encoding run on a
// thread of their own, after the frame's measurement is out: the tracker's latency does not carry them.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>
#include <opencv2/core.hpp>

#include "face_detector.hpp"
#include "head_pose.hpp"

namespace hkf_estimator {

struct PictureFrame {
    cv::Mat image;  // the frame, shared (never written)
    std::optional<Face> face;
    std::vector<cv::Point2f> landmarks;  // px in the frame
    std::optional<HeadPose> pose;
    int64_t utime = 0, seq = 0;
};

class CameraPictures {
public:
    // Listens for requests on lcm (handled where the caller handles lcm); publishes on `channel`.
    CameraPictures(lcm::LCM &lcm, std::mutex &lcm_mutex, std::string channel, std::string request_channel);
    ~CameraPictures();
    CameraPictures(const CameraPictures &) = delete;
    CameraPictures &operator=(const CameraPictures &) = delete;

    // True when a view asked within the last 2 s, the next picture is due, and the thread is free.
    bool due();
    // The frame for the next picture (dropped when the thread is busy with the one before).
    void offer(PictureFrame frame);
    long sent() const { return sent_; }

    // A request's message (public for the LCM handler).
    void on_request(const lcm::ReceiveBuffer *rbuf, const std::string &channel);

private:
    void run();
    void send(const PictureFrame &frame, int width);

    lcm::LCM &lcm_;
    std::mutex &lcm_mutex_;
    std::string channel_;
    std::mutex mutex_;  // below
    std::condition_variable wake_;
    std::optional<PictureFrame> pending_;
    bool stopping_ = false;
    int64_t asked_us_ = -1;  // steady clock of the last request (-1: none)
    double fps_ = 0.0;
    int width_ = 320;
    int64_t next_us_ = 0;
    std::atomic<long> sent_{0};
    std::thread thread_;
};

}  // namespace hkf_estimator

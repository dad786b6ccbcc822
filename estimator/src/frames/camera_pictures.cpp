// camera_pictures.cpp - see camera_pictures.hpp.
#include "camera_pictures.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "hkf/camera_picture_t.hpp"
#include "hkf/picture_request_t.hpp"
#include "pose_drawing.hpp"

namespace hkf_estimator {
namespace {

constexpr int64_t kRequestLastsUs = 2000000;  // pictures stop 2 s after the last request
constexpr double kMaxFps = 30.0;
constexpr int kJpegQuality = 75;

int64_t steady_us()
{
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

}  // namespace

CameraPictures::CameraPictures(lcm::LCM &lcm, std::mutex &lcm_mutex, std::string channel, std::string request_channel)
    : lcm_(lcm), lcm_mutex_(lcm_mutex), channel_(std::move(channel))
{
    lcm_.subscribe(request_channel, &CameraPictures::on_request, this);
    thread_ = std::thread([this] { run(); });
}

CameraPictures::~CameraPictures()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stopping_ = true;
    }
    wake_.notify_all();
    thread_.join();
}

void CameraPictures::on_request(const lcm::ReceiveBuffer *rbuf, const std::string &)
{
    hkf::picture_request_t r;
    if (r.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) < 0 || !std::isfinite(r.fps) || r.fps <= 0.f ||
        r.width < 64 || r.width > 1280)
        return;  // not a request this estimator can serve: ignored
    std::lock_guard<std::mutex> lock(mutex_);
    asked_us_ = steady_us();
    fps_ = std::min(static_cast<double>(r.fps), kMaxFps);
    width_ = r.width;
}

bool CameraPictures::due()
{
    const int64_t now_us = steady_us();
    std::lock_guard<std::mutex> lock(mutex_);
    return asked_us_ >= 0 && now_us - asked_us_ <= kRequestLastsUs && now_us >= next_us_ && !pending_;
}

void CameraPictures::offer(PictureFrame frame)
{
    const int64_t now_us = steady_us();
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (pending_) return;
        pending_ = std::move(frame);
        // on the request's cadence (a frame a little late does not slow it), anew after a pause
        const int64_t interval = static_cast<int64_t>(1e6 / fps_);
        next_us_ = now_us - next_us_ > interval ? now_us + interval : next_us_ + interval;
    }
    wake_.notify_one();
}

void CameraPictures::run()
{
    for (;;) {
        PictureFrame frame;
        int width;
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [this] { return stopping_ || pending_.has_value(); });
            if (stopping_) return;
            frame = std::move(*pending_);
            width = width_;
        }
        send(frame, width);
        std::lock_guard<std::mutex> lock(mutex_);
        pending_.reset();
    }
}

// The frame scaled to width, drawn on and published as JPEG (a failure skips the picture: it is only a view).
void CameraPictures::send(const PictureFrame &frame, int width)
{
    if (frame.image.empty()) return;
    const double scale = static_cast<double>(width) / frame.image.cols;
    cv::Mat small;
    cv::resize(frame.image, small, cv::Size(), scale, scale, cv::INTER_AREA);
    if (frame.face) {
        const cv::Rect2f &b = frame.face->box;
        const cv::Rect2f box(b.x * scale, b.y * scale, b.width * scale, b.height * scale);
        cv::rectangle(small, box, cv::Scalar(0, 255, 255), 2, cv::LINE_AA);
        const cv::Rect inside(0, 0, small.cols, small.rows);
        for (const cv::Point2f &p : frame.landmarks) {
            const cv::Point at(p * scale);
            if (inside.contains(at)) small.at<cv::Vec3b>(at) = cv::Vec3b(80, 255, 80);
        }
        if (frame.pose)
            draw_pose_axes(small, *frame.pose, cv::Point2f(box.x + box.width / 2, box.y + box.height / 2),
                           0.8f * box.width, 2);
    }
    hkf::camera_picture_t m;
    if (!cv::imencode(".jpg", small, m.jpeg, {cv::IMWRITE_JPEG_QUALITY, kJpegQuality}) ||
        m.jpeg.size() > static_cast<size_t>(hkf::camera_picture_t::MAX_JPEG_SIZE))
        return;
    m.utime = frame.utime;
    m.seq = frame.seq;
    m.width = static_cast<int16_t>(small.cols);
    m.height = static_cast<int16_t>(small.rows);
    m.jpeg_size = static_cast<int32_t>(m.jpeg.size());
    std::lock_guard<std::mutex> lock(lcm_mutex_);
    if (lcm_.publish(channel_, &m) == 0) ++sent_;
}

}  // namespace hkf_estimator

// frame_source.hpp - frames with capture timestamps from a camera (V4L2 index
// or device), a video file, or a folder of images.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>

namespace hkf_estimator {

struct Frame {
    cv::Mat image;         // BGR
    int64_t utime = 0;     // capture time, us since the Unix epoch
    int64_t index = 0;     // 0, 1, 2, ... in source order
};

int64_t wall_utime();

class FrameSource {
public:
    // "0" or "/dev/video0": a camera; a named pipe or character device: a live
    // stream (e.g. a camera's video piped in); a folder: its images in name
    // order; else a video file. fps paces image folders (and files without a frame rate).
    // Throws EstimatorError when it cannot be opened.
    FrameSource(const std::string &spec, double fps_for_images);

    bool live() const { return live_; }  // a camera or stream: frames arrive in real time
    double fps() const { return fps_; }
    // A video file's frame count from its container (0: unknown), and how many
    // frames have been read: a file that ends well short of its count is damaged.
    int64_t expected_frames() const { return expected_frames_; }
    int64_t frames_read() const { return next_index_; }
    const std::string &description() const { return description_; }

    // The next frame; false at the end of a file or folder. Camera frames are
    // stamped when grabbed; file frames at start + index / fps.
    bool read(Frame &frame);

private:
    cv::VideoCapture capture_;
    std::vector<std::string> images_;
    bool live_ = false;
    double fps_ = 30.0;
    int64_t start_utime_ = 0, next_index_ = 0, expected_frames_ = 0;
    std::string description_;
};

}  // namespace hkf_estimator

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

// The largest frame taken (a documented cap: OpenCV's own allows ~3 GB a frame).
constexpr int64_t kMaxFramePixels = 7680LL * 4320;  // 8K UHD, 33.2 M pixels
constexpr int kMaxFrameSide = 16384;                // px
constexpr long kMaxCameraIndex = 999;

// An image file as a BGR frame, or an empty one when it is no regular file (a named pipe would block),
// cannot be decoded, or is beyond kMaxFramePixels: OpenCV refuses that from the header alone when
// OPENCV_IO_MAX_IMAGE_PIXELS was in the environment as it loaded (main sees to it), else after decoding.
cv::Mat read_image_file(const std::string &path);

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
    // Images of a folder that could not be read (skipped, the run goes on).
    long skipped_images() const { return skipped_images_; }
    const std::string &description() const { return description_; }

    // The next frame; false at the end of a file or folder. Camera frames are
    // stamped when grabbed; file frames at start + index / fps. Throws
    // EstimatorError for a video frame beyond kMaxFramePixels.
    bool read(Frame &frame);

private:
    void check_not_repeating(const cv::Mat &image);  // a file's decoder stuck on one frame: EstimatorError
    cv::VideoCapture capture_;
    std::vector<std::string> images_;
    bool live_ = false;
    double fps_ = 30.0;
    int64_t start_utime_ = 0, next_index_ = 0, expected_frames_ = 0;
    size_t next_image_ = 0;
    long skipped_images_ = 0;
    cv::Mat last_read_;      // a file's last frame that differed from the one before
    int64_t repeats_ = 0;    // frames in a row equal to it
    std::string description_;
};

}  // namespace hkf_estimator

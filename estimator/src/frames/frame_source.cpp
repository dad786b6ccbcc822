// frame_source.cpp - see frame_source.hpp.
#include "frame_source.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "model_spec.hpp"
#include "safe_files.h"

namespace hkf_estimator {

int64_t wall_utime()
{
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch()).count();
}

namespace {

// Within the documented cap (OpenCV itself allows ~1 G pixels, 3 GB a frame).
bool within_frame_cap(int width, int height)
{
    return width <= kMaxFrameSide && height <= kMaxFrameSide && static_cast<int64_t>(width) * height <= kMaxFramePixels;
}

// A video's frames beyond the cap are refused.
void check_frame_size(int width, int height, const std::string &what)
{
    if (!within_frame_cap(width, height))
        throw EstimatorError(what + " has " + std::to_string(width) + "x" + std::to_string(height) +
                             " px frames; hkf-estimator takes at most " + std::to_string(kMaxFramePixels) +
                             " px (8K UHD) and " + std::to_string(kMaxFrameSide) + " px a side");
}

}  // namespace

FrameSource::FrameSource(const std::string &spec, double fps_for_images) : fps_(fps_for_images)
{
    namespace fs = std::filesystem;
    std::error_code error;  // a path that cannot be looked at (a symlink loop, no permission) is not a folder
    const bool index = !spec.empty() && std::all_of(spec.begin(), spec.end(), ::isdigit);
    if (index && (spec.size() > 3 || std::stol(spec) > kMaxCameraIndex))
        throw EstimatorError("no camera " + spec + ": a camera index is 0 to " + std::to_string(kMaxCameraIndex));
    if (index || spec.rfind("/dev/video", 0) == 0) {
        live_ = true;
        const bool opened = index ? capture_.open(std::stoi(spec), cv::CAP_V4L2) : capture_.open(spec, cv::CAP_V4L2);
        if (!opened) throw EstimatorError("cannot open camera " + spec + " (no such V4L2 device here?)");
        const double camera_fps = capture_.get(cv::CAP_PROP_FPS);
        if (camera_fps > 0) fps_ = camera_fps;
        description_ = "camera " + spec;
    } else if (fs::is_directory(spec, error)) {
        for (const auto &entry : fs::directory_iterator(spec, error)) {
            std::string ext = entry.path().extension().string();
            std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
            if (ext == ".jpg" || ext == ".jpeg" || ext == ".png" || ext == ".bmp") images_.push_back(entry.path().string());
        }
        std::sort(images_.begin(), images_.end());
        if (images_.empty()) throw EstimatorError("no images (.jpg .jpeg .png .bmp) in " + spec);
        description_ = "folder " + spec + " (" + std::to_string(images_.size()) + " images)";
    } else if (fs::is_fifo(spec, error) || fs::is_character_file(spec, error)) {  // a stream arriving in real time
        live_ = true;
        if (!capture_.open(spec, cv::CAP_FFMPEG) || !capture_.isOpened())
            throw EstimatorError("cannot read the stream " + spec + " (not a video OpenCV can decode)");
        const double stream_fps = capture_.get(cv::CAP_PROP_FPS);
        if (stream_fps > 0 && stream_fps < 1000) fps_ = stream_fps;
        description_ = "stream " + spec;
    } else {
        if (!fs::exists(spec, error))
            throw EstimatorError("no such file or camera: " + spec + (error ? " (" + error.message() + ")" : ""));
        if (!capture_.open(spec, cv::CAP_FFMPEG) || !capture_.isOpened())
            throw EstimatorError("cannot read video " + spec + " (not a video OpenCV can decode)");
        const double file_fps = capture_.get(cv::CAP_PROP_FPS);
        if (file_fps > 0 && file_fps < 1000) fps_ = file_fps;
        const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
        if (count > 0 && count < 1e9) expected_frames_ = static_cast<int64_t>(count);
        description_ = "video " + spec;
    }
    if (images_.empty())
        check_frame_size(static_cast<int>(capture_.get(cv::CAP_PROP_FRAME_WIDTH)),
                         static_cast<int>(capture_.get(cv::CAP_PROP_FRAME_HEIGHT)), description_);
    start_utime_ = wall_utime();
}

// OpenCV's FFmpeg reader gives the last frame again, and says it read one, when it cannot
// convert a frame (a stream whose frames change size, e.g. concatenated MJPEG): the same
// pose would go out as measured for the rest of the file. A file whose frames repeat bit for
// bit for a second on end is stopped with the reason (no camera does that; a duplicated frame
// of a frame-rate conversion repeats once).
void FrameSource::check_not_repeating(const cv::Mat &image)
{
    const bool same = image.size() == last_read_.size() && image.type() == last_read_.type() && image.isContinuous() &&
                      last_read_.isContinuous() &&
                      std::memcmp(image.data, last_read_.data, image.total() * image.elemSize()) == 0;
    repeats_ = same ? repeats_ + 1 : 0;
    if (!same) image.copyTo(last_read_);
    if (static_cast<double>(repeats_) >= std::max(fps_, 1.0))
        throw EstimatorError(description_ + " repeats its frame " +
                             std::to_string(next_index_ - repeats_) + " bit for bit from then on: its decoder is stuck (frames that change "
                             "size mid-stream, e.g. concatenated MJPEG?)");
}

cv::Mat read_image_file(const std::string &path)
{
    if (!safe_is_regular_file(path.c_str())) return cv::Mat();
    try {
        cv::Mat image = cv::imread(path, cv::IMREAD_COLOR);
        return !image.empty() && within_frame_cap(image.cols, image.rows) ? image : cv::Mat();
    } catch (const cv::Exception &) {  // beyond OPENCV_IO_MAX_IMAGE_PIXELS: refused from its header
        return cv::Mat();
    }
}

bool FrameSource::read(Frame &frame)
{
    if (!images_.empty()) {
        for (;;) {  // an image that cannot be read (damaged, not an image, too large) is skipped and counted
            if (next_image_ >= images_.size()) return false;
            const std::string &path = images_[next_image_++];
            frame.image = read_image_file(path);
            if (!frame.image.empty()) break;
            if (skipped_images_++ < 5)
                std::fprintf(stderr, "hkf-estimator: cannot read the image %s (damaged, not an image, not a regular "
                             "file, or larger than %lld px); skipped\n", path.c_str(), static_cast<long long>(kMaxFramePixels));
        }
    } else {
        if (!capture_.read(frame.image) || frame.image.empty()) return false;
        check_frame_size(frame.image.cols, frame.image.rows, description_);  // a stream may change size
        if (!live_) check_not_repeating(frame.image);
    }
    frame.index = next_index_++;
    frame.utime = live_ ? wall_utime() : start_utime_ + static_cast<int64_t>(std::llround(1e6 * static_cast<double>(frame.index) / fps_));
    return true;
}

}  // namespace hkf_estimator

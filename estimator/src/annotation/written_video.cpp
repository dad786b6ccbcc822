// written_video.cpp - see written_video.hpp.
#include "written_video.hpp"

#include <opencv2/videoio.hpp>

namespace hkf_estimator {

std::string written_video_problem(const std::string &path, long written)
{
    if (written == 0) return "";
    cv::VideoCapture back(path);
    if (!back.isOpened()) return "the video " + path + " cannot be opened: it is cut (a full disk?)";
    const long frames = static_cast<long>(back.get(cv::CAP_PROP_FRAME_COUNT));
    if (frames != written)
        return "the video " + path + " holds " + std::to_string(frames) + " of the " + std::to_string(written) +
               " frames written (a full disk?)";
    return "";
}

}  // namespace hkf_estimator

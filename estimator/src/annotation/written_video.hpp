// written_video.hpp - checks a video this program wrote. cv::VideoWriter reports
// no failed write: a full disk or a file-size limit leaves an mp4 without its
// index, which nothing can play, and the program would still say it succeeded.
#pragma once

#include <string>

namespace hkf_estimator {

// After the writer is released: "" when the video at path opens and holds the `written`
// frames, else what is wrong with it.
std::string written_video_problem(const std::string &path, long written);

}  // namespace hkf_estimator

// opencv_environment.hpp - OpenCV's environment variables, settled before OpenCV reads them. OpenCV 4.6 reads
// a few dozen variables as its libraries load, before main, and aborts the process on a value it cannot
// parse: a size (std::stoull's exception: "abc", "", "-1", 10^20) or a boolean (cv::Exception: "yes", "on").
// A function in the program's .preinit_array, which the loader runs before any library's initializers, reads
// them first, each by OpenCV's own rule for its kind (the list: opencv_environment.cpp, every variable that
// aborted hkf-estimator --version with a bad value, found from the libraries' strings). A bad one is taken
// out of the environment (OpenCV loads with its default) and the program reports it from main. Two are
// hkf's own:
// - OPENCV_IO_MAX_IMAGE_PIXELS must be a whole number of pixels from 1 to kMaxFramePixels; a bad one is
//   replaced by kMaxFramePixels. (Unset, hkf-estimator's main runs itself again with the variable set, so
//   that a larger image is refused from its header, not decoded first: an environment variable cannot be
//   added here for good.)
// - OPENCV_TRACE on would make OpenCV write OpenCVTrace.txt into the current folder, a file nobody checked
//   (it could be an input): refused, the variable taken out.
// This file must be linked into each program that loads OpenCV.
#pragma once

namespace hkf_estimator {

// "" when every variable was unset or good; else why the first bad one was refused (for an exit 2).
const char *opencv_environment_problem();

}  // namespace hkf_estimator

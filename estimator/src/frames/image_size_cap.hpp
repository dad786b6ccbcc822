// image_size_cap.hpp - OPENCV_IO_MAX_IMAGE_PIXELS, settled before OpenCV reads it. OpenCV reads its image
// size cap from the environment as its library loads, before main, and aborts the process on a value it
// cannot parse (std::stoull's exception). A function in the program's .preinit_array, which the loader runs
// before any library's initializers, reads the variable first: set, it must be a whole number of pixels
// from 1 to kMaxFramePixels, else it is replaced by kMaxFramePixels (OpenCV loads safely) and the program
// reports the problem from main. (Unset, hkf-estimator's main runs itself again with the variable set, so
// that a larger image is refused from its header, not decoded first: an environment variable cannot be
// added here for good.) This file must be linked into each program that loads OpenCV's imgcodecs.
#pragma once

namespace hkf_estimator {

// "" when OPENCV_IO_MAX_IMAGE_PIXELS was unset or good; else why it was refused (for an exit 2).
const char *image_size_cap_problem();

}  // namespace hkf_estimator

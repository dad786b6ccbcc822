// face_crop.hpp - the region of a frame around a detected face that a model or a dataset's
// check looks at.
#pragma once

#include <opencv2/core.hpp>

namespace hkf_estimator {

// The crop of a face box enlarged by margin (a fraction of the box's width
// and height on each side), clipped to the image; empty if nothing is left.
cv::Rect face_crop_rect(const cv::Rect2f &box, float margin, const cv::Size &image);

}  // namespace hkf_estimator

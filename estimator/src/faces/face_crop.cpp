// face_crop.cpp - see face_crop.hpp.
#include "face_crop.hpp"

#include <algorithm>
#include <cmath>

namespace hkf_estimator {

cv::Rect face_crop_rect(const cv::Rect2f &box, float margin, const cv::Size &image)
{
    const float dx = box.width * margin, dy = box.height * margin;
    const int x0 = std::max(0, static_cast<int>(std::floor(box.x - dx)));
    const int y0 = std::max(0, static_cast<int>(std::floor(box.y - dy)));
    const int x1 = std::min(image.width, static_cast<int>(std::ceil(box.x + box.width + dx)));
    const int y1 = std::min(image.height, static_cast<int>(std::ceil(box.y + box.height + dy)));
    if (x1 <= x0 || y1 <= y0) return cv::Rect();
    return cv::Rect(x0, y0, x1 - x0, y1 - y0);
}

}  // namespace hkf_estimator

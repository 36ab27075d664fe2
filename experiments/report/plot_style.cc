#include "experiments/report/plot_style.h"

#include <cmath>
#include <cstdio>

namespace cmt::report {

std::string hex_color(const cv::Scalar& bgr) {
  char buf[8];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", static_cast<int>(bgr[2]), static_cast<int>(bgr[1]),
                static_cast<int>(bgr[0]));
  return buf;
}

cv::Scalar darker(const cv::Scalar& bgr, double factor) {
  return cv::Scalar(std::round(bgr[0] * factor), std::round(bgr[1] * factor), std::round(bgr[2] * factor));
}

}  // namespace cmt::report

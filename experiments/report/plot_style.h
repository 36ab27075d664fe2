// Colors, fonts and line widths shared by the report's figures. Colors are BGR, OpenCV's order; the data
// colors are from the Okabe-Ito palette (distinguishable with the common color-vision deficiencies), and pure
// red is reserved for the observed ends outside the prediction, so a red pixel means exactly that.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace cmt::report {

// From 0xRRGGBB as written in palettes.
inline cv::Scalar rgb(unsigned hex) { return cv::Scalar(hex & 0xff, (hex >> 8) & 0xff, (hex >> 16) & 0xff); }
// "#rrggbb" for legends in figures.json.
std::string hex_color(const cv::Scalar& bgr);
// The same hue at `factor` of its brightness (outlines, observed ends drawn on their predicted set).
cv::Scalar darker(const cv::Scalar& bgr, double factor = 0.5);

inline const cv::Scalar kBackground = rgb(0xffffff);
inline const cv::Scalar kInk = rgb(0x000000);           // frame, ticks, text
inline const cv::Scalar kGrid = rgb(0xececec);          // light grid behind the data
inline const cv::Scalar kOutsideRed = rgb(0xff0000);    // observed ends outside the prediction (only use)
inline const cv::Scalar kFaceFill = rgb(0xdcdcdc);      // C-space faces seen from free space
inline const cv::Scalar kFaceOutline = rgb(0x787878);   // their sides (the C-space edges)
inline const cv::Scalar kBackFaceLine = rgb(0xbdbdbd);  // faces seen from the obstacle side: outline only
inline const cv::Scalar kGoalFill = rgb(0xc8ebd2);
inline const cv::Scalar kGoalLine = rgb(0x009e73);  // bluish green
inline const cv::Scalar kStartColor = rgb(0x000000);
inline const cv::Scalar kSensedPositionsLine = rgb(0xd55e00);  // vermillion: a planned motion's P_s
// The last motion's termination set: the one the goal is judged on.
inline const cv::Scalar kLastMotionColor = rgb(0xe69f00);  // orange
// Earlier motions, in order (cycled).
inline const cv::Scalar kMotionColors[] = {rgb(0x56b4e9), rgb(0xcc79a7), rgb(0xf0e442), rgb(0x0072b2)};

// Hershey fonts (ASCII only, so labels spell "alpha/phi" rather than Greek letters).
inline constexpr int kFont = 0;  // cv::FONT_HERSHEY_SIMPLEX
inline constexpr double kTitleScale = 0.62;
inline constexpr double kLabelScale = 0.52;
inline constexpr double kTickScale = 0.42;
inline constexpr double kLegendScale = 0.42;
inline constexpr double kDataLabelScale = 0.38;  // numbers written beside data points

}  // namespace cmt::report

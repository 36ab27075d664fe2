// The legend of a report figure: one row per entry, a marker drawn the way the data is drawn, then the label.
// It sits in its own column right of the plot area, so it never hides data.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace cmt::report {

enum class LegendMarker {
  kFill,      // filled swatch with a darker border (a shaded region or band)
  kLine,      // thick line (an edge or a curve)
  kOutline,   // thin outline box (faces drawn without fill)
  kDot,       // filled dot
  kCross,     // x cross
  kSquare,    // filled square
  kDiamond,   // filled diamond
  kTriangle,  // filled triangle, point up
  kNone,      // no marker: a row of explanation
};

struct LegendEntry {
  std::string label;
  cv::Scalar color;
  LegendMarker marker = LegendMarker::kFill;
};

// A point marker (kDot, kSquare, kDiamond, kTriangle, kCross) of `radius` px around `center`, as the data and
// the legend draw it; other markers draw nothing.
void draw_point_marker(cv::Mat& image, const cv::Point& center, LegendMarker shape, int radius,
                       const cv::Scalar& color);

// Draws the entries top-down inside `box` of `image` (a framed white box fitted to the entries). Labels too
// long for the box are cut with "...".
void draw_legend(cv::Mat& image, const cv::Rect& box, const std::vector<LegendEntry>& entries);

// [{"label", "color": "#rrggbb", "marker"}] for figures.json.
nlohmann::json legend_json(const std::vector<LegendEntry>& entries);

}  // namespace cmt::report

#include "experiments/report/plot_legend.h"

#include <opencv2/imgproc.hpp>

#include "experiments/report/plot_style.h"

namespace cmt::report {
namespace {

constexpr int kRowHeight = 22;     // px per entry
constexpr int kPadding = 8;        // px inside the frame
constexpr int kMarkerWidth = 26;   // px of the marker column
constexpr int kMarkerHeight = 12;  // px of a swatch

const char* marker_name(LegendMarker m) {
  switch (m) {
    case LegendMarker::kFill:
      return "fill";
    case LegendMarker::kLine:
      return "line";
    case LegendMarker::kOutline:
      return "outline";
    case LegendMarker::kDot:
      return "dot";
    case LegendMarker::kCross:
      return "cross";
    case LegendMarker::kSquare:
      return "square";
    case LegendMarker::kDiamond:
      return "diamond";
    case LegendMarker::kTriangle:
      return "triangle";
    case LegendMarker::kNone:
      return "none";
  }
  return "fill";
}

void draw_marker(cv::Mat& image, const cv::Rect& cell, const LegendEntry& e) {
  const cv::Point c(cell.x + cell.width / 2, cell.y + cell.height / 2);
  switch (e.marker) {
    case LegendMarker::kFill:
      cv::rectangle(image, cell, e.color, cv::FILLED);
      cv::rectangle(image, cell, darker(e.color), 1);
      break;
    case LegendMarker::kLine:
      cv::line(image, {cell.x, c.y}, {cell.x + cell.width, c.y}, e.color, 3);
      break;
    case LegendMarker::kOutline:
      cv::rectangle(image, cell, e.color, 1);
      break;
    case LegendMarker::kDot:
      cv::circle(image, c, 4, e.color, cv::FILLED);
      break;
    case LegendMarker::kCross:
      draw_point_marker(image, c, e.marker, 5, e.color);
      break;
    case LegendMarker::kSquare:
    case LegendMarker::kDiamond:
    case LegendMarker::kTriangle:
      draw_point_marker(image, c, e.marker, kMarkerHeight / 2, e.color);
      break;
    case LegendMarker::kNone:
      break;
  }
}

void fill_convex(cv::Mat& image, const std::vector<cv::Point>& corners, const cv::Scalar& color) {
  cv::fillConvexPoly(image, corners, color, cv::LINE_8);
}

}  // namespace

void draw_point_marker(cv::Mat& image, const cv::Point& center, LegendMarker shape, int r,
                       const cv::Scalar& color) {
  const cv::Point& c = center;
  switch (shape) {
    case LegendMarker::kDot:
      cv::circle(image, c, r, color, cv::FILLED, cv::LINE_8);
      break;
    case LegendMarker::kCross:
      cv::line(image, c + cv::Point(-r, -r), c + cv::Point(r, r), color, 2, cv::LINE_8);
      cv::line(image, c + cv::Point(-r, r), c + cv::Point(r, -r), color, 2, cv::LINE_8);
      break;
    case LegendMarker::kSquare:
      cv::rectangle(image, c + cv::Point(-r, -r), c + cv::Point(r, r), color, cv::FILLED, cv::LINE_8);
      break;
    case LegendMarker::kDiamond:
      fill_convex(image,
                  {c + cv::Point(0, -r), c + cv::Point(r, 0), c + cv::Point(0, r), c + cv::Point(-r, 0)},
                  color);
      break;
    case LegendMarker::kTriangle:
      fill_convex(image, {c + cv::Point(0, -r), c + cv::Point(r, r), c + cv::Point(-r, r)}, color);
      break;
    default:
      break;
  }
}

void draw_legend(cv::Mat& image, const cv::Rect& box, const std::vector<LegendEntry>& entries) {
  if (entries.empty()) return;
  const int height = std::min(box.height, 2 * kPadding + kRowHeight * static_cast<int>(entries.size()));
  const cv::Rect frame(box.x, box.y, box.width, height);
  cv::rectangle(image, frame, kBackground, cv::FILLED);
  cv::rectangle(image, frame, kInk, 1);
  const int text_width = box.width - 3 * kPadding - kMarkerWidth;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const int y = box.y + kPadding + kRowHeight * static_cast<int>(i);
    if (y + kRowHeight > frame.y + frame.height) break;
    const cv::Rect cell(box.x + kPadding, y + (kRowHeight - kMarkerHeight) / 2, kMarkerWidth, kMarkerHeight);
    draw_marker(image, cell, entries[i]);
    std::string label = entries[i].label;
    int baseline = 0;
    while (label.size() > 3 && cv::getTextSize(label, kFont, kLegendScale, 1, &baseline).width > text_width)
      label = label.substr(0, label.size() - 4) + "...";
    cv::putText(image, label, {cell.x + kMarkerWidth + kPadding, y + kRowHeight / 2 + 5}, kFont, kLegendScale,
                kInk, 1, cv::LINE_AA);
  }
}

nlohmann::json legend_json(const std::vector<LegendEntry>& entries) {
  nlohmann::json out = nlohmann::json::array();
  for (const LegendEntry& e : entries)
    out.push_back({{"label", e.label}, {"color", hex_color(e.color)}, {"marker", marker_name(e.marker)}});
  return out;
}

}  // namespace cmt::report

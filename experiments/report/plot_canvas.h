// A report figure: a white image with a title, one plot area with framed axes, ticks and labels, and a legend
// column on the right. Data is drawn in data coordinates and clipped to the plot area. The mapping is linear:
//   px = plot.left + (x - x.min) / (x.max - x.min) * (plot.width - 1)
//   py = plot.top + (y.max - y) / (y.max - y.min) * (plot.height - 1)
// and layout() reports it (figures.json), so readers and tests can locate data in the PNG.
// Shapes are drawn without anti-aliasing so that every data pixel has exactly its legend color.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "experiments/report/plot_legend.h"

namespace cmt::report {

// Which point of a text label sits at its anchor: its centre, its left end or its right end (all vertically
// centred).
enum class TextAnchor { kCenter, kLeft, kRight };

struct Range {
  double min = 0, max = 1;
};

using DataPoint = cv::Point2d;  // a point in data coordinates

// Figure size and margins in pixels.
struct FigureSize {
  int width = 1000, height = 720;
  int left = 90, right = 20, top = 56, bottom = 64;  // around the plot area + legend column
  int legend_width = 270;                            // the legend column, between plot area and right margin
};

class PlotCanvas {
 public:
  PlotCanvas(const FigureSize& size, std::string title, std::string x_label, std::string y_label);

  // The data shown. With equal_aspect one range is widened (about its middle) so that a unit has the same
  // length on both axes, as an orthographic view needs. Empty or non-finite ranges become [-1, 1] about
  // their value.
  void set_ranges(Range x, Range y, bool equal_aspect);
  const Range& x_range() const { return x_; }
  const Range& y_range() const { return y_; }

  // Pixel of a data point in the whole image (sub-pixel; draw calls round).
  DataPoint to_image(const DataPoint& p) const;

  // Drawing in data coordinates, clipped to the plot area. Non-finite points are skipped.
  void grid();  // light lines at the ticks, behind the data
  void fill_polygon(const std::vector<DataPoint>& outer, const std::vector<std::vector<DataPoint>>& holes,
                    const cv::Scalar& color);
  void polyline(const std::vector<DataPoint>& points, bool closed, const cv::Scalar& color, int thickness);
  void dashed_line(const DataPoint& a, const DataPoint& b, const cv::Scalar& color, int thickness,
                   int dash_px = 8);
  void dot(const DataPoint& p, int radius_px, const cv::Scalar& color);
  void cross(const DataPoint& p, int half_px, const cv::Scalar& color, int thickness);
  // A circle of data radius r (equal-aspect plots only), filled when fill is true.
  void circle(const DataPoint& center, double r, const cv::Scalar& color, bool fill, int thickness = 1);
  // A circle outline of radius_px pixels around p (a marker that keeps its size at any scale).
  void ring(const DataPoint& p, int radius_px, const cv::Scalar& color, int thickness);
  void rectangle(const DataPoint& a, const DataPoint& b, const cv::Scalar& color);  // filled
  // A point marker as the legend draws it (plot_legend.h draw_point_marker), radius_px around p.
  void marker(const DataPoint& p, LegendMarker shape, int radius_px, const cv::Scalar& color);
  // A small text label (plot_style.h kDataLabelScale) anchored offset_px away from p.
  void text(const DataPoint& p, const std::string& label, const cv::Point& offset_px, TextAnchor anchor,
            const cv::Scalar& color);

  void add_legend(LegendEntry entry) { legend_.push_back(std::move(entry)); }

  // Draws frame, ticks, tick labels, axis labels, title and legend (after the data, so the frame is on top).
  void finish();
  const cv::Mat& image() const { return image_; }
  // Writes the PNG; throws std::runtime_error naming the file when it cannot.
  void save(const std::filesystem::path& file) const;
  // {"width", "height", "title", "plot": {left, top, width, height}, "x": {label, min, max},
  //  "y": {label, min, max}, "legend": [...]}
  nlohmann::json layout() const;

 private:
  cv::Point pixel(const DataPoint& p) const;  // in plot-area coordinates, rounded and clamped to int range
  void draw_axes();

  FigureSize size_;
  std::string title_, x_label_, y_label_;
  cv::Mat image_;
  cv::Rect plot_;  // the plot area in the image
  cv::Mat area_;   // image_(plot_): drawing here clips to the plot area
  Range x_, y_;
  std::vector<LegendEntry> legend_;
};

}  // namespace cmt::report

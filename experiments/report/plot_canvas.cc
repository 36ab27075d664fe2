#include "experiments/report/plot_canvas.h"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "experiments/report/plot_style.h"
#include "experiments/report/plot_ticks.h"

namespace cmt::report {
namespace {

// Far outside any plot area but safely inside int: OpenCV clips what lies beyond the image.
constexpr double kPixelClamp = 1e6;
constexpr int kTickLength = 5;  // px
constexpr int kLegendGap = 14;  // px between the plot area and the legend box
constexpr int kXTicks = 7;      // about this many ticks per axis
constexpr int kYTicks = 6;

bool finite(const DataPoint& p) { return std::isfinite(p.x) && std::isfinite(p.y); }

Range sane(Range r) {
  if (!std::isfinite(r.min) || !std::isfinite(r.max)) return {-1, 1};
  if (r.max < r.min) std::swap(r.min, r.max);
  if (r.max - r.min <= 1e-12 * std::max(1.0, std::abs(r.max))) return {r.min - 1, r.max + 1};
  return r;
}

Range widen(const Range& r, double span) {
  const double mid = 0.5 * (r.min + r.max);
  return {mid - 0.5 * span, mid + 0.5 * span};
}

}  // namespace

PlotCanvas::PlotCanvas(const FigureSize& size, std::string title, std::string x_label, std::string y_label)
    : size_(size), title_(std::move(title)), x_label_(std::move(x_label)), y_label_(std::move(y_label)) {
  image_ = cv::Mat(size.height, size.width, CV_8UC3, kBackground);
  plot_ = cv::Rect(size.left, size.top, size.width - size.left - size.right - size.legend_width,
                   size.height - size.top - size.bottom);
  area_ = image_(plot_);
}

void PlotCanvas::set_ranges(Range x, Range y, bool equal_aspect) {
  x_ = sane(x);
  y_ = sane(y);
  if (!equal_aspect) return;
  // Units per pixel on each axis; the coarser one wins and the other range grows to match.
  const double ux = (x_.max - x_.min) / (plot_.width - 1);
  const double uy = (y_.max - y_.min) / (plot_.height - 1);
  if (ux > uy)
    y_ = widen(y_, ux * (plot_.height - 1));
  else
    x_ = widen(x_, uy * (plot_.width - 1));
}

DataPoint PlotCanvas::to_image(const DataPoint& p) const {
  return {plot_.x + (p.x - x_.min) / (x_.max - x_.min) * (plot_.width - 1),
          plot_.y + (y_.max - p.y) / (y_.max - y_.min) * (plot_.height - 1)};
}

cv::Point PlotCanvas::pixel(const DataPoint& p) const {
  const DataPoint q = to_image(p) - DataPoint(plot_.x, plot_.y);
  return {static_cast<int>(std::lround(std::clamp(q.x, -kPixelClamp, kPixelClamp))),
          static_cast<int>(std::lround(std::clamp(q.y, -kPixelClamp, kPixelClamp)))};
}

void PlotCanvas::grid() {
  for (double t : nice_ticks(x_.min, x_.max, kXTicks))
    cv::line(area_, pixel({t, y_.min}), pixel({t, y_.max}), kGrid, 1);
  for (double t : nice_ticks(y_.min, y_.max, kYTicks))
    cv::line(area_, pixel({x_.min, t}), pixel({x_.max, t}), kGrid, 1);
}

void PlotCanvas::fill_polygon(const std::vector<DataPoint>& outer,
                              const std::vector<std::vector<DataPoint>>& holes, const cv::Scalar& color) {
  auto to_pixels = [&](const std::vector<DataPoint>& pts) {
    std::vector<cv::Point> out;
    for (const DataPoint& p : pts)
      if (finite(p)) out.push_back(pixel(p));
    return out;
  };
  const std::vector<cv::Point> ring = to_pixels(outer);
  if (ring.size() < 3) return;
  if (holes.empty()) {
    cv::fillPoly(area_, std::vector<std::vector<cv::Point>>{ring}, color, cv::LINE_8);
    return;
  }
  // Holes: fill the outer ring into a mask, clear the holes, then paint through the mask.
  cv::Mat mask(area_.size(), CV_8UC1, cv::Scalar(0));
  cv::fillPoly(mask, std::vector<std::vector<cv::Point>>{ring}, cv::Scalar(255), cv::LINE_8);
  std::vector<std::vector<cv::Point>> hole_rings;
  for (const auto& h : holes)
    if (auto r = to_pixels(h); r.size() >= 3) hole_rings.push_back(std::move(r));
  if (!hole_rings.empty()) cv::fillPoly(mask, hole_rings, cv::Scalar(0), cv::LINE_8);
  area_.setTo(color, mask);
}

void PlotCanvas::polyline(const std::vector<DataPoint>& points, bool closed, const cv::Scalar& color,
                          int thickness) {
  std::vector<cv::Point> px;
  for (const DataPoint& p : points)
    if (finite(p)) px.push_back(pixel(p));
  if (px.empty()) return;
  if (px.size() == 1) {
    cv::circle(area_, px[0], std::max(1, thickness / 2), color, cv::FILLED, cv::LINE_8);
    return;
  }
  cv::polylines(area_, std::vector<std::vector<cv::Point>>{px}, closed, color, thickness, cv::LINE_8);
}

void PlotCanvas::dashed_line(const DataPoint& a, const DataPoint& b, const cv::Scalar& color, int thickness,
                             int dash_px) {
  if (!finite(a) || !finite(b)) return;
  const cv::Point pa = pixel(a), pb = pixel(b);
  const double length = cv::norm(pb - pa);
  const int dashes = std::max(1, static_cast<int>(length / (2 * dash_px)));
  for (int i = 0; i < dashes; ++i) {
    const double t0 = static_cast<double>(2 * i) / (2 * dashes),
                 t1 = static_cast<double>(2 * i + 1) / (2 * dashes);
    const cv::Point p0(static_cast<int>(pa.x + t0 * (pb.x - pa.x)),
                       static_cast<int>(pa.y + t0 * (pb.y - pa.y)));
    const cv::Point p1(static_cast<int>(pa.x + t1 * (pb.x - pa.x)),
                       static_cast<int>(pa.y + t1 * (pb.y - pa.y)));
    cv::line(area_, p0, p1, color, thickness, cv::LINE_8);
  }
}

void PlotCanvas::dot(const DataPoint& p, int radius_px, const cv::Scalar& color) {
  if (finite(p)) cv::circle(area_, pixel(p), radius_px, color, cv::FILLED, cv::LINE_8);
}

void PlotCanvas::cross(const DataPoint& p, int half_px, const cv::Scalar& color, int thickness) {
  if (!finite(p)) return;
  const cv::Point c = pixel(p);
  cv::line(area_, c + cv::Point(-half_px, -half_px), c + cv::Point(half_px, half_px), color, thickness,
           cv::LINE_8);
  cv::line(area_, c + cv::Point(-half_px, half_px), c + cv::Point(half_px, -half_px), color, thickness,
           cv::LINE_8);
}

void PlotCanvas::circle(const DataPoint& center, double r, const cv::Scalar& color, bool fill,
                        int thickness) {
  if (!finite(center) || !std::isfinite(r) || r < 0) return;
  const double px_per_unit = (plot_.width - 1) / (x_.max - x_.min);
  const int radius = static_cast<int>(std::lround(std::min(r * px_per_unit, kPixelClamp)));
  cv::circle(area_, pixel(center), std::max(1, radius), color, fill ? cv::FILLED : thickness, cv::LINE_8);
}

void PlotCanvas::ring(const DataPoint& p, int radius_px, const cv::Scalar& color, int thickness) {
  if (finite(p)) cv::circle(area_, pixel(p), std::max(1, radius_px), color, thickness, cv::LINE_8);
}

void PlotCanvas::rectangle(const DataPoint& a, const DataPoint& b, const cv::Scalar& color) {
  if (finite(a) && finite(b)) cv::rectangle(area_, pixel(a), pixel(b), color, cv::FILLED, cv::LINE_8);
}

void PlotCanvas::marker(const DataPoint& p, LegendMarker shape, int radius_px, const cv::Scalar& color) {
  if (finite(p)) draw_point_marker(area_, pixel(p), shape, radius_px, color);
}

void PlotCanvas::text(const DataPoint& p, const std::string& label, const cv::Point& offset_px,
                      TextAnchor anchor, const cv::Scalar& color) {
  if (!finite(p)) return;
  int baseline = 0;
  const cv::Size s = cv::getTextSize(label, kFont, kDataLabelScale, 1, &baseline);
  const cv::Point at = pixel(p) + offset_px;
  const int left = anchor == TextAnchor::kLeft    ? at.x
                   : anchor == TextAnchor::kRight ? at.x - s.width
                                                  : at.x - s.width / 2;
  cv::putText(area_, label, {left, at.y + s.height / 2}, kFont, kDataLabelScale, color, 1, cv::LINE_AA);
}

void PlotCanvas::draw_axes() {
  cv::rectangle(image_, plot_, kInk, 1);
  int baseline = 0;
  const double xs = nice_step(x_.min, x_.max, kXTicks), ys = nice_step(y_.min, y_.max, kYTicks);
  for (double t : nice_ticks(x_.min, x_.max, kXTicks)) {
    const int px = static_cast<int>(std::lround(to_image({t, y_.min}).x));
    const int bottom = plot_.y + plot_.height - 1;
    cv::line(image_, {px, bottom}, {px, bottom + kTickLength}, kInk, 1);
    const std::string label = tick_label(t, xs);
    const cv::Size s = cv::getTextSize(label, kFont, kTickScale, 1, &baseline);
    cv::putText(image_, label, {px - s.width / 2, bottom + kTickLength + 4 + s.height}, kFont, kTickScale,
                kInk, 1, cv::LINE_AA);
  }
  for (double t : nice_ticks(y_.min, y_.max, kYTicks)) {
    const int py = static_cast<int>(std::lround(to_image({x_.min, t}).y));
    cv::line(image_, {plot_.x - kTickLength, py}, {plot_.x, py}, kInk, 1);
    const std::string label = tick_label(t, ys);
    const cv::Size s = cv::getTextSize(label, kFont, kTickScale, 1, &baseline);
    cv::putText(image_, label, {plot_.x - kTickLength - 4 - s.width, py + s.height / 2}, kFont, kTickScale,
                kInk, 1, cv::LINE_AA);
  }
  // x label centred under the tick labels.
  const cv::Size xl = cv::getTextSize(x_label_, kFont, kLabelScale, 1, &baseline);
  cv::putText(image_, x_label_, {plot_.x + (plot_.width - xl.width) / 2, size_.height - 16}, kFont,
              kLabelScale, kInk, 1, cv::LINE_AA);
  // y label: drawn horizontally into a strip, turned a quarter left, pasted left of the tick labels.
  const cv::Size yl = cv::getTextSize(y_label_, kFont, kLabelScale, 1, &baseline);
  cv::Mat strip(yl.height + baseline + 4, yl.width + 4, CV_8UC3, kBackground);
  cv::putText(strip, y_label_, {2, yl.height + 2}, kFont, kLabelScale, kInk, 1, cv::LINE_AA);
  cv::Mat turned;
  cv::rotate(strip, turned, cv::ROTATE_90_COUNTERCLOCKWISE);
  const int top = std::max(0, plot_.y + (plot_.height - turned.rows) / 2);
  const cv::Rect target(6, top, turned.cols, std::min(turned.rows, size_.height - top));
  turned(cv::Rect(0, 0, target.width, target.height)).copyTo(image_(target));
  // Title centred over the plot area.
  const cv::Size ts = cv::getTextSize(title_, kFont, kTitleScale, 1, &baseline);
  cv::putText(image_, title_,
              {std::max(4, plot_.x + (plot_.width - ts.width) / 2), size_.top / 2 + ts.height / 2}, kFont,
              kTitleScale, kInk, 1, cv::LINE_AA);
}

void PlotCanvas::finish() {
  draw_axes();
  const cv::Rect legend_box(plot_.x + plot_.width + kLegendGap, plot_.y, size_.legend_width - kLegendGap,
                            plot_.height);
  draw_legend(image_, legend_box, legend_);
}

// PNG through libpng's simplified API rather than OpenCV's imgcodecs: imgcodecs loads about 120 shared
// libraries (GDAL, GDCM, Poppler, ...) into every process that links it, 0.3 s of start-up for each cmt run.
void PlotCanvas::save(const std::filesystem::path& file) const {
  const cv::Mat bgr = image_.isContinuous() ? image_ : image_.clone();
  png_image png{};
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(bgr.cols);
  png.height = static_cast<png_uint_32>(bgr.rows);
  png.format = PNG_FORMAT_BGR;
  const bool ok = png_image_write_to_file(&png, file.string().c_str(), 0, bgr.data,
                                          static_cast<png_int_32>(bgr.step[0]), nullptr) != 0;
  const std::string reason = png.message;
  png_image_free(&png);
  if (!ok) throw std::runtime_error(file.string() + ": cannot write the figure: " + reason);
}

nlohmann::json PlotCanvas::layout() const {
  return {{"width", size_.width},
          {"height", size_.height},
          {"title", title_},
          {"plot", {{"left", plot_.x}, {"top", plot_.y}, {"width", plot_.width}, {"height", plot_.height}}},
          {"x", {{"label", x_label_}, {"min", x_.min}, {"max", x_.max}}},
          {"y", {{"label", y_label_}, {"min", y_.min}, {"max", y_.max}}},
          {"legend", legend_json(legend_)}};
}

}  // namespace cmt::report

#include "experiments/report/extremes_figure.h"

#include <algorithm>
#include <vector>

#include "experiments/report/plot_style.h"

namespace cmt::report {
namespace {

using nlohmann::json;

// One color and marker per motion, cycling (Okabe-Ito).
const cv::Scalar kCurveColors[] = {rgb(0x0072b2), rgb(0xd55e00), rgb(0x009e73), rgb(0xcc79a7), rgb(0xe69f00)};
const LegendMarker kCurveMarkers[] = {LegendMarker::kDot, LegendMarker::kSquare, LegendMarker::kDiamond,
                                      LegendMarker::kTriangle, LegendMarker::kCross};
constexpr int kCurveStyles = 5;
constexpr int kMarkerRadiusPx = 5;

double number_or(const json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

// (distance outside in eps_p, success rate) for the trials with rollouts.
std::vector<DataPoint> motion_curve(const json& motion) {
  std::vector<DataPoint> points;
  const json& vertices = motion.value("vertices", json());
  if (number_or(vertices, "rollouts", 0) > 0) points.push_back({0, number_or(vertices, "rate", 0)});
  for (const json& g : motion.value("grown", json::array()))
    if (number_or(g, "rollouts", 0) > 0)
      points.push_back({number_or(g, "factor", 0), number_or(g, "rate", 0)});
  std::sort(points.begin(), points.end(), [](const DataPoint& a, const DataPoint& b) { return a.x < b.x; });
  return points;
}

}  // namespace

std::optional<PlotCanvas> draw_extremes_figure(const json& run, const std::string& title,
                                               const FigureSize& size) {
  if (!run.is_object() || !run.contains("extremes") || !run["extremes"].is_object()) return std::nullopt;
  const json& motions = run["extremes"].value("motions", json::array());
  std::vector<std::vector<DataPoint>> curves;
  std::vector<std::string> names;
  double x_max = 1;
  for (const json& m : motions) {
    curves.push_back(motion_curve(m));
    names.push_back(m.value("motion", std::string("?")) +
                    (m.value("claims_cell", false) ? " (cell)" : " (a point)"));
    for (const DataPoint& p : curves.back()) x_max = std::max(x_max, p.x);
  }
  if (std::all_of(curves.begin(), curves.end(), [](const auto& c) { return c.empty(); })) return std::nullopt;
  PlotCanvas canvas(
      size, title,
      "commanded at least this far outside the motion's cpositions (eps_p; 0: at their vertices)",
      "fraction of rollouts that reached the goal");
  canvas.set_ranges({-0.05 * x_max, 1.05 * x_max}, {0, 1.05}, false);
  canvas.grid();
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const cv::Scalar& color = kCurveColors[i % kCurveStyles];
    const LegendMarker marker = kCurveMarkers[i % kCurveStyles];
    if (curves[i].size() > 1) canvas.polyline(curves[i], false, color, 2);
    for (const DataPoint& p : curves[i]) canvas.marker(p, marker, kMarkerRadiusPx, color);
    canvas.add_legend({names[i], color, marker});
  }
  canvas.add_legend(
      {"the planner claims every point at 0: all must reach the goal", kInk, LegendMarker::kNone});
  canvas.finish();
  return canvas;
}

}  // namespace cmt::report

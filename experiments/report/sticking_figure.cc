#include "experiments/report/sticking_figure.h"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <vector>

#include "experiments/report/plot_style.h"

namespace cmt::report {
namespace {

constexpr const char* kKinds[] = {"face", "edge", "vertex"};
constexpr const char* kKindPlurals[] = {"faces", "edges", "vertices"};
const cv::Scalar kKindColors[] = {rgb(0x0072b2), rgb(0xe69f00), rgb(0xcc79a7)};
constexpr const char* kClasses[] = {"must", "may", "never"};
const cv::Scalar kClassBands[] = {rgb(0xd9ecd0), rgb(0xfdf0c2), rgb(0xe3e0f0)};
constexpr int kCurveThickness = 2;
constexpr int kBinDotRadius = 4;
constexpr double kYMargin = 0.05;  // stick fractions are in [0, 1]; a little air above and below

struct Bin {
  std::array<int, 3> trials{}, stuck{};  // per kind
  std::array<bool, 3> classes{};         // which classes occur
};

int index_of(const std::string& s, const char* const* names, int count) {
  for (int i = 0; i < count; ++i)
    if (s == names[i]) return i;
  return -1;
}

}  // namespace

std::optional<PlotCanvas> draw_sticking_figure(const nlohmann::json& sticking, const std::string& title,
                                               const FigureSize& size) {
  if (!sticking.is_object() || !sticking.contains("records")) return std::nullopt;
  const nlohmann::json& records = sticking["records"];
  if (!records.is_array()) throw std::invalid_argument("records: expected a list");
  std::map<int, Bin> bins;  // bin index -> counts
  for (std::size_t i = 0; i < records.size(); ++i) {
    const nlohmann::json& r = records[i];
    if (!r.is_object()) throw std::invalid_argument("records[" + std::to_string(i) + "]: expected an object");
    const auto number = [&](const char* key) {
      return r.contains(key) && r[key].is_number() ? r[key].get<double>() : std::nan("");
    };
    const double alpha = number("command_angle"), phi = number("phi");
    const int kind = index_of(r.value("kind", ""), kKinds, 3);
    const int cls = index_of(r.value("class", ""), kClasses, 3);
    // A record without a finite angle ratio or of an unknown kind has no place on the plot.
    if (!std::isfinite(alpha) || !std::isfinite(phi) || phi <= 0 || kind < 0) continue;
    Bin& b = bins[static_cast<int>(std::floor(alpha / phi / kStickBinWidth))];
    ++b.trials[kind];
    if (r.value("stuck", false)) ++b.stuck[kind];
    if (cls >= 0) b.classes[cls] = true;
  }
  if (bins.empty()) return std::nullopt;

  PlotCanvas canvas(size, title + ": stick fraction vs command angle",
                    "alpha/phi (command angle / friction angle, 1)", "stick fraction (stuck / trials, 1)");
  const double x_lo = std::min(0.0, bins.begin()->first * kStickBinWidth);
  const double x_hi = (bins.rbegin()->first + 2) * kStickBinWidth;  // a bin of air right of the last one
  canvas.set_ranges({x_lo, x_hi}, {-kYMargin, 1 + kYMargin}, false);
  // Bands: each bin's height [0, 1] split evenly among the classes occurring in it, must at the bottom.
  for (const auto& [k, b] : bins) {
    const int present = b.classes[0] + b.classes[1] + b.classes[2];
    double y = 0;
    for (int c = 0; c < 3; ++c) {
      if (!b.classes[c]) continue;
      canvas.rectangle({k * kStickBinWidth, y}, {(k + 1) * kStickBinWidth, y + 1.0 / present},
                       kClassBands[c]);
      y += 1.0 / present;
    }
  }
  canvas.grid();
  // alpha = phi: where a face's friction cone ends.
  canvas.dashed_line({1, -kYMargin}, {1, 1 + kYMargin}, rgb(0x606060), 1);
  bool any_kind[3] = {false, false, false};
  for (int kind = 0; kind < 3; ++kind) {
    std::vector<Point2> run;  // consecutive bins with trials form one polyline
    int last = 0;
    auto flush = [&] {
      canvas.polyline(run, false, kKindColors[kind], kCurveThickness);
      run.clear();
    };
    for (const auto& [k, b] : bins) {
      if (b.trials[kind] == 0) continue;
      any_kind[kind] = true;
      if (!run.empty() && k != last + 1) flush();
      const Point2 p((k + 0.5) * kStickBinWidth, static_cast<double>(b.stuck[kind]) / b.trials[kind]);
      run.push_back(p);
      canvas.dot(p, kBinDotRadius, kKindColors[kind]);
      last = k;
    }
    flush();
  }
  for (int kind = 0; kind < 3; ++kind)
    if (any_kind[kind])
      canvas.add_legend(
          {std::string("observed, ") + kKindPlurals[kind], kKindColors[kind], LegendMarker::kLine});
  for (int c = 0; c < 3; ++c)
    canvas.add_legend(
        {std::string("predicted ") + kClasses[c] + " stick", kClassBands[c], LegendMarker::kFill});
  canvas.add_legend({"alpha = phi", rgb(0x606060), LegendMarker::kLine});
  canvas.finish();
  return canvas;
}

}  // namespace cmt::report

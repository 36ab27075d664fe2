#include "experiments/report/edr_figure.h"

#include <algorithm>
#include <vector>

#include "experiments/report/plot_style.h"

namespace cmt::report {
namespace {

using nlohmann::json;

const cv::Scalar kOutcomeColors[] = {rgb(0x009e73), rgb(0xe69f00), rgb(0x0072b2), rgb(0x999999),
                                     rgb(0xcccccc), rgb(0xd55e00), rgb(0xcc79a7)};
const char* const kOutcomeLabels[] = {"success",
                                      "missed success",
                                      "failure signalled",
                                      "time-out",
                                      "unstable",
                                      "false success (forbidden)",
                                      "false failure (forbidden)"};
constexpr int kOutcomeCount = 7;
constexpr double kBarHalfWidth = 0.004;         // of the parameter's interval
constexpr double kDiscreteBarHalfWidth = 0.15;  // of the smallest gap between a discrete parameter's values

double number_or(const json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

// One world: its value of the first parameter and its rollouts per outcome (worlds drawn at the same value,
// as a discrete parameter's are, make one bar).
struct WorldBar {
  double x = 0;
  double counts[kOutcomeCount] = {};
  double total = 0;
};

std::vector<WorldBar> world_bars(const json& worlds) {
  std::vector<WorldBar> bars;
  for (const json& w : worlds) {
    if (!w.is_object() || !w.contains("params") || !w["params"].is_array() || w["params"].empty() ||
        !w["params"][0].is_number())
      continue;
    WorldBar b;
    b.x = w["params"][0].get<double>();
    for (int k = 0; k < kOutcomeCount; ++k) {
      b.counts[k] = std::max(0.0, number_or(w.value("outcomes", json()), kEdrFigureOutcomes[k], 0));
      b.total += b.counts[k];
    }
    if (b.total <= 0) continue;
    auto same = std::find_if(bars.begin(), bars.end(), [&](const WorldBar& o) { return o.x == b.x; });
    if (same == bars.end()) {
      bars.push_back(b);
      continue;
    }
    for (int k = 0; k < kOutcomeCount; ++k) same->counts[k] += b.counts[k];
    same->total += b.total;
  }
  std::sort(bars.begin(), bars.end(), [](const WorldBar& a, const WorldBar& b) { return a.x < b.x; });
  return bars;
}

// Half a bar's width: a fixed fraction of the span, or for a discrete parameter of the closest bars' gap.
double bar_half_width(const json& parameter, const std::vector<WorldBar>& bars, double span) {
  const bool discrete = parameter.contains("discrete") && parameter["discrete"].is_boolean() &&
                        parameter["discrete"].get<bool>();
  if (!discrete) return kBarHalfWidth * span;
  double gap = span;
  for (std::size_t i = 1; i < bars.size(); ++i) gap = std::min(gap, bars[i].x - bars[i - 1].x);
  return kDiscreteBarHalfWidth * gap;
}

}  // namespace

std::optional<PlotCanvas> draw_edr_figure(const json& run, const std::string& title, const FigureSize& size) {
  if (!run.is_object() || !run.contains("check") || !run["check"].is_object()) return std::nullopt;
  const json& parameters = run.value("parameters", json());
  if (!parameters.is_array() || parameters.empty() || !parameters[0].is_object()) return std::nullopt;
  const std::vector<WorldBar> bars = world_bars(run["check"].value("worlds", json::array()));
  if (bars.empty()) return std::nullopt;
  const json& p = parameters[0];
  Range x{number_or(p, "min", bars.front().x), number_or(p, "max", bars.front().x)};
  for (const WorldBar& b : bars) x = {std::min(x.min, b.x), std::max(x.max, b.x)};
  const double span = x.max > x.min ? x.max - x.min : 1.0;
  const std::string name =
      p.contains("name") && p["name"].is_string() ? p["name"].get<std::string>() : "parameter";
  PlotCanvas canvas(size, title, name, "fraction of the world's rollouts");
  canvas.set_ranges({x.min - 0.02 * span, x.max + 0.02 * span}, {0, 1}, false);
  canvas.grid();
  const double half_width = bar_half_width(p, bars, span);
  for (const WorldBar& b : bars) {
    double y = 0;
    for (int k = 0; k < kOutcomeCount; ++k) {
      if (b.counts[k] <= 0) continue;
      const double top = y + b.counts[k] / b.total;
      canvas.rectangle({b.x - half_width, y}, {b.x + half_width, top}, kOutcomeColors[k]);
      y = top;
    }
  }
  for (const json& c : p.value("critical", json::array()))
    if (c.is_number()) canvas.dashed_line({c.get<double>(), 0}, {c.get<double>(), 1}, rgb(0x000000), 1);
  for (int k = 0; k < kOutcomeCount; ++k) canvas.add_legend({kOutcomeLabels[k], kOutcomeColors[k]});
  canvas.add_legend({"critical value (dashed)", rgb(0x000000), LegendMarker::kLine});
  canvas.add_legend({"one bar per world (parameter value)", rgb(0x000000), LegendMarker::kNone});
  canvas.finish();
  return canvas;
}

}  // namespace cmt::report

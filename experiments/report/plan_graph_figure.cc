// The plan's state graph as a figure (plan_graph_figure.h).
#include "experiments/report/plan_graph_figure.h"

#include <algorithm>
#include <map>

#include "experiments/report/plot_style.h"

namespace cmt::report {
namespace {

using nlohmann::json;

std::string state_label(const json& state) {
  std::string out;
  if (!state.is_array()) return out;
  for (const json& atom : state) out += (out.empty() ? "" : ", ") + atom.get<std::string>();
  return out;
}

const cv::Scalar kStateFill = rgb(0xe8eef7);
const cv::Scalar kStateLine = rgb(0x4a5a75);
constexpr double kArrowHead = 0.06;  // data units

}  // namespace

PlanGraph plan_graph(const json& run) {
  PlanGraph g;
  if (!run.contains("steps") || !run["steps"].is_array() || run["steps"].empty()) return g;
  std::map<std::pair<std::string, int>, int> index;  // (label, column) -> node
  std::map<int, int> rows;                           // column -> rows used
  const auto node = [&](const std::string& label, int column) {
    const auto [it, fresh] = index.emplace(std::pair{label, column}, static_cast<int>(g.nodes.size()));
    if (fresh) g.nodes.push_back({label, column, rows[column]++, true});
    return it->second;
  };
  if (run.contains("start_states") && run["start_states"].is_array())
    for (const json& s : run["start_states"]) node(state_label(s), 0);
  // Steps are depth first: a step's state is the head of an earlier step (or a start state); its column is
  // the deepest such node's (a state met again deeper is drawn again).
  std::map<std::string, int> column_of;
  for (const PlanGraphNode& n : g.nodes) column_of[n.label] = 0;
  for (const json& step : run["steps"]) {
    const std::string from_label = state_label(step.value("state", json::array()));
    const int column = column_of.count(from_label) ? column_of[from_label] : 0;
    const int from = node(from_label, column);
    g.nodes[static_cast<std::size_t>(from)].goal = false;
    for (const json& head : step.value("heads", json::array())) {
      const std::string label = state_label(head);
      const int to = node(label, column + 1);
      g.edges.push_back({from, to, step.value("motion", std::string())});
      column_of[label] = column + 1;
    }
  }
  return g;
}

std::optional<PlotCanvas> draw_plan_graph(const json& run, const std::string& title, const FigureSize& size) {
  const PlanGraph g = plan_graph(run);
  if (g.nodes.empty()) return std::nullopt;
  int columns = 0, rows = 0;
  for (const PlanGraphNode& n : g.nodes) columns = std::max(columns, n.column), rows = std::max(rows, n.row);
  PlotCanvas canvas(size, title, "motions done", "state");
  canvas.set_ranges({-0.5, columns + 0.5}, {-rows - 0.5, 0.5}, true);
  const auto at = [&](int i) {
    const PlanGraphNode& n = g.nodes[static_cast<std::size_t>(i)];
    return DataPoint{static_cast<double>(n.column), -static_cast<double>(n.row)};
  };
  for (const PlanGraphEdge& e : g.edges) {  // from the right side of one box to the left side of the next
    const DataPoint a = at(e.from), b = at(e.to);
    const DataPoint start{a.x + kPlanNodeHalfWidth, a.y}, end{b.x - kPlanNodeHalfWidth, b.y};
    canvas.polyline({start, end}, false, kInk, 2);
    const double dx = end.x - start.x, dy = end.y - start.y, len = std::max(1e-9, std::hypot(dx, dy));
    const double ux = dx / len, uy = dy / len;
    canvas.polyline({{end.x - kArrowHead * (ux - uy), end.y - kArrowHead * (uy + ux)},
                     end,
                     {end.x - kArrowHead * (ux + uy), end.y - kArrowHead * (uy - ux)}},
                    false, kInk, 2);
    canvas.text({(start.x + end.x) / 2, (start.y + end.y) / 2}, e.motion, {0, -10}, TextAnchor::kCenter,
                kInk);
  }
  for (std::size_t i = 0; i < g.nodes.size(); ++i) {
    const PlanGraphNode& n = g.nodes[i];
    const DataPoint c = at(static_cast<int>(i));
    const DataPoint lo{c.x - kPlanNodeHalfWidth, c.y - kPlanNodeHalfHeight},
        hi{c.x + kPlanNodeHalfWidth, c.y + kPlanNodeHalfHeight};
    canvas.rectangle(lo, hi, n.goal ? kGoalFill : kStateFill);
    canvas.polyline({lo, {hi.x, lo.y}, hi, {lo.x, hi.y}}, true, n.goal ? kGoalLine : kStateLine, 2);
    canvas.text(c, n.label, {0, 0}, TextAnchor::kCenter, kInk);
  }
  canvas.add_legend({"state", kStateLine, LegendMarker::kLine});
  canvas.add_legend({"goal state", kGoalLine, LegendMarker::kLine});
  canvas.finish();
  return canvas;
}

}  // namespace cmt::report

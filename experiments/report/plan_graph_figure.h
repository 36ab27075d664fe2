// A plan as a graph (Buckley §6.5, Figs 6.12-6.13's state graphs; docs/planner.md "Output"): the states of a
// `cmt plan --json` result (sets of atoms the robot cannot tell apart) as boxes, one column per motion done,
// and per step an arrow from its state to each of its heads, labelled with the motion. The states no step
// leaves (a found plan's goals, `goal` the goal stop) are drawn in the goal's colors.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "experiments/report/plot_canvas.h"

namespace cmt::report {

// Where the graph puts each state: column (motions done) and row, in the figure's data coordinates
// (x = column, y = -row).
struct PlanGraphNode {
  std::string label;  // the state's atom names, comma separated
  int column = 0, row = 0;
  bool goal = false;  // no step leaves it
};
struct PlanGraphEdge {
  int from = 0, to = 0;  // node indices
  std::string motion;
};
struct PlanGraph {
  std::vector<PlanGraphNode> nodes;
  std::vector<PlanGraphEdge> edges;
};

// The graph of the result's `start_states` and `steps` (state, motion, heads); empty without steps.
PlanGraph plan_graph(const nlohmann::json& plan_run);

// The figure, or nothing when the result has no steps.
std::optional<PlotCanvas> draw_plan_graph(const nlohmann::json& plan_run, const std::string& title,
                                          const FigureSize& size = {});

// The box half-size of a node, in data units (columns are 1 apart, rows 1 apart).
inline constexpr double kPlanNodeHalfWidth = 0.3;
inline constexpr double kPlanNodeHalfHeight = 0.2;

}  // namespace cmt::report

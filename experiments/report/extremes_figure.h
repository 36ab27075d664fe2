// Buckley §6.3.4's experiment as a figure (docs/planner.md "§6.3.4"): per planned motion of a `cmt plan
// --extremes` result, the fraction of rollouts that reached the goal against how far outside the motion's
// cposition polyhedra it was commanded, in eps_p (0: at their vertices, then at the vertices of the polyhedra
// grown by each --grow factor).
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "experiments/report/plot_canvas.h"

namespace cmt::report {

// The figure, or nothing when the result has no `extremes`.
std::optional<PlotCanvas> draw_extremes_figure(const nlohmann::json& plan_run, const std::string& title,
                                               const FigureSize& size = {});

}  // namespace cmt::report

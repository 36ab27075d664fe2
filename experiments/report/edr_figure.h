// The outcomes of an EDR physics check against a model parameter (docs/edr.md "Physics check"): per world of
// a `cmt edr --check` result, a stacked bar at the world's value of the first model parameter with the
// fraction of its rollouts per outcome (success, missed success, failure signalled, time-out, unstable and
// the two forbidden ones, false success and false failure), and the parameter's critical values (where the
// C-space's topology changes, e.g. the goal vanishes) as dashed lines.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "experiments/report/plot_canvas.h"

namespace cmt::report {

// The outcomes in stacking order (bottom first), as the check's per-world `outcomes` objects name them.
inline constexpr const char* kEdrFigureOutcomes[] = {"success",      "missed_success", "failure_signalled",
                                                     "timeout",      "unstable",       "false_success",
                                                     "false_failure"};

// The figure, or nothing when the result has no check with worlds or no model parameter.
std::optional<PlotCanvas> draw_edr_figure(const nlohmann::json& edr_run, const std::string& title,
                                          const FigureSize& size = {});

}  // namespace cmt::report

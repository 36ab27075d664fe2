// Stick fraction against the command angle, from the per-trial records of the sticking physics check
// (experiments/validation/sticking_check.h): trials are binned by alpha/phi (the command's angle from the
// atom's inward direction over the friction angle atan(mu)), one curve per atom kind, and behind the curves
// the verifier's classes that occur in each bin (must / may / never stick) are shaded as bands.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "experiments/report/plot_canvas.h"

namespace cmt::report {

// Bin width in alpha/phi.
inline constexpr double kStickBinWidth = 0.05;

// The figure, or nothing when the JSON has no usable records (no sticking check ran, or every record lacks a
// finite angle or a positive friction angle). Throws std::invalid_argument naming the JSON path when
// `records` is not a list of objects.
std::optional<PlotCanvas> draw_sticking_figure(const nlohmann::json& sticking, const std::string& title,
                                               const FigureSize& size = {});

}  // namespace cmt::report

// Stick fraction against the command angle, from the per-trial records of the sticking physics check
// (experiments/validation/sticking_check.h): trials are binned by alpha/phi (the command's angle from the
// atom's inward direction over the friction angle atan(mu)), and per atom kind (face, edge, vertex, or any
// other kind the records name) one marker is drawn per non-empty bin at (bin centre, stuck / trials), with a
// shape and colour per kind and the number of trials in the bin written beside it. Behind the markers the
// verifier's classes that occur in each bin (must / may / never stick) are shaded as bands.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "experiments/report/plot_canvas.h"

namespace cmt::report {

// The bin width is the smallest of 1, 2, 2.5 or 5 times a power of ten, and at least kStickMinBinWidth, that
// covers the records' alpha/phi range with at most kStickMaxBins bins whose edges are multiples of the width.
// Each such width divides 1, so alpha = phi (where a face's friction cone ends) is always a bin edge.
inline constexpr int kStickMaxBins = 15;
inline constexpr double kStickMinBinWidth = 0.01;

// The trials of one atom kind whose alpha/phi lies in one bin [lo, hi).
struct StickBin {
  std::string kind;  // the records' "kind"
  int index = 0;     // the bin's place from the first: lo = origin + index * width
  double lo = 0, hi = 0;
  int trials = 0, stuck = 0;
  std::array<int, 3> classes{};  // trials per predicted class: must, may, never

  double centre() const { return 0.5 * (lo + hi); }
  double fraction() const { return trials > 0 ? static_cast<double>(stuck) / trials : 0.0; }
};

struct StickBinning {
  double origin = 0, width = 0;    // the first bin's left edge and the bin width, in alpha/phi
  int count = 0;                   // bins from the first to the last non-empty one
  std::vector<std::string> kinds;  // the kinds present: face, edge, vertex in this order, then others by name
  std::vector<StickBin> bins;      // the non-empty bins, by kind (in the order of `kinds`), then by index
  int skipped = 0;                 // records without a kind or a finite alpha/phi (phi must be positive)
};

// The bin width for alpha/phi values in [lo, hi] (see kStickMaxBins).
double stick_bin_width(double lo, double hi);

// The records of a sticking_check_json object binned per kind; no bins when it has no "records". Throws
// std::invalid_argument naming the JSON path when `records` is not a list of objects.
StickBinning bin_sticking_records(const nlohmann::json& sticking);

// The figure, or nothing when the JSON has no usable records (no sticking check ran, or every record lacks a
// kind, a finite angle or a positive friction angle). Throws as bin_sticking_records.
std::optional<PlotCanvas> draw_sticking_figure(const nlohmann::json& sticking, const std::string& title,
                                               const FigureSize& size = {});

}  // namespace cmt::report

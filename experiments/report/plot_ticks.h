// Axis tick positions and labels for the report's figures: "nice" steps (1, 2 or 5 times a power of ten), as
// a reader of a printed plot expects.
#pragma once

#include <string>
#include <vector>

namespace cmt::report {

// Ticks inside [lo, hi] at a nice step chosen so that about `target` of them fall in the range. An empty or
// non-finite range gives no ticks.
std::vector<double> nice_ticks(double lo, double hi, int target = 6);

// The tick step nice_ticks uses for the same arguments (0 when it gives no ticks).
double nice_step(double lo, double hi, int target = 6);

// A label with just enough decimals for ticks `step` apart ("0.25", "-3", "1e+03" for huge values).
std::string tick_label(double value, double step);

}  // namespace cmt::report

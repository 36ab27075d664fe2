#include "experiments/report/plot_ticks.h"

#include <cmath>
#include <cstdio>

namespace cmt::report {
namespace {

// Labels switch to exponent notation beyond these magnitudes, where fixed notation would not fit a tick.
constexpr double kLargestFixedLabel = 1e5;
constexpr double kSmallestFixedStep = 1e-4;

}  // namespace

double nice_step(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || hi <= lo || target < 1) return 0;
  const double raw = (hi - lo) / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double fraction = raw / magnitude;
  const double nice = fraction < 1.5 ? 1 : fraction < 3.5 ? 2 : fraction < 7.5 ? 5 : 10;
  return nice * magnitude;
}

std::vector<double> nice_ticks(double lo, double hi, int target) {
  const double step = nice_step(lo, hi, target);
  std::vector<double> ticks;
  if (step <= 0) return ticks;
  // Multiples of the step, so 0 is a tick whenever it is in range; the half-step slack keeps an end tick that
  // rounding puts a hair outside.
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1) {
    const double t = k * step;
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);  // no "-0"
  }
  return ticks;
}

std::string tick_label(double value, double step) {
  char buf[32];
  if (std::abs(value) >= kLargestFixedLabel || (step > 0 && step < kSmallestFixedStep)) {
    std::snprintf(buf, sizeof buf, "%.3g", value);
    return buf;
  }
  int decimals = 0;
  if (step > 0 && step < 1) decimals = static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  // 0.25-type steps need one decimal more than their magnitude.
  const double scaled = step * std::pow(10.0, decimals);
  if (std::abs(scaled - std::round(scaled)) > 1e-6) ++decimals;
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

}  // namespace cmt::report

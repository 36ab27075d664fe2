// minimize_over_lambda (verifier/internal/spring_velocity.h), the search behind the spring's support-bound
// sections: it finds the minimum of a convex function wherever the minimiser lies in [−1e3, 1e3], from any
// starting guess, to the documented resolution, and every value it returns is a value of the function.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "verifier/internal/spring_velocity.h"

namespace cmt::face_geometry {
namespace {

TEST(LambdaSearch, FindsTheMinimumOfAConvexFunctionFromAnyGuess) {
  for (const double target : {-999.5, -37.25, 0.0, 1e-3, 4.5, 700.0}) {
    for (const double start : {0.0, target, -800.0, 650.0}) {
      const auto f = [&](double x) { return 2 + std::abs(x - target) + 0.25 * (x - target) * (x - target); };
      double guess = start;
      const double best = minimize_over_lambda(f, &guess);
      EXPECT_NEAR(guess, target, 1e-8) << "target " << target << " from " << start;
      EXPECT_GE(best, 2);  // a value of f
      EXPECT_NEAR(best, 2, 1e-8);
      EXPECT_EQ(best, f(guess));
    }
  }
}

// A minimiser beyond the range: the search stops at the range's end, whose value it returns.
TEST(LambdaSearch, AMinimiserBeyondTheRangeGivesTheRangesEnd) {
  const auto f = [](double x) { return -x; };
  double guess = 0;
  EXPECT_EQ(minimize_over_lambda(f, &guess), -1e3);
  EXPECT_EQ(guess, 1e3);
}

// Neighbouring directions: starting from the previous minimiser costs far fewer evaluations than a cold
// start.
TEST(LambdaSearch, AWarmStartNeedsFewerEvaluations) {
  int calls = 0;
  const auto f = [&](double x) {
    ++calls;
    return std::hypot(x - 3.2, 1.0);
  };
  double cold = -900;
  const double cold_best = minimize_over_lambda(f, &cold);
  const int cold_calls = calls;
  calls = 0;
  double warm = 3.19;
  const double warm_best = minimize_over_lambda(f, &warm);
  // A smooth minimum: values within rounding of f(3.2) = 1 (its minimisers are known only to about 1e-8).
  EXPECT_LE(cold_best, 1 + 1e-15);
  EXPECT_LE(warm_best, 1 + 1e-15);
  EXPECT_NEAR(cold, 3.2, 1e-6);
  EXPECT_NEAR(warm, 3.2, 1e-6);
  EXPECT_LT(calls, cold_calls * 2 / 3) << calls << " vs " << cold_calls;
}

// With a value tolerance the search stops once convexity bounds the minimum to within it: the value returned
// is a value of f within the tolerance of the least, found in fewer evaluations, on smooth minima and kinks.
TEST(LambdaSearch, AValueToleranceStopsWithinItOfTheMinimum) {
  const std::vector<std::function<double(double)>> functions = {
      [](double x) { return std::hypot(x - 3.2, 1.0); },                       // smooth, minimum 1
      [](double x) { return 1 + std::abs(x + 0.7) + 1e-3 * x * x - 4.9e-4; },  // a kink at -0.7
      [](double x) { return std::max(1 - x, 0.5 * x - 0.5) + 0.5; }};          // two lines: .5 at x = 1
  const std::vector<double> least = {1.0, 1 + 1e-3 * 0.49 - 4.9e-4, 0.5};
  for (std::size_t k = 0; k < functions.size(); ++k) {
    for (const double tolerance : {1e-3, 1e-9}) {
      int calls = 0;
      const auto f = [&](double x) {
        ++calls;
        return functions[k](x);
      };
      double exact_guess = 0, guess = 0;
      const double exact = minimize_over_lambda(f, &exact_guess);
      const int exact_calls = calls;
      calls = 0;
      const double stopped = minimize_over_lambda(f, &guess, tolerance);
      EXPECT_EQ(stopped, functions[k](guess)) << k;  // a value of f
      EXPECT_GE(stopped, least[k] - 1e-12) << k;
      EXPECT_LE(stopped, least[k] + tolerance) << k << " tolerance " << tolerance;
      EXPECT_NEAR(exact, least[k], 1e-9) << k;
      EXPECT_LT(calls, exact_calls) << k << " tolerance " << tolerance;
    }
  }
}

}  // namespace
}  // namespace cmt::face_geometry

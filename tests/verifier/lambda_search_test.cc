// minimize_over_lambda (verifier/internal/spring_velocity.h), the search behind the spring's support-bound
// sections: it finds the minimum of a convex function wherever the minimiser lies in [−1e3, 1e3], from any
// starting guess, to the documented resolution, and every value it returns is a value of the function.
#include <gtest/gtest.h>

#include <cmath>
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

}  // namespace
}  // namespace cmt::face_geometry

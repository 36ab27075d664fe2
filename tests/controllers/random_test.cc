// Seeded streams: SplitMix64 matches its reference, rollout streams depend on (seed, index) only, and the
// samplers stay in their sets.
#include "controllers/random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace cmt {
namespace {

TEST(Random, SplitMix64MatchesTheReferenceGenerator) {
  // Reference: the first outputs of Vigna's splitmix64.c seeded with 0 (state advanced by the golden gamma
  // before mixing, which splitmix64() does too).
  EXPECT_EQ(splitmix64(0), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(splitmix64(0x9e3779b97f4a7c15ULL), 0x6e789e6aa1b965f4ULL);
}

TEST(Random, RolloutStreamsDependOnSeedAndIndexOnly) {
  Rng a = rollout_stream(42, 7), b = rollout_stream(42, 7);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a(), b());
  // Neighbouring indices and seeds give different streams.
  std::set<std::uint64_t> firsts;
  for (std::uint64_t seed = 0; seed < 20; ++seed)
    for (std::uint64_t index = 0; index < 20; ++index) firsts.insert(rollout_stream(seed, index)());
  EXPECT_EQ(firsts.size(), 400u);
}

TEST(Random, SamplersStayInTheirSets) {
  Rng rng = rollout_stream(1, 0);
  double mean = 0;
  int counts[5] = {0};
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double u = uniform01(rng);
    ASSERT_GE(u, 0);
    ASSERT_LT(u, 1);
    mean += u / n;
    ++counts[uniform_index(rng, 5)];
    const Vec3 s = uniform_on_sphere(rng);
    ASSERT_NEAR(s.norm(), 1, 1e-15);
    const Vec3 c = uniform_on_sphere(rng, true);
    ASSERT_EQ(c.y(), 0);
    ASSERT_NEAR(c.norm(), 1, 1e-15);
    ASSERT_LE(uniform_in_ball(rng, 0.3).norm(), 0.3 * (1 + 1e-15));
    const Vec3 d = uniform_in_ball(rng, 0.3, true);
    ASSERT_EQ(d.y(), 0);
  }
  EXPECT_NEAR(mean, 0.5, 0.01);  // 7 standard errors
  for (const int c : counts) EXPECT_NEAR(c, n / 5, 300);
}

TEST(Random, BallSamplesAreUniformInVolume) {
  // Uniform in a ball: P(|x| <= r/2) = 1/8 in 3-D, 1/4 in a disc.
  Rng rng = rollout_stream(3, 0);
  int inner3 = 0, inner2 = 0;
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    inner3 += uniform_in_ball(rng, 2.0).norm() <= 1.0;
    inner2 += uniform_in_ball(rng, 2.0, true).norm() <= 1.0;
  }
  EXPECT_NEAR(inner3 / double(n), 0.125, 0.01);
  EXPECT_NEAR(inner2 / double(n), 0.25, 0.01);
}

}  // namespace
}  // namespace cmt

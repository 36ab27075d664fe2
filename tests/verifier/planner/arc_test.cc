// Type 1 arc composition (verifier/planner/arc.h, Buckley Table 6.4, Theorems 6.1 and 6.3) on small random
// inputs: the composed arcs are nonoverlapping (a commanded position lies in one arc at most), complete
// (every commanded position of a weak arc lies in a composed arc) and carry every possible target (the arc
// holding a position has exactly the union of the targets of the weak arcs that hold it).
#include "verifier/planner/arc.h"

#include <gtest/gtest.h>

#include <random>

namespace cmt::planner {
namespace {

const AxisBox kDomain{Vec3(-4, -4, -4), Vec3(4, 4, 4)};

double margin(const Vec3& p, const std::vector<Arc>& arcs) {
  double m = 1e9;
  for (const Arc& a : arcs)
    for (const ConvexPiece& piece : a.cpositions.pieces())
      for (const HalfSpace& h : piece.halfspaces) m = std::min(m, std::abs(h.normal.dot(p) - h.offset));
  return m;
}

TEST(ArcComposition, RandomWeakArcsComposeCompleteAndNonoverlapping) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> corner(-3, 3), side(0.5, 3);
  for (int trial = 0; trial < 6; ++trial) {
    std::vector<Arc> weak;
    for (int i = 0; i < 5; ++i) {
      const Vec3 lo(corner(rng), corner(rng), corner(rng));
      const Vec3 hi = lo + Vec3(side(rng), side(rng), side(rng));
      weak.push_back({{i % 3 + (trial % 2) * i}, CPositionSet::convex(box_halfspaces({lo, hi}), kDomain)});
    }
    // One weak arc a union of two overlapping pieces, with a target shared with another arc.
    weak.push_back(
        {{1},
         CPositionSet::convex(box_halfspaces({Vec3(-1, -1, -1), Vec3(1, 1, 1)}), kDomain)
             .unite(CPositionSet::convex(box_halfspaces({Vec3(0, 0, 0), Vec3(2, 2, 2)}), kDomain))});
    const std::vector<Arc> composed = compose_type1(weak);
    std::uniform_real_distribution<double> u(-3.9, 3.9);
    int compared = 0;
    for (int i = 0; i < 1500; ++i) {
      const Vec3 p(u(rng), u(rng), u(rng));
      if (margin(p, weak) < 1e-6 || margin(p, composed) < 1e-6) continue;
      ++compared;
      std::vector<int> expected;
      for (const Arc& a : weak)
        if (a.cpositions.contains(p)) expected = target_union(expected, a.targets);
      int holders = 0;
      for (const Arc& a : composed)
        if (a.cpositions.contains(p)) {
          ++holders;
          EXPECT_EQ(a.targets, expected) << p.transpose();
        }
      EXPECT_EQ(holders, expected.empty() ? 0 : 1) << "trial " << trial << " at " << p.transpose();
    }
    EXPECT_GT(compared, 1000);
  }
}

TEST(ArcComposition, ArcsWithIdenticalTargetsMerge) {
  const Arc a{{2}, CPositionSet::convex(box_halfspaces({Vec3(0, 0, 0), Vec3(1, 1, 1)}), kDomain)};
  const Arc b{{2}, CPositionSet::convex(box_halfspaces({Vec3(0.5, 0, 0), Vec3(2, 1, 1)}), kDomain)};
  const auto composed = compose_type1({a, b});
  ASSERT_EQ(composed.size(), 1u);
  EXPECT_TRUE(composed[0].cpositions.contains(Vec3(1.5, 0.5, 0.5)));
  EXPECT_TRUE(composed[0].cpositions.contains(Vec3(0.2, 0.5, 0.5)));
}

}  // namespace
}  // namespace cmt::planner

// Arc composition (verifier/planner/arc.h) on small inputs. Type 1 (Buckley Table 6.4, Theorems 6.1 and
// 6.3): the composed arcs are nonoverlapping (a commanded position lies in one arc at most), complete (every
// commanded position of a weak arc lies in a composed arc) and carry every possible target (the arc holding
// a position has exactly the union of the targets of the weak arcs that hold it). Type 2 (Table 6.2):
// Table 6.2's five arcs, and on random inputs sound at the set level and complete.
#include "verifier/planner/arc.h"

#include <gtest/gtest.h>

#include <algorithm>
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

CPositionSet box(const Vec3& lo, const Vec3& hi) {
  return CPositionSet::convex(box_halfspaces({lo, hi}), kDomain);
}

// Table 6.2 on two weak arcs: five arcs, (C1 ∩ C2, S1 ∩ S2, {1, 2}), (C1 − C2, S1, {1}), (C1, S1 − S2, {1}),
// (C2 − C1, S2, {2}), (C2, S2 − S1, {2}), checked at points of each region.
TEST(Type2ArcComposition, TwoWeakArcsGiveTable62sFiveArcs) {
  const Type2Arc one{{1}, box(Vec3(0, 0, 0), Vec3(2, 2, 2)), box(Vec3(0, 0, 0), Vec3(1, 1, 1))};
  const Type2Arc two{{2}, box(Vec3(1, 0, 0), Vec3(3, 2, 2)), box(Vec3(0.5, 0, 0), Vec3(1.5, 1, 1))};
  const std::vector<Type2Arc> arcs = compose_type2({one, two});
  ASSERT_EQ(arcs.size(), 5u);
  // Which arcs hold commanded position c with sensed position s.
  const auto holders = [&](const Vec3& c, const Vec3& s) {
    std::vector<std::vector<int>> out;
    for (const Type2Arc& a : arcs)
      if (a.cpositions.contains(c) && a.spositions.contains(s)) out.push_back(a.targets);
    std::sort(out.begin(), out.end());
    return out;
  };
  const Vec3 c1(0.5, 1, 1), c12(1.5, 1, 1), c2(2.5, 1, 1);                 // C1 only, both, C2 only
  const Vec3 s1(0.25, 0.5, 0.5), s12(0.75, 0.5, 0.5), s2(1.25, 0.5, 0.5);  // S1 only, both, S2 only
  using V = std::vector<std::vector<int>>;
  EXPECT_EQ(holders(c12, s12), (V{{1, 2}}));  // only the intersection arc
  EXPECT_EQ(holders(c1, s12), (V{{1}}));      // C1 − C2
  EXPECT_EQ(holders(c1, s1), (V{{1}, {1}}));  // C1 − C2, and C1 with S1 − S2
  EXPECT_EQ(holders(c12, s1), (V{{1}}));      // C1 with S1 − S2 (s1 is not in S2)
  EXPECT_EQ(holders(c2, s2), (V{{2}, {2}}));
  EXPECT_EQ(holders(c12, s2), (V{{2}}));  // C2 with S2 − S1
}

// Random weak arcs: every composed arc is sound at the set level (each weak atom outside its targets has
// commanded or sensed positions disjoint from it up to shared boundaries: no motion of the arc may stop
// there) and the arcs are
// complete (a commanded position c of C_i with a sensed position s of S_i lies in an arc together).
TEST(Type2ArcComposition, RandomWeakArcsComposeSoundAndComplete) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> corner(-3, 1), side(0.8, 2.9);  // boxes inside kDomain
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<Type2Arc> weak;
    std::vector<std::pair<AxisBox, AxisBox>> boxes;  // C_i, S_i
    for (int i = 0; i < 3; ++i) {
      const Vec3 c(corner(rng), corner(rng), corner(rng)), s(corner(rng), corner(rng), corner(rng));
      boxes.push_back(
          {{c, c + Vec3(side(rng), side(rng), side(rng))}, {s, s + Vec3(side(rng), side(rng), side(rng))}});
      weak.push_back({{i},
                      box(boxes.back().first.min, boxes.back().first.max),
                      box(boxes.back().second.min, boxes.back().second.max)});
    }
    const std::vector<Type2Arc> arcs = compose_type2(weak);
    ASSERT_FALSE(arcs.empty());
    for (const Type2Arc& a : arcs)
      for (const Type2Arc& w : weak) {
        if (std::binary_search(a.targets.begin(), a.targets.end(), w.targets[0])) continue;
        // Up to shared boundaries (a difference keeps its closed boundary: a slab of zero width).
        EXPECT_TRUE(!a.cpositions.intersect(w.cpositions).interior_point() ||
                    !a.spositions.intersect(w.spositions).interior_point())
            << "trial " << trial << ": an arc without " << w.targets[0] << " may stop there";
      }
    // Completeness at points (c, s) of each weak arc's C_i x S_i.
    std::uniform_real_distribution<double> t(0.001, 0.999);
    const auto in = [&](const AxisBox& b) {
      return Vec3(b.min.x() + t(rng) * (b.max.x() - b.min.x()), b.min.y() + t(rng) * (b.max.y() - b.min.y()),
                  b.min.z() + t(rng) * (b.max.z() - b.min.z()));
    };
    int checked = 0;
    for (const auto& [cbox, sbox] : boxes)
      for (int k = 0; k < 100; ++k) {
        const Vec3 c = in(cbox), s = in(sbox);
        ++checked;
        const bool covered = std::any_of(arcs.begin(), arcs.end(), [&](const Type2Arc& a) {
          return a.cpositions.contains(c) && a.spositions.contains(s);
        });
        EXPECT_TRUE(covered) << "trial " << trial << " c " << c.transpose() << " s " << s.transpose();
      }
    EXPECT_EQ(checked, 300);
  }
}

}  // namespace
}  // namespace cmt::planner

// Sets of commanded positions (verifier/planner/cposition_set.h): intersection, difference and complement
// agree with point membership away from the pieces' boundaries; empty results are empty; interior points
// are inside.
#include "verifier/planner/cposition_set.h"

#include <gtest/gtest.h>

#include <random>

namespace cmt::planner {
namespace {

const AxisBox kDomain{Vec3(-4, -4, -4), Vec3(4, 4, 4)};

CPositionSet box(const Vec3& lo, const Vec3& hi) {
  return CPositionSet::convex(box_halfspaces({lo, hi}), kDomain);
}

// The least distance from p to a plane of any piece of the sets: membership is only compared away from it.
double margin(const Vec3& p, const std::vector<const CPositionSet*>& sets) {
  double m = 1e9;
  for (const CPositionSet* s : sets)
    for (const ConvexPiece& piece : s->pieces())
      for (const HalfSpace& h : piece.halfspaces) m = std::min(m, std::abs(h.normal.dot(p) - h.offset));
  return m;
}

TEST(CPositionSet, DifferenceAndIntersectionMatchMembership) {
  const CPositionSet a = box(Vec3(-2, -2, -2), Vec3(2, 2, 2));
  const CPositionSet tilted = CPositionSet::convex({{Vec3(1, 1, 0).normalized(), 1.0},
                                                    {Vec3(-1, 0, 0), 1.5},
                                                    {Vec3(0, 0, 1), 3.0},
                                                    {Vec3(0, -1, -1).normalized(), 2.0}},
                                                   kDomain);
  const CPositionSet diff = a.minus(tilted), both = a.intersect(tilted);
  ASSERT_FALSE(diff.empty());
  ASSERT_FALSE(both.empty());
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3.5, 3.5);
  int compared = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p(u(rng), u(rng), u(rng));
    if (margin(p, {&a, &tilted, &diff, &both}) < 1e-6) continue;
    ++compared;
    EXPECT_EQ(diff.contains(p), a.contains(p) && !tilted.contains(p)) << p.transpose();
    EXPECT_EQ(both.contains(p), a.contains(p) && tilted.contains(p)) << p.transpose();
  }
  EXPECT_GT(compared, 3000);
}

TEST(CPositionSet, AComplementIsTheDomainLessTheConvexPart) {
  Polyhedron inner;
  inner.kind = Polyhedron::Kind::kComplement;
  inner.halfspaces = box_halfspaces({Vec3(-1, -1, -1), Vec3(1, 1, 1)});
  const CPositionSet outside = CPositionSet::of(inner, kDomain);
  EXPECT_TRUE(outside.contains(Vec3(3, 0, 0)));
  EXPECT_TRUE(outside.contains(Vec3(0, -1.5, 0.5)));
  EXPECT_FALSE(outside.contains(Vec3(0.5, 0.5, 0.5)));
  EXPECT_FALSE(outside.contains(Vec3(5, 0, 0)));  // outside the domain
}

TEST(CPositionSet, DisjointOrCoveredDifferencesAndEmptyIntersections) {
  const CPositionSet a = box(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const CPositionSet far = box(Vec3(2, 2, 2), Vec3(3, 3, 3));
  const CPositionSet big = box(Vec3(-1, -1, -1), Vec3(2, 2, 2));
  EXPECT_TRUE(a.intersect(far).empty());
  EXPECT_EQ(a.minus(far).pieces().size(), 1u);
  EXPECT_TRUE(a.minus(big).empty());
  EXPECT_TRUE(CPositionSet::none(kDomain).minus(a).empty());
}

TEST(CPositionSet, TheInteriorPointIsDeepInside) {
  const CPositionSet l = box(Vec3(0, 0, 0), Vec3(2, 2, 2)).minus(box(Vec3(1, 1, -1), Vec3(3, 3, 3)));
  const auto inside = l.interior_point();
  ASSERT_TRUE(inside.has_value());
  EXPECT_TRUE(l.contains(inside->point));
  EXPECT_GT(inside->depth, 0.2);
  EXPECT_FALSE(
      box(Vec3(0, 0, 0), Vec3(1, 1, 1)).intersect(box(Vec3(1, 0, 0), Vec3(2, 1, 1))).interior_point());
}

}  // namespace
}  // namespace cmt::planner

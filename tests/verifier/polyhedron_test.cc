// Polyhedra in half-space form (verifier/polyhedron.h): membership of the four kinds (closed convex sets,
// open complements), offsets that grow or shrink (flipped for complements), and hull_plus_cone on a cube, a
// point plus a cone of rays, and a lower-dimensional half-strip, checked against sets described by hand.
#include "verifier/polyhedron.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace cmt {
namespace {

const Vec3 kX = Vec3::UnitX(), kY = Vec3::UnitY(), kZ = Vec3::UnitZ();

// The cube [-1,1]^3 as six half-spaces.
Polyhedron cube() {
  Polyhedron p;
  p.kind = Polyhedron::Kind::kConvex;
  for (const Vec3& n : {kX, kY, kZ, Vec3(-kX), Vec3(-kY), Vec3(-kZ)}) p.halfspaces.push_back({n, 1.0});
  return p;
}

std::vector<Vec3> unit_cube_corners() {
  std::vector<Vec3> out;
  for (int i = 0; i < 8; ++i) out.push_back(Vec3(i & 1, (i >> 1) & 1, (i >> 2) & 1));
  return out;
}

TEST(Polyhedron, EmptyAndEverythingIgnorePoints) {
  EXPECT_FALSE(Polyhedron::nothing().contains(Vec3::Zero()));
  EXPECT_TRUE(Polyhedron::everything().contains(Vec3::Zero()));
  EXPECT_TRUE(Polyhedron::everything().contains(Vec3(1e9, -1e9, 3)));
  // Offsets leave them as they are.
  EXPECT_FALSE(Polyhedron::nothing().offset(5).contains(Vec3::Zero()));
  EXPECT_TRUE(Polyhedron::everything().offset(-5).contains(Vec3(1e9, 0, 0)));
}

TEST(Polyhedron, ConvexContainsItsClosedInterior) {
  const Polyhedron p = cube();
  EXPECT_TRUE(p.contains(Vec3::Zero()));
  EXPECT_TRUE(p.contains(Vec3(1, 0.5, -0.5)));  // on a face: closed
  EXPECT_TRUE(p.contains(Vec3(1, 1, 1)));       // a corner
  EXPECT_FALSE(p.contains(Vec3(1.001, 0, 0)));
  EXPECT_FALSE(p.contains(Vec3(0, 0, -1.001)));
}

TEST(Polyhedron, ComplementIsTheOpenOutside) {
  Polyhedron p = cube();
  p.kind = Polyhedron::Kind::kComplement;
  EXPECT_FALSE(p.contains(Vec3::Zero()));
  EXPECT_FALSE(p.contains(Vec3(1, 0.5, 0)));  // the cube's boundary belongs to the cube
  EXPECT_TRUE(p.contains(Vec3(1.001, 0, 0)));
  EXPECT_TRUE(p.contains(Vec3(-5, 7, 0)));
}

TEST(Polyhedron, OffsetMovesEveryPlane) {
  const Polyhedron grown = cube().offset(0.5), shrunk = cube().offset(-0.5);
  for (const HalfSpace& h : grown.halfspaces) EXPECT_DOUBLE_EQ(h.offset, 1.5);
  for (const HalfSpace& h : shrunk.halfspaces) EXPECT_DOUBLE_EQ(h.offset, 0.5);
  EXPECT_TRUE(grown.contains(Vec3(1.4, -1.4, 1.5)));  // in [-1.5, 1.5]^3
  EXPECT_FALSE(grown.contains(Vec3(1.6, 0, 0)));
  EXPECT_TRUE(shrunk.contains(Vec3(0.5, 0.5, 0.5)));  // [-.5, .5]^3
  EXPECT_FALSE(shrunk.contains(Vec3(0.6, 0, 0)));
}

TEST(Polyhedron, GrowingAComplementShrinksItsConvexPart) {
  // The complement of the cube grown by .25 is the complement of [-.75, .75]^3; shrunk, of [-1.25, 1.25]^3.
  Polyhedron outside = cube();
  outside.kind = Polyhedron::Kind::kComplement;
  const Polyhedron grown = outside.offset(0.25), shrunk = outside.offset(-0.25);
  EXPECT_TRUE(grown.contains(Vec3(0.8, 0, 0)));
  EXPECT_FALSE(grown.contains(Vec3(0.7, 0, 0)));
  EXPECT_TRUE(shrunk.contains(Vec3(1.3, 0, 0)));
  EXPECT_FALSE(shrunk.contains(Vec3(1.2, 0, 0)));
}

TEST(Polyhedron, HullOfCubeCornersIsTheCube) {
  // No rays: every candidate plane is valid and supports the hull, so their intersection is [0,1]^3. A zero
  // ray generates nothing and must change nothing.
  for (const std::vector<Vec3>& rays : {std::vector<Vec3>{}, std::vector<Vec3>{Vec3::Zero()}}) {
    const Polyhedron p = hull_plus_cone(unit_cube_corners(), rays);
    ASSERT_EQ(p.kind, Polyhedron::Kind::kConvex);
    EXPECT_TRUE(p.contains(Vec3(0.5, 0.5, 0.5)));
    EXPECT_TRUE(p.contains(Vec3(1, 0.5, 0.25)));  // on a facet
    EXPECT_TRUE(p.contains(Vec3(1, 1, 1)));
    EXPECT_FALSE(p.contains(Vec3(1.01, 0.5, 0.5)));
    EXPECT_FALSE(p.contains(Vec3(0.5, -0.01, 0.5)));
    EXPECT_FALSE(p.contains(Vec3(0.5, 0.5, 1.01)));
    for (const HalfSpace& h : p.halfspaces) EXPECT_NEAR(h.normal.norm(), 1, 1e-15);
  }
}

TEST(Polyhedron, PointPlusRaysIsTheGeneratedCone) {
  // Apex (1, 2, 3) and rays (±1, 0, 1), (0, ±1, 1): at height h above the apex the section is the diamond
  // |x| + |y| <= h (convex combinations of the four rays at z = 1).
  const Vec3 apex(1, 2, 3);
  const Polyhedron p = hull_plus_cone({apex}, {{1, 0, 1}, {-1, 0, 1}, {0, 1, 1}, {0, -1, 1}});
  ASSERT_EQ(p.kind, Polyhedron::Kind::kConvex);
  EXPECT_TRUE(p.contains(apex));
  EXPECT_TRUE(p.contains(apex + Vec3(0, 0, 10)));
  EXPECT_TRUE(p.contains(apex + Vec3(0.5, -0.5, 1)));  // on a facet
  EXPECT_TRUE(p.contains(apex + Vec3(2, 0, 2)));       // on an extreme ray
  EXPECT_FALSE(p.contains(apex + Vec3(0.6, 0.5, 1)));
  EXPECT_FALSE(p.contains(apex + Vec3(0.5, 0.5, 0.99)));
  EXPECT_FALSE(p.contains(apex + Vec3(0, 0, -0.01)));
}

TEST(Polyhedron, SegmentPlusOneRayIsAHalfStrip) {
  // Segment (0,0,0)-(1,0,0) swept along +z: {y = 0, 0 <= x <= 1, z >= 0}, bounded by the planes y = 0 (both
  // sides: x cross z), x = 0, x = 1 and z = 0 (single directions).
  const Polyhedron p = hull_plus_cone({{0, 0, 0}, {1, 0, 0}}, {{0, 0, 1}});
  ASSERT_EQ(p.kind, Polyhedron::Kind::kConvex);
  EXPECT_TRUE(p.contains(Vec3(0.5, 0, 3)));
  EXPECT_TRUE(p.contains(Vec3(0, 0, 0)));
  EXPECT_TRUE(p.contains(Vec3(1, 0, 100)));
  EXPECT_FALSE(p.contains(Vec3(0.5, 0.01, 3)));
  EXPECT_FALSE(p.contains(Vec3(0.5, -0.01, 3)));
  EXPECT_FALSE(p.contains(Vec3(1.01, 0, 1)));
  EXPECT_FALSE(p.contains(Vec3(-0.01, 0, 1)));
  EXPECT_FALSE(p.contains(Vec3(0.5, 0, -0.01)));
}

TEST(Polyhedron, RaysSpanningAllDirectionsGiveEverything) {
  // cone(±x, ±y, ±z) is all of R^3: every point is in the hull plus the cone.
  const Polyhedron p = hull_plus_cone({Vec3::Zero()}, {kX, Vec3(-kX), kY, Vec3(-kY), kZ, Vec3(-kZ)});
  for (const Vec3& q : {Vec3(100, -3, 7), Vec3(-1e6, 0, 0), Vec3(0, 0, -42)}) EXPECT_TRUE(p.contains(q));
}

TEST(Polyhedron, GrownHullContainsEveryPointWithinTheOffset) {
  // Soundness of offset(delta) for a weak region: P + ball(delta) lies in the grown set. Points at distance
  // .99 delta from the cube's corners, edge midpoints and facet centres, in many directions.
  const double delta = 0.1;
  const Polyhedron grown = hull_plus_cone(unit_cube_corners(), {}).offset(delta);
  std::vector<Vec3> anchors = unit_cube_corners();
  for (const Vec3& d : {kX, kY, kZ}) {
    anchors.push_back(Vec3(0.5, 0.5, 0.5) + 0.5 * d);
    anchors.push_back(Vec3(0.5, 0.5, 0.5) - 0.5 * d);
  }
  anchors.push_back(Vec3(0.5, 0, 0));
  anchors.push_back(Vec3(1, 1, 0.5));
  for (const Vec3& a : anchors)
    for (int i = -3; i <= 3; ++i)
      for (int j = -3; j <= 3; ++j)
        for (int k = -3; k <= 3; ++k) {
          const Vec3 d(i, j, k);
          if (d.norm() == 0) continue;
          EXPECT_TRUE(grown.contains(a + 0.99 * delta * d.normalized()))
              << a.transpose() << " " << d.transpose();
        }
  EXPECT_FALSE(grown.contains(Vec3(1.11, 0.5, 0.5)));  // beyond a facet by more than delta
}

}  // namespace
}  // namespace cmt

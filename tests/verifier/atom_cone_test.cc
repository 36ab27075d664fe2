// Atom friction cones (verifier/atom_cone.h) on a block in a room: atom_faces and atom_points of faces, edges
// and vertices; the face cone, the Minkowski sum at concave edges and corners (wedging limit derived by
// hand), coplanar faces counted once only when their cones agree; AtomCones against the per-atom builders.
#include "verifier/atom_cone.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "tests/verifier/test_geometry.h"

namespace cmt {
namespace {

const Vec3 kX = Vec3::UnitX(), kY = Vec3::UnitY(), kZ = Vec3::UnitZ();

using test::room;

// A 2 x 2 x 1 block [-1,1]^2 x [0,1] on the floor of the room [-4,4]^2 x [0,4], mu .25 everywhere.
std::shared_ptr<const LoadedTask> block_room() { return room("[{box: {min: [-1, -1, 0], max: [1, 1, 1]}}]"); }

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// Every point of `want` is in `got` and the sizes agree (order-free comparison of small point sets).
void expect_same_points(const std::vector<Vec3>& got, const std::vector<Vec3>& want) {
  ASSERT_EQ(got.size(), want.size());
  for (const Vec3& w : want)
    EXPECT_TRUE(std::any_of(got.begin(), got.end(), [&](const Vec3& g) { return (g - w).norm() < 1e-12; }))
        << w.transpose();
}

TEST(AtomCone, FaceAtomIsItsOwnFaceAndPolygon) {
  const auto t = block_room();
  const CSpace& c = t->cspace;
  const int top = test::face_at(c, kZ, Vec3(0, 0, 1));
  ASSERT_GE(top, 0);
  EXPECT_EQ(atom_faces(c, top), std::vector<int>{top});
  // The block's top is the square [-1,1]^2 at z = 1.
  expect_same_points(atom_points(c, top), {{-1, -1, 1}, {1, -1, 1}, {1, 1, 1}, {-1, 1, 1}});
}

TEST(AtomCone, EdgeAtomHasItsTwoFacesAndEndPoints) {
  const auto t = block_room();
  const CSpace& c = t->cspace;
  const int rim = test::edge_between(c, Vec3(1, -1, 1), Vec3(1, 1, 1));  // top meets side x = 1
  const int top = test::face_at(c, kZ, Vec3(0, 0, 1));
  const int side = test::face_at(c, kX, Vec3(1, 0, 0.5));
  ASSERT_GE(rim, 0);
  ASSERT_GE(top, 0);
  ASSERT_GE(side, 0);
  EXPECT_EQ(sorted(atom_faces(c, rim)), sorted({top, side}));
  expect_same_points(atom_points(c, rim), {{1, -1, 1}, {1, 1, 1}});
}

TEST(AtomCone, VertexAtomHasItsFacesAndItsPoint) {
  const auto t = block_room();
  const CSpace& c = t->cspace;
  const int corner = test::vertex_at(c, Vec3(1, 1, 1));  // top, side x = 1, side y = 1
  ASSERT_GE(corner, 0);
  const std::vector<int> want = {test::face_at(c, kZ, Vec3(0, 0, 1)), test::face_at(c, kX, Vec3(1, 0, 0.5)),
                                 test::face_at(c, kY, Vec3(0, 1, 0.5))};
  for (int f : want) ASSERT_GE(f, 0);
  EXPECT_EQ(sorted(atom_faces(c, corner)), sorted(want));
  expect_same_points(atom_points(c, corner), {{1, 1, 1}});
}

TEST(AtomCone, FaceConeIsCircularAboutTheOutwardNormal) {
  const auto t = block_room();
  const int top = test::face_at(t->cspace, kZ, Vec3(0, 0, 1));
  ASSERT_GE(top, 0);
  const FrictionCone cone = atom_friction_cone(t->cspace, top);
  ASSERT_TRUE(cone.circular());
  EXPECT_NEAR((cone.generators()[0].axis - kZ).norm(), 0, 1e-15);
  EXPECT_NEAR(cone.generators()[0].half_angle, std::atan(0.25), 1e-15);  // .2450
  // Reaction directions .2 and .3 from +z: inside and outside; the face's signed angle is exact.
  const Vec3 in(std::sin(0.2), 0, std::cos(0.2)), out(0, std::sin(0.3), std::cos(0.3));
  EXPECT_EQ(cone.classify(in), ConeMembership::kInside);
  EXPECT_EQ(cone.classify(out), ConeMembership::kOutside);
  EXPECT_NEAR(cone.signed_angle(in), 0.2 - std::atan(0.25), 1e-12);
  EXPECT_NEAR(cone.signed_angle(out), 0.3 - std::atan(0.25), 1e-12);
}

TEST(AtomCone, ConcaveEdgeConeIsTheSumOfItsFaceConesWithWedging) {
  // The room's floor (+z) meets the wall x = -4 (+x). In the sum a + b, a in cone(z, phi), b in cone(x, phi),
  // the direction (1, y, 1) is reached up to y = max 2 mu cos s / (1 − mu sin s) = 2 mu / sqrt(1 − mu^2) =
  // .5164 (at sin s = mu), beyond the kinetic .5 of either cone alone.
  const auto t = block_room();
  const CSpace& c = t->cspace;
  const int corner = test::edge_between(c, Vec3(-4, -4, 0), Vec3(-4, 4, 0));
  ASSERT_GE(corner, 0);
  const FrictionCone cone = atom_friction_cone(c, corner);
  ASSERT_EQ(cone.generators().size(), 2u);
  for (const CircularCone& g : cone.generators()) {
    EXPECT_NEAR(g.half_angle, std::atan(0.25), 1e-15);
    EXPECT_TRUE((g.axis - kX).norm() < 1e-15 || (g.axis - kZ).norm() < 1e-15) << g.axis.transpose();
  }
  EXPECT_EQ(cone.classify(Vec3(1, 0, 1)), ConeMembership::kInside);
  EXPECT_EQ(cone.classify(Vec3(1, 0.45, 1)), ConeMembership::kInside);
  EXPECT_EQ(cone.classify(Vec3(1, -0.45, 1)), ConeMembership::kInside);
  EXPECT_EQ(cone.classify(Vec3(1, 0.6, 1)), ConeMembership::kOutside);
  EXPECT_EQ(cone.classify(kY), ConeMembership::kOutside);  // along the edge: no normal force to hold it
  EXPECT_EQ(cone.classify(-kZ), ConeMembership::kOutside);
}

TEST(AtomCone, CornerConeIsTheSumOfThreeFaceCones) {
  const auto t = block_room();
  const int v = test::vertex_at(t->cspace, Vec3(-4, -4, 0));  // walls +x, +y, floor +z
  ASSERT_GE(v, 0);
  const FrictionCone cone = atom_friction_cone(t->cspace, v);
  EXPECT_EQ(cone.generators().size(), 3u);
  EXPECT_EQ(cone.classify(Vec3(1, 1, 1)), ConeMembership::kInside);
  EXPECT_EQ(cone.classify(kZ), ConeMembership::kInside);
  // (−1, 1, 1) is outside: w = (−1, −.3, −.3) has w . d > 0, yet w is at least pi/2 + phi from each axis
  // (cos(w, x) = −.92, cos(w, y) = cos(w, z) = −.276 <= −sin phi = −.2425), so w . c <= 0 on every cone.
  EXPECT_EQ(cone.classify(Vec3(-1, 1, 1)), ConeMembership::kOutside);
  EXPECT_FALSE(cone.is_full(/*outer=*/true));
}

TEST(AtomCone, FlatEdgeWithEqualFrictionContributesOneCone) {
  // Around the block the floor is cut into convex pieces; the cut x = -1, y in [-4, -1] is a flat edge
  // between two pieces with the same normal and mu: one circular cone, not two copies.
  const auto t = block_room();
  const CSpace& c = t->cspace;
  const int cut = test::edge_between(c, Vec3(-1, -4, 0), Vec3(-1, -1, 0));
  ASSERT_GE(cut, 0);
  ASSERT_EQ(c.edges()[c.atom_index(cut)].shape, EdgeShape::kFlat);
  EXPECT_EQ(atom_faces(c, cut).size(), 2u);
  const FrictionCone cone = atom_friction_cone(c, cut);
  EXPECT_TRUE(cone.circular());
  EXPECT_NEAR(cone.generators()[0].half_angle, std::atan(0.25), 1e-15);
}

TEST(AtomCone, FlatEdgeWithDifferentFrictionKeepsBothCones) {
  // Tops of two blocks at z = 1, mu .2 (x < 0) and .5 (x > 0), meet at x = 0: both cones (atan .2 = .1974,
  // atan .5 = .4636) about +z; their sum is the wider one: .4 from +z is inside, .5 outside.
  const auto t = room(
      "[{box: {min: [-2, -2, 0], max: [0, 2, 1], friction: 0.2}}, "
      "{box: {min: [0, -2, 0], max: [2, 2, 1], friction: 0.5}}]");
  const CSpace& c = t->cspace;
  const int seam = test::edge_between(c, Vec3(0, -2, 1), Vec3(0, 2, 1));
  ASSERT_GE(seam, 0);
  const FrictionCone cone = atom_friction_cone(c, seam);
  ASSERT_EQ(cone.generators().size(), 2u);
  std::vector<double> halves = {cone.generators()[0].half_angle, cone.generators()[1].half_angle};
  std::sort(halves.begin(), halves.end());
  EXPECT_NEAR(halves[0], std::atan(0.2), 1e-15);
  EXPECT_NEAR(halves[1], std::atan(0.5), 1e-15);
  EXPECT_EQ(cone.classify(Vec3(std::sin(0.4), 0, std::cos(0.4))), ConeMembership::kInside);
  EXPECT_EQ(cone.classify(Vec3(std::sin(0.5), 0, std::cos(0.5))), ConeMembership::kOutside);
}

TEST(AtomCone, AtomConesHoldEveryAtomsConeAndUniqueStickSet) {
  const auto t = block_room();
  const CSpace& c = t->cspace;
  const AtomCones cones(c);
  ASSERT_EQ(cones.size(), c.atom_count());
  for (int id = 0; id < c.atom_count(); ++id) {
    const FrictionCone direct = atom_friction_cone(c, id);
    ASSERT_EQ(cones[id].generators().size(), direct.generators().size()) << c.atom_name(id);
    for (std::size_t k = 0; k < direct.generators().size(); ++k) {
      EXPECT_EQ(cones[id].generators()[k].axis, direct.generators()[k].axis) << c.atom_name(id);
      EXPECT_EQ(cones[id].generators()[k].half_angle, direct.generators()[k].half_angle) << c.atom_name(id);
    }
  }
  // The unique-stick sets are the atoms' own: a face's margin straight in is phi; at the room's floor/wall
  // edge the bisector is asin(1/3) from the kinetic facet (unique_stick_test.cc derives both).
  const int floor_piece = test::face_at(c, kZ, Vec3(-3, 0, 0));
  const int corner = test::edge_between(c, Vec3(-4, -4, 0), Vec3(-4, 4, 0));
  ASSERT_GE(floor_piece, 0);
  ASSERT_GE(corner, 0);
  EXPECT_NEAR(cones.unique(floor_piece).margin(-kZ), std::atan(0.25), 1e-12);
  EXPECT_NEAR(cones.unique(corner).margin(-Vec3(1, 0, 1)), std::asin(1.0 / 3), 1e-12);
}

}  // namespace
}  // namespace cmt

// UniqueStick (verifier/unique_stick.h): the force directions for which sticking is the only Coulomb
// solution. Margins and must-cones of faces, perpendicular concave edges (kinetic cone |t| <= mu1 N1 + mu2 N2
// or a face cone where the other wall separates), concave box corners and the intersection kind, derived by
// hand; the soundness side checked against a Coulomb predicate; for_atom's choice of kind on loaded scenes.
#include "verifier/unique_stick.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "tests/verifier/test_geometry.h"

namespace cmt {
namespace {

using std::numbers::pi;

const Vec3 kX = Vec3::UnitX(), kY = Vec3::UnitY(), kZ = Vec3::UnitZ();

double angle_between(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

// A unit vector at polar angle `polar` from −z, azimuth 0 (toward +x).
Vec3 from_down(double polar) { return Vec3(std::sin(polar), 0, -std::cos(polar)); }

// Unit directions on a polar/azimuth grid over the whole sphere (poles included).
std::vector<Vec3> sphere_grid(int polar_steps, int azimuth_steps) {
  std::vector<Vec3> out;
  for (int i = 0; i <= polar_steps; ++i) {
    const double p = pi * i / polar_steps;
    for (int j = 0; j < azimuth_steps; ++j) {
      const double a = 2 * pi * j / azimuth_steps + 0.0123;  // off the axes' exact symmetry planes
      out.push_back(Vec3(std::sin(p) * std::cos(a), std::sin(p) * std::sin(a), std::cos(p)));
    }
  }
  return out;
}

// Directions at angle r from unit f, at `count` azimuths around it.
std::vector<Vec3> ring(const Vec3& f, double r, int count) {
  const Vec3 u = f.unitOrthogonal(), w = f.cross(u);
  std::vector<Vec3> out;
  for (int k = 0; k < count; ++k) {
    const double a = 2 * pi * k / count;
    out.push_back(std::cos(r) * f + std::sin(r) * (std::cos(a) * u + std::sin(a) * w));
  }
  return out;
}

// Coulomb, written from the header: at the concave edge of the floor n1 = +z (mu1) and the wall n2 = +x
// (mu2), e = n1 x n2 = +y, f = −N1 n1 − N2 n2 + t e sticks uniquely iff both faces are pressed and the
// friction of both can hold the edge component (N1, N2 >= 0, |t| <= mu1 N1 + mu2 N2), or one face separates
// and f is inside the other face's own cone.
bool edge_sticks_uniquely(const Vec3& f, double mu1, double mu2) {
  const Vec3 d = f.normalized();
  const double N1 = -d.z(), N2 = -d.x(), t = d.y();
  if (N1 >= 0 && N2 >= 0 && std::abs(t) <= mu1 * N1 + mu2 * N2) return true;
  if (N2 <= 0 && angle_between(d, -kZ) <= std::atan(mu1)) return true;
  return N1 <= 0 && angle_between(d, -kX) <= std::atan(mu2);
}

// At a concave box corner with normals +x, +y, +z: pressing into all three faces (no face can separate, every
// motion that keeps contact is blocked).
bool corner_pressed(const Vec3& f) { return f.x() <= 0 && f.y() <= 0 && f.z() <= 0; }

bool in_all(const std::vector<CircularCone>& cones, const Vec3& d) {
  for (const CircularCone& c : cones)
    if (angle_between(d, c.axis) > c.half_angle) return false;
  return true;
}

void expect_cone(const CircularCone& c, const Vec3& axis, double half) {
  EXPECT_NEAR((c.axis - axis.normalized()).norm(), 0, 1e-12) << c.axis.transpose();
  EXPECT_NEAR(c.half_angle, half, 1e-12);
}

// ---- faces and the intersection kind ----

TEST(UniqueStick, FaceMarginIsTheAngleToTheFrictionConeRim) {
  const double phi = std::atan(0.25);  // .2450
  const UniqueStick floor = UniqueStick::face(kZ, 0.25);
  EXPECT_NEAR(floor.margin(-kZ), phi, 1e-12);                   // straight into the floor: phi from the rim
  EXPECT_NEAR(floor.margin(from_down(0.1)), phi - 0.1, 1e-12);  // .1 off the inward normal
  EXPECT_NEAR(floor.margin(kX), phi - pi / 2, 1e-12);           // tangential: pi/2 from the inward normal
  EXPECT_NEAR(floor.margin(kZ), phi - pi, 1e-12);               // pulling straight off
  // Neither the force's length nor the given normal's length matters (both are normalized).
  EXPECT_NEAR(UniqueStick::face(2 * kZ, 0.25).margin(-5 * kZ), phi, 1e-12);
}

TEST(UniqueStick, FrictionlessFaceHasNoPositiveMargin) {
  // mu = 0: the cone is the inward normal alone, so no direction error at all can be tolerated.
  const UniqueStick slick = UniqueStick::face(kZ, 0.0);
  EXPECT_EQ(slick.margin(-kZ), 0.0);
  EXPECT_NEAR(slick.margin(from_down(0.01)), -0.01, 1e-12);
  EXPECT_TRUE(slick.must_cones(0.0).empty());  // half-angle 0 - 0 leaves nothing
}

TEST(UniqueStick, IntersectionMarginIsTheSmallestFaceMargin) {
  // Faces +z (mu .25, phi .2450) and n2 tilted .1 from +z toward +x (mu .5, phi .4636): the margin is the
  // smaller of phi_i − angle(f, −n_i).
  const Vec3 n2(std::sin(0.1), 0, std::cos(0.1));
  const UniqueStick u = UniqueStick::intersection({kZ, n2}, {0.25, 0.5});
  EXPECT_NEAR(u.margin(-kZ), std::atan(0.25), 1e-12);        // min(.2450, .4636 − .1)
  EXPECT_NEAR(u.margin(-n2), std::atan(0.25) - 0.1, 1e-12);  // min(.2450 − .1, .4636)
  EXPECT_NEAR(u.margin(from_down(0.05)), std::atan(0.25) - 0.05,
              1e-12);  // min(.1950, .4636 − .15: −n2 leans to −x)
  // A convex edge (faces +z and +x): the diagonal push is pi/4 from either inward normal, outside both cones.
  const UniqueStick rim = UniqueStick::intersection({kZ, kX}, {0.25, 0.25});
  EXPECT_NEAR(rim.margin(-(kX + kZ)), std::atan(0.25) - pi / 4, 1e-12);
}

TEST(UniqueStick, FaceMustConeIsTheFrictionConeNarrowedByTheError) {
  const double phi = std::atan(0.25);
  const UniqueStick floor = UniqueStick::face(kZ, 0.25);
  auto cones = floor.must_cones(0.1);
  ASSERT_EQ(cones.size(), 1u);
  ASSERT_EQ(cones[0].size(), 1u);
  expect_cone(cones[0][0], -kZ, phi - 0.1);
  cones = floor.must_cones(0.0);
  ASSERT_EQ(cones.size(), 1u);
  ASSERT_EQ(cones[0].size(), 1u);
  expect_cone(cones[0][0], -kZ, phi);
  // An error of .25 > phi = .2450 can always tip the force out of the cone: nothing must stick.
  EXPECT_TRUE(floor.must_cones(0.25).empty());
}

TEST(UniqueStick, IntersectionMustConesAreLeftOutWhenTheConesAreDisjoint) {
  // Convex edge +z / +x, mu .25: the narrowed cones about −z and −x (half-angles <= .2450) are pi/2 apart and
  // meet only at the apex, so no direction sticks uniquely.
  EXPECT_TRUE(UniqueStick::intersection({kZ, kX}, {0.25, 0.25}).must_cones(0.0).empty());
  // Normals .1 apart (mu .25 and .5), error .05: cones (−z, .1950) and (−n2, .4136) overlap (.1 < .6086).
  const Vec3 n2(std::sin(0.1), 0, std::cos(0.1));
  const auto cones = UniqueStick::intersection({kZ, n2}, {0.25, 0.5}).must_cones(0.05);
  ASSERT_EQ(cones.size(), 1u);
  ASSERT_EQ(cones[0].size(), 2u);
  expect_cone(cones[0][0], -kZ, std::atan(0.25) - 0.05);
  expect_cone(cones[0][1], -n2, std::atan(0.5) - 0.05);
}

// ---- perpendicular concave edges ----

TEST(UniqueStick, ConcaveEdgeBisectorMarginIsTheKineticFacetAngle) {
  // Floor +z, wall +x, mu .25, e = +y. The kinetic facet t = mu (N1 + N2) is the plane through (0, .25, −1)
  // and (−1, .25, 0); its normal is (.25, 1, .25) (length sqrt 1.125). The bisector (−1, 0, −1)/sqrt 2 is at
  // asin(.5 / sqrt 2 / sqrt 1.125) = asin(1/3) = .3398 from it (docs/verifier.md quotes .3398), nearer than
  // either rim (pi/4 − .2450 = .5404).
  const UniqueStick edge = UniqueStick::concave_edge(kZ, 0.25, kX, 0.25);
  EXPECT_NEAR(edge.margin(-(kX + kZ)), std::asin(1.0 / 3), 1e-12);
}

TEST(UniqueStick, ConcaveEdgePushIntoTheFloorIsBoundedByTheKineticFacet) {
  // −z: N1 = 1, N2 = 0, t = 0 is in the kinetic cone. Candidates: the floor rim phi = .2450, the wall rim
  // pi/2 − phi, and the facet planes with normals (±.25, 1, ±.25)/sqrt 1.125 at asin(.25 / sqrt 1.125) =
  // .2379 (the value docs/verifier.md quotes). A lower bound: pulling off the wall the true limit is the rim
  // .2450.
  const UniqueStick edge = UniqueStick::concave_edge(kZ, 0.25, kX, 0.25);
  EXPECT_NEAR(edge.margin(-kZ), std::asin(0.25 / std::sqrt(1.125)), 1e-12);
  EXPECT_LT(edge.margin(-kZ), std::atan(0.25));
}

TEST(UniqueStick, ConcaveEdgeBeyondTheKineticLimitIsNotUniqueStick) {
  const UniqueStick edge = UniqueStick::concave_edge(kZ, 0.25, kX, 0.25);
  // f = −(1, y, 1): N1 = N2 = 1, |t| = |y|, kinetic limit mu (N1 + N2) = .5. Past it (but inside the summed
  // cone's wedging limit .5164) sticking and sliding are both Coulomb solutions: margin 0.
  EXPECT_EQ(edge.margin(-Vec3(1, 0.51, 1)), 0.0);
  EXPECT_EQ(edge.margin(-Vec3(1, -0.51, 1)), 0.0);
  // Just inside: the facet for t < 0 has normal (−.25, 1, −.25); its dot with (−1, −.49, −1) is .01, so the
  // margin is asin(.01 / (sqrt 1.125 sqrt 2.2401)) = .0063 (the other facet and the rims are farther).
  EXPECT_NEAR(edge.margin(-Vec3(1, 0.49, 1)), std::asin(0.01 / (std::sqrt(1.125) * std::sqrt(2.2401))),
              1e-12);
  // Along the edge: neither face pressed, the edge direction outside both face cones.
  EXPECT_EQ(edge.margin(kY), 0.0);
  EXPECT_EQ(edge.margin(-kY), 0.0);
}

TEST(UniqueStick, ConcaveEdgeKeepsTheFloorConeWhereTheWallSeparates) {
  const UniqueStick edge = UniqueStick::concave_edge(kZ, 0.25, kX, 0.25);
  // (.1, 0, −1): pulls off the wall (N2 = −.1) and is atan .1 = .0997 inside the floor's cone: the floor rim
  // is atan .25 − atan .1 = .1453 away (facets: asin(.225 / (sqrt 1.01 sqrt 1.125)) = .2127; wall
  // rim 1.4255).
  EXPECT_NEAR(edge.margin(Vec3(0.1, 0, -1)), std::atan(0.25) - std::atan(0.1), 1e-12);
  // (.3, 0, −1): off the wall and atan .3 = .2915 > .2450 from the floor normal: it slides on the floor.
  EXPECT_EQ(edge.margin(Vec3(0.3, 0, -1)), 0.0);
  // The same by symmetry on the wall: (−1, 0, .1) pulls off the floor, inside the wall's cone.
  EXPECT_NEAR(edge.margin(Vec3(-1, 0, 0.1)), std::atan(0.25) - std::atan(0.1), 1e-12);
}

TEST(UniqueStick, ConcaveEdgeMarginIsALowerBoundOnTheAngleToTheBoundary) {
  // Soundness: every direction within the margin of f sticks uniquely (by the Coulomb predicate above), and a
  // direction outside the set has margin <= 0. Unequal coefficients so that mu1 and mu2 are not mixed up.
  for (const auto& [mu1, mu2] : {std::pair{0.25, 0.25}, std::pair{0.25, 0.6}, std::pair{0.8, 0.1}}) {
    const UniqueStick edge = UniqueStick::concave_edge(kZ, mu1, kX, mu2);
    int checked = 0;
    for (const Vec3& f : sphere_grid(36, 48)) {
      const double m = edge.margin(f);
      if (!edge_sticks_uniquely(f, mu1, mu2)) {
        EXPECT_LE(m, 0.0) << f.transpose() << " mu " << mu1 << " " << mu2;
        continue;
      }
      if (m < 1e-6) continue;  // no claim worth testing against rounding
      ++checked;
      for (double r : {0.5 * m, 0.999 * m})
        for (const Vec3& d : ring(f, r, 24))
          EXPECT_TRUE(edge_sticks_uniquely(d, mu1, mu2))
              << "f " << f.transpose() << " margin " << m << " d " << d.transpose();
    }
    EXPECT_GT(checked, 20);  // the grid really reaches into the set
  }
}

TEST(UniqueStick, ConcaveEdgeMustConesAreTheKineticWedgeOrAFaceCone) {
  const double phi = std::atan(0.25);
  const UniqueStick edge = UniqueStick::concave_edge(kZ, 0.25, kX, 0.25);
  // Error .1: the wedge's four planes f . w <= 0, w in {n1, n2, e + mu(n1 + n2), mu(n1 + n2) − e}, each as
  // cone(−w, pi/2 − .1); then each face's cone narrowed to phi − .1.
  auto cones = edge.must_cones(0.1);
  ASSERT_EQ(cones.size(), 3u);
  ASSERT_EQ(cones[0].size(), 4u);
  expect_cone(cones[0][0], -kZ, pi / 2 - 0.1);
  expect_cone(cones[0][1], -kX, pi / 2 - 0.1);
  expect_cone(cones[0][2], -Vec3(0.25, 1, 0.25), pi / 2 - 0.1);
  expect_cone(cones[0][3], -Vec3(0.25, -1, 0.25), pi / 2 - 0.1);
  ASSERT_EQ(cones[1].size(), 1u);
  expect_cone(cones[1][0], -kZ, phi - 0.1);
  ASSERT_EQ(cones[2].size(), 1u);
  expect_cone(cones[2][0], -kX, phi - 0.1);
  // Error .3 > phi: only the wedge is left.
  cones = edge.must_cones(0.3);
  ASSERT_EQ(cones.size(), 1u);
  EXPECT_EQ(cones[0].size(), 4u);
  // The two ±e facets' axes are acos(−.875 / 1.125) = pi − 2 asin(1/3) apart, so their cones narrowed to
  // pi/2 − theta stop meeting at theta = asin(1/3) = .3398, the bisector's margin.
  EXPECT_EQ(edge.must_cones(0.33).size(), 1u);
  EXPECT_TRUE(edge.must_cones(0.35).empty());
}

TEST(UniqueStick, ConcaveEdgeMustConesKeepStickingUniqueUnderTheError) {
  // Soundness of must_cones: a direction in every cone of some alternative, turned by up to theta in any
  // direction, still sticks uniquely.
  const double mu1 = 0.25, mu2 = 0.4, theta = 0.1;
  const auto alternatives = UniqueStick::concave_edge(kZ, mu1, kX, mu2).must_cones(theta);
  ASSERT_EQ(alternatives.size(), 3u);
  std::vector<int> hits(alternatives.size(), 0);
  for (const Vec3& d : sphere_grid(60, 72))
    for (std::size_t k = 0; k < alternatives.size(); ++k) {
      if (!in_all(alternatives[k], d)) continue;
      ++hits[k];
      for (double r : {0.5 * theta, theta})
        for (const Vec3& q : ring(d, r, 16))
          EXPECT_TRUE(edge_sticks_uniquely(q, mu1, mu2)) << "alternative " << k << " d " << d.transpose();
    }
  for (std::size_t k = 0; k < alternatives.size(); ++k) EXPECT_GT(hits[k], 0) << k;
}

// ---- concave box corners ----

TEST(UniqueStick, CornerMarginIsTheAngleToTheNearestFacePlane) {
  const UniqueStick corner = UniqueStick::corner(kX, kY, kZ, {0.25, 0.25, 0.25});
  // Into the corner along the diagonal: asin(1/sqrt 3) = .6155 from each coordinate plane.
  EXPECT_NEAR(corner.margin(-Vec3(1, 1, 1)), std::asin(1 / std::sqrt(3.0)), 1e-12);
  // −(1, 2, 3)/sqrt 14 is nearest the plane x = 0: asin(1 / sqrt 14).
  EXPECT_NEAR(corner.margin(-Vec3(1, 2, 3)), std::asin(1 / std::sqrt(14.0)), 1e-12);
  // Pulling away from the face x: not pressing all three.
  EXPECT_EQ(corner.margin(Vec3(1, -1, -1)), 0.0);
  // −x presses one face only (on the planes y = 0 and z = 0): no margin in the pressing set.
  EXPECT_EQ(corner.margin(-kX), 0.0);
}

TEST(UniqueStick, CornerMarginIsALowerBoundOnTheAngleToThePressingSet) {
  const UniqueStick corner = UniqueStick::corner(kX, kY, kZ, {0.25, 0.25, 0.25});
  int checked = 0;
  for (const Vec3& f : sphere_grid(36, 48)) {
    const double m = corner.margin(f);
    if (!corner_pressed(f)) {
      EXPECT_LE(m, 0.0) << f.transpose();
      continue;
    }
    if (m < 1e-6) continue;
    ++checked;
    for (double r : {0.5 * m, 0.999 * m})
      for (const Vec3& d : ring(f, r, 24)) EXPECT_TRUE(corner_pressed(d)) << f.transpose() << " " << m;
  }
  EXPECT_GT(checked, 20);
}

TEST(UniqueStick, CornerMustConesArePressingAllThreeOrOneFacesCone) {
  const double phi = std::atan(0.25);
  auto cones = UniqueStick::corner(kX, kY, kZ, {0.25, 0.25, 0.25}).must_cones(0.1);
  // Pressing into all three by at least .1: cone(−n_k, pi/2 − .1) each; then each face's narrowed cone.
  ASSERT_EQ(cones.size(), 4u);
  ASSERT_EQ(cones[0].size(), 3u);
  expect_cone(cones[0][0], -kX, pi / 2 - 0.1);
  expect_cone(cones[0][1], -kY, pi / 2 - 0.1);
  expect_cone(cones[0][2], -kZ, pi / 2 - 0.1);
  for (int k = 0; k < 3; ++k) {
    ASSERT_EQ(cones[k + 1].size(), 1u);
    expect_cone(cones[k + 1][0], -Vec3::Unit(k), phi - 0.1);
  }
  // Without coefficients only the pressing alternative exists; an error of pi/2 leaves nothing.
  cones = UniqueStick::corner(kX, kY, kZ).must_cones(0.1);
  ASSERT_EQ(cones.size(), 1u);
  EXPECT_EQ(cones[0].size(), 3u);
  EXPECT_TRUE(UniqueStick::corner(kX, kY, kZ).must_cones(pi / 2).empty());
}

// ---- for_atom on loaded scenes ----

std::shared_ptr<const LoadedTask> room(double friction, const std::string& obstacles) {
  return load_task_from_string(
      "name: t\nunits: in\nfriction: " + std::to_string(friction) +
          "\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: 0.1}\ncspace: " + obstacles +
          "\nbounds: {min: [-4, -4, 0], max: [4, 4, 4]}\n"
          "start: {point: [0, 0, 4]}\ngoal: {point: [0, 0, 4]}\nmotions:\n  m: {damper: [0, 0, -1]}\n"
          "strategies:\n  s: [m]\n",
      "test");
}

// A 2 x 2 x 1 block [-1,1]^2 x [0,1] on the floor of the room [-4,4]^2 x [0,4], mu .25.
std::shared_ptr<const LoadedTask> block_room() {
  return room(0.25, "[{box: {min: [-1, -1, 0], max: [1, 1, 1]}}]");
}

TEST(UniqueStick, ForAtomUsesTheFaceConeOnAFaceAndTheKineticConeAtAConcaveEdge) {
  const auto t = block_room();
  const CSpace& c = t->cspace;
  const int top = test::face_at(c, kZ, Vec3(0, 0, 1));
  ASSERT_GE(top, 0);
  EXPECT_NEAR(UniqueStick::for_atom(c, top).margin(-kZ), std::atan(0.25), 1e-12);
  // The floor meets the block's side x = −1 (normal −x) in a perpendicular concave edge: the push into it,
  // (1, 0, −1), is the bisector case above mirrored: asin(1/3).
  const int foot = test::edge_between(c, Vec3(-1, -1, 0), Vec3(-1, 1, 0));
  ASSERT_GE(foot, 0);
  ASSERT_EQ(c.edges()[c.atom_index(foot)].shape, EdgeShape::kConcave);
  EXPECT_NEAR(UniqueStick::for_atom(c, foot).margin(Vec3(1, 0, -1)), std::asin(1.0 / 3), 1e-12);
}

TEST(UniqueStick, ForAtomTreatsAConcaveRoomCornerAsABoxCorner) {
  const auto t = block_room();
  const int v = test::vertex_at(t->cspace, Vec3(-4, -4, 0));  // walls +x, +y and the floor +z
  ASSERT_GE(v, 0);
  EXPECT_NEAR(UniqueStick::for_atom(t->cspace, v).margin(-Vec3(1, 1, 1)), std::asin(1 / std::sqrt(3.0)),
              1e-12);
}

TEST(UniqueStick, ForAtomUsesEveryFacesConeAtConvexEdgesAndCorners) {
  const auto t = block_room();
  const CSpace& c = t->cspace;
  const double phi = std::atan(0.25);
  // The block's top rim x = 1: a diagonal push is pi/4 from both inward normals, outside both cones (a box
  // corner's kind would have called it safe).
  const int rim = test::edge_between(c, Vec3(1, -1, 1), Vec3(1, 1, 1));
  ASSERT_GE(rim, 0);
  EXPECT_NEAR(UniqueStick::for_atom(c, rim).margin(-Vec3(1, 0, 1)), phi - pi / 4, 1e-12);
  // The block's top corner (1, 1, 1): three perpendicular faces, but convex: the diagonal push is
  // acos(1/sqrt 3) = .9553 from each inward normal.
  const int top_corner = test::vertex_at(c, Vec3(1, 1, 1));
  ASSERT_GE(top_corner, 0);
  EXPECT_NEAR(UniqueStick::for_atom(c, top_corner).margin(-Vec3(1, 1, 1)),
              phi - std::acos(1 / std::sqrt(3.0)), 1e-12);
  // The foot of the block's vertical edge (−1, −1, 0): floor, sides −x and −y, mutually perpendicular, but
  // the sides meet in a convex edge: pushing (1, 1, −1) into all three is not a box corner either.
  const int foot_corner = test::vertex_at(c, Vec3(-1, -1, 0));
  ASSERT_GE(foot_corner, 0);
  EXPECT_NEAR(UniqueStick::for_atom(c, foot_corner).margin(Vec3(1, 1, -1)),
              phi - std::acos(1 / std::sqrt(3.0)), 1e-12);
}

TEST(UniqueStick, ForAtomFlatEdgeTakesTheSmallerFriction) {
  // Two blocks side by side, tops coplanar at z = 1, mu .2 (x < 0) and .5 (x > 0): their tops meet in a flat
  // edge at x = 0, which sticks uniquely only inside the smaller cone atan .2 = .1974.
  const auto t = room(0.25,
                      "[{box: {min: [-2, -2, 0], max: [0, 2, 1], friction: 0.2}}, "
                      "{box: {min: [0, -2, 0], max: [2, 2, 1], friction: 0.5}}]");
  const CSpace& c = t->cspace;
  const int seam = test::edge_between(c, Vec3(0, -2, 1), Vec3(0, 2, 1));
  ASSERT_GE(seam, 0);
  ASSERT_EQ(c.edges()[c.atom_index(seam)].shape, EdgeShape::kFlat);
  const UniqueStick u = UniqueStick::for_atom(c, seam);
  EXPECT_NEAR(u.margin(-kZ), std::atan(0.2), 1e-12);
  EXPECT_NEAR(u.margin(from_down(0.3)), std::atan(0.2) - 0.3, 1e-12);  // < 0 though .3 < atan .5
}

TEST(UniqueStick, ForAtomNonPerpendicularConcaveEdgeIsTheIntersectionOfFaceCones) {
  // A 45-degree ramp rising from x = 0 (the slope z = x, normal (−1, 0, 1)/sqrt 2) on the floor, mu 1
  // (phi = pi/4). The bisector of the two inward normals is pi/8 from each: margin pi/4 − pi/8 = pi/8.
  const auto t = room(1.0, "[{convex: {vertices: [[0,-4,0],[2,-4,0],[2,-4,2],[0,4,0],[2,4,0],[2,4,2]]}}]");
  const CSpace& c = t->cspace;
  const int toe = test::edge_between(c, Vec3(0, -4, 0), Vec3(0, 4, 0));
  ASSERT_GE(toe, 0);
  ASSERT_EQ(c.edges()[c.atom_index(toe)].shape, EdgeShape::kConcave);
  const Vec3 slope = Vec3(-1, 0, 1).normalized();
  const UniqueStick u = UniqueStick::for_atom(c, toe);
  EXPECT_NEAR(u.margin(-(kZ + slope)), pi / 8, 1e-12);
  // must_cones(.1): one alternative, both face cones narrowed to pi/4 − .1 (axes pi/4 apart: they overlap).
  const auto cones = u.must_cones(0.1);
  ASSERT_EQ(cones.size(), 1u);
  ASSERT_EQ(cones[0].size(), 2u);
  for (const CircularCone& cone : cones[0]) EXPECT_NEAR(cone.half_angle, pi / 4 - 0.1, 1e-12);
}

}  // namespace
}  // namespace cmt

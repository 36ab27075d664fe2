// Hand-worked cases for the damper's stick/slide analysis (Buckley §3.2, §4.3.5). Expected values are derived
// in the comments from the cone geometry, not taken from the program.
#include "verifier/damper.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "verifier/unique_stick.h"

namespace cmt {
namespace {

const Vec3 kUp = Vec3::UnitZ();

// A unit vector at polar angle `polar` from −z, azimuth 0 (toward +x).
Vec3 from_down(double polar) { return Vec3(std::sin(polar), 0, -std::cos(polar)); }

// A face: the friction cone and the unique-stick set are the same circular cone.
StickClass classify_face(const Vec3& n, double mu, const Vec3& v, double theta_v) {
  return classify_damper(FrictionCone::face(n, mu), UniqueStick::face(n, mu), v, theta_v);
}

TEST(DamperStick, FaceCone) {
  const double mu = 0.25, phi = std::atan(mu);  // .2450
  auto classify = [&](const Vec3& v, double theta_v) { return classify_face(kUp, mu, v, theta_v); };
  // Straight down: must stick while theta_v < phi, may when the velocity cone pokes out.
  EXPECT_EQ(classify(-kUp, 0.0), StickClass::kMust);
  EXPECT_EQ(classify(-kUp, 0.1), StickClass::kMust);
  EXPECT_EQ(classify(-kUp, 0.25), StickClass::kMay);
  // At alpha from the inward normal: must iff alpha + theta_v < phi, never iff alpha − theta_v > phi.
  EXPECT_EQ(classify(from_down(0.5 * phi), 0.0), StickClass::kMust);
  EXPECT_EQ(classify(from_down(1.05 * phi), 0.0), StickClass::kNever);
  EXPECT_EQ(classify(from_down(phi + 0.2), 0.25), StickClass::kMay);
  EXPECT_EQ(classify(from_down(phi + 0.3), 0.25), StickClass::kNever);
  // Pulling away never sticks.
  EXPECT_EQ(classify(kUp, 0.25), StickClass::kNever);
}

TEST(DamperStick, FrictionlessAndLargeFriction) {
  // mu = 0: only the exact normal push is in the cone (a ray): never "must", may on the normal, never off it.
  EXPECT_EQ(classify_face(kUp, 0.0, -kUp, 0.0), StickClass::kMay);
  EXPECT_EQ(classify_face(kUp, 0.0, from_down(0.01), 0.0), StickClass::kNever);
  EXPECT_EQ(classify_face(kUp, 0.0, from_down(0.01), 0.02), StickClass::kMay);
  // mu = 10: phi = 1.4711; alpha = 1.2 with theta_v = .25 stays inside (1.45 < 1.4711).
  EXPECT_EQ(classify_face(kUp, 10.0, from_down(1.2), 0.25), StickClass::kMust);
  EXPECT_EQ(classify_face(kUp, 10.0, from_down(1.3), 0.25), StickClass::kMay);
}

TEST(DamperStick, ConcaveEdgeStickIsDecidedByTheKineticCone) {
  // Faces with normals +z and +x (a concave edge along y), mu = .25. Sticking is possible in the summed cone,
  // but it is the only Coulomb solution only in the kinetic cone |t| <= mu (N1 + N2) (plus each face's own
  // cone where the other face separates): at the bisector the kinetic cone reaches y = 2 mu = .5 at (1, y,
  // 1), atan(.5 / sqrt 2) = .3398 rad; the sum reaches 2 mu / sqrt(1 − mu^2) = .5164 (wedging).
  const double mu = 0.25, phi = std::atan(mu);
  const FrictionCone sum = FrictionCone::sum({{kUp, phi}, {Vec3::UnitX(), phi}});
  const UniqueStick unique = UniqueStick::concave_edge(kUp, mu, Vec3::UnitX(), mu);
  auto classify = [&](const Vec3& v, double theta_v) { return classify_damper(sum, unique, v, theta_v); };
  const Vec3 into_corner = -Vec3(1, 0, 1).normalized();
  EXPECT_EQ(classify(into_corner, 0.25), StickClass::kMust);  // .25 < .3398
  EXPECT_EQ(classify(into_corner, 0.40), StickClass::kMay);   // .40 > .3398
  // Between the kinetic and the wedging limit both sticking and sliding are Coulomb solutions: may, not must.
  EXPECT_EQ(classify(-Vec3(1, 0.51, 1), 0.0), StickClass::kMay);
  EXPECT_EQ(classify(-Vec3(1, 0.49, 1), 0.0), StickClass::kMust);
  EXPECT_EQ(classify(-Vec3(1, 0.53, 1), 0.0), StickClass::kNever);  // beyond the sum: no static solution
  // Pushing only into the floor: pulling off the wall leaves the floor's cone (margin phi = .245); pressing
  // the wall too meets the kinetic facet through (0, mu, -1) and (-1, mu, 0), whose plane is asin(.2357) =
  // .2379 away.
  EXPECT_EQ(classify(-kUp, 0.2), StickClass::kMust);
  EXPECT_EQ(classify(-kUp, 0.3), StickClass::kMay);
  // Along the edge (y): never.
  EXPECT_EQ(classify(Vec3::UnitY(), 0.25), StickClass::kNever);
  // mu = 0 edge: a planar wedge; a push with any y component escapes it.
  const FrictionCone slick = FrictionCone::sum({{kUp, 0}, {Vec3::UnitX(), 0}});
  const UniqueStick slick_unique = UniqueStick::concave_edge(kUp, 0, Vec3::UnitX(), 0);
  EXPECT_EQ(classify_damper(slick, slick_unique, -Vec3(1, 0.2, 1).normalized(), 0.1), StickClass::kNever);
  EXPECT_EQ(classify_damper(slick, slick_unique, -Vec3(1, 0.2, 1).normalized(), 0.15), StickClass::kMay);
}

TEST(DamperStick, VertexOfThreeFaces) {
  // A box corner: the sum of three cones contains the positive octant, whose boundary is asin(1/sqrt 3) =
  // .6155 from (1,1,1): a push into the corner with theta_v = .5 must stick; pulling out never does.
  const double phi = std::atan(0.25);
  const FrictionCone corner = FrictionCone::sum({{Vec3::UnitX(), phi}, {Vec3::UnitY(), phi}, {kUp, phi}});
  const UniqueStick unique = UniqueStick::corner(Vec3::UnitX(), Vec3::UnitY(), kUp);
  // Pressing into all three faces, asin(1/sqrt 3) = .6155 from each coordinate plane: only sticking is
  // possible.
  EXPECT_EQ(classify_damper(corner, unique, -Vec3(1, 1, 1).normalized(), 0.5), StickClass::kMust);
  EXPECT_EQ(classify_damper(corner, unique, -Vec3(1, 1, 1).normalized(), 0.7), StickClass::kMay);
  EXPECT_EQ(classify_damper(corner, unique, Vec3(1, 1, 1).normalized(), 0.5), StickClass::kNever);
}

TEST(SlidingCone, NoSlidingWhenTheVelocityConeIsInside) {
  const SlidingCone c = sliding_cone(kUp, 0.25, -kUp, 0.1);  // .1 < phi
  EXPECT_FALSE(c.possible);
}

TEST(SlidingCone, FrictionConeInsideVelocityConeSlidesEverywhere) {
  const SlidingCone c = sliding_cone(kUp, 0.25, -kUp, 0.3);  // phi = .245 < .3 (Alg 4.3, first case)
  EXPECT_TRUE(c.possible);
  EXPECT_TRUE(c.all);
}

TEST(SlidingCone, TangentPointsBoundTheCone) {
  // v at polar beta = 1.0 from −n, theta_v = .25: the cap's azimuth half-width is asin(sin theta / sin beta)
  // = .29845, reached at polar angle acos(cos beta / cos theta) = .979 > phi, inside the face (beta + theta <
  // pi/2).
  const SlidingCone c = sliding_cone(kUp, 0.25, from_down(1.0), 0.25);
  ASSERT_TRUE(c.possible);
  EXPECT_FALSE(c.all);
  EXPECT_NEAR(c.half_angle, std::asin(std::sin(0.25) / std::sin(1.0)), 1e-8);
  EXPECT_NEAR(c.axis.x(), 1.0, 1e-12);
  EXPECT_TRUE(c.contains(Vec3(1, 0.2, 0), kUp));
  EXPECT_FALSE(c.contains(Vec3(1, 0.4, 0), kUp));
}

TEST(SlidingCone, FrictionRimBoundsTheCone) {
  // beta = .3, theta = .25, phi = atan .25: the tangent points lie inside the friction cone, so the extremes
  // are where the two rims cross: cos D = (cos theta − cos phi cos beta) / (sin phi sin beta).
  const double phi = std::atan(0.25), beta = 0.3, theta = 0.25;
  const double expected =
      std::acos((std::cos(theta) - std::cos(phi) * std::cos(beta)) / (std::sin(phi) * std::sin(beta)));
  const SlidingCone c = sliding_cone(kUp, 0.25, from_down(beta), theta);
  ASSERT_TRUE(c.possible);
  EXPECT_NEAR(c.half_angle, expected, 1e-8);
}

TEST(SlidingCone, WiderThanAHalfTurn) {
  // The pole (−n) inside the velocity cone but the friction cone not: beta = .1, theta = .3; the formula
  // above gives cos D < 0, a sliding cone wider than pi/2 (the case the thesis singles out in Alg 4.3).
  const double phi = std::atan(0.25), beta = 0.1, theta = 0.3;
  const double expected =
      std::acos((std::cos(theta) - std::cos(phi) * std::cos(beta)) / (std::sin(phi) * std::sin(beta)));
  ASSERT_GT(expected, std::numbers::pi / 2);
  const SlidingCone c = sliding_cone(kUp, 0.25, from_down(beta), theta);
  ASSERT_TRUE(c.possible);
  EXPECT_FALSE(c.all);
  EXPECT_NEAR(c.half_angle, expected, 1e-8);
}

TEST(SlidingCone, LeavingTheFaceBoundsTheCone) {
  // v points slightly away from the face (beta = 1.7 > pi/2): only velocities below the face's plane press
  // and slide; their azimuths reach cos D = cos theta / sin beta on the polar = pi/2 circle.
  const SlidingCone c = sliding_cone(kUp, 0.25, from_down(1.7), 0.25);
  ASSERT_TRUE(c.possible);
  EXPECT_NEAR(c.half_angle, std::acos(std::cos(0.25) / std::sin(1.7)), 1e-8);
  // Entirely away from the face: no sliding.
  EXPECT_FALSE(sliding_cone(kUp, 0.25, from_down(2.0), 0.25).possible);
}

TEST(DamperStick, ConvexEdgeOfTheHoleRim) {
  // The rim edge between the top face (+z) and the hole wall (+x), mu = .48. Buckley's edge cone is the same
  // sum as for a concave edge, so a diagonal push −(1,0,1) admits a static solution. But at a convex edge the
  // contact may act through either face: on the top face alone the push has tangential/normal ratio 1 > mu
  // and slides over the rim, on the wall alone likewise. Sticking is unique only inside both faces' cones
  // (empty here, the normals are pi/2 apart and 2 phi = .895 < pi/2): never "must".
  const double phi = std::atan(0.48);
  const FrictionCone rim = FrictionCone::sum({{kUp, phi}, {Vec3::UnitX(), phi}});
  const UniqueStick unique = UniqueStick::intersection({kUp, Vec3::UnitX()}, {0.48, 0.48});
  EXPECT_EQ(classify_damper(rim, unique, -Vec3(1, 0, 1).normalized(), 0.0), StickClass::kMay);
  EXPECT_EQ(classify_damper(rim, unique, -Vec3(1, 0, 1).normalized(), 0.25), StickClass::kMay);
  EXPECT_EQ(classify_damper(rim, unique, -kUp, 0.1), StickClass::kMay);
  // Sliding off the rim into the hole (velocity +x, down a little): outside the sum, never.
  EXPECT_EQ(classify_damper(rim, unique, Vec3(1, 0, -0.2).normalized(), 0.25), StickClass::kNever);
}

}  // namespace
}  // namespace cmt

namespace cmt {
namespace {

// UniqueStick::must_cones: a face (mu .5, phi = .4636) under theta .1 keeps one cone about −n of half-angle
// .3636; under theta .5 > phi nothing. A concave box corner (normals +x, +y, +z, mu .5) under theta .1:
// pressing into all three (cones of half-angle pi/2 − .1 about each −n_k) and each face's own cone: four
// alternatives, none empty (an empty alternative would mean every direction).
TEST(UniqueStickMustCones, FaceAndCornerAlternatives) {
  const auto face = UniqueStick::face(Vec3::UnitZ(), 0.5).must_cones(0.1);
  ASSERT_EQ(face.size(), 1u);
  ASSERT_EQ(face[0].size(), 1u);
  EXPECT_NEAR(face[0][0].half_angle, std::atan(0.5) - 0.1, 1e-12);
  EXPECT_TRUE(face[0][0].axis.isApprox(-Vec3::UnitZ()));
  EXPECT_TRUE(UniqueStick::face(Vec3::UnitZ(), 0.5).must_cones(0.5).empty());
  const auto corner =
      UniqueStick::corner(Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), {0.5, 0.5, 0.5}).must_cones(0.1);
  ASSERT_EQ(corner.size(), 4u);
  EXPECT_EQ(corner[0].size(), 3u);
  EXPECT_NEAR(corner[0][0].half_angle, std::numbers::pi / 2 - 0.1, 1e-12);
  for (const auto& alternative : corner) EXPECT_FALSE(alternative.empty());
  // Three face cones of a convex corner (intersection kind) are pairwise disjoint: no alternative.
  EXPECT_TRUE(UniqueStick::intersection({Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()}, {0.5, 0.5, 0.5})
                  .must_cones(0.1)
                  .empty());
}

}  // namespace
}  // namespace cmt

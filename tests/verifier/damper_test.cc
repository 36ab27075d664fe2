// Hand-worked cases for the damper's stick/slide analysis (Buckley §3.2, §4.3.5). Expected values are derived
// in the comments from the cone geometry, not taken from the program.
#include "verifier/damper.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cmt {
namespace {

const Vec3 kUp = Vec3::UnitZ();

// A unit vector at polar angle `polar` from −z, azimuth 0 (toward +x).
Vec3 from_down(double polar) { return Vec3(std::sin(polar), 0, -std::cos(polar)); }

TEST(DamperStick, FaceCone) {
  const double mu = 0.25, phi = std::atan(mu);  // .2450
  const FrictionCone face = FrictionCone::face(kUp, mu);
  // Straight down: must stick while theta_v < phi, may when the velocity cone pokes out.
  EXPECT_EQ(classify_damper(face, -kUp, 0.0), StickClass::kMust);
  EXPECT_EQ(classify_damper(face, -kUp, 0.1), StickClass::kMust);
  EXPECT_EQ(classify_damper(face, -kUp, 0.25), StickClass::kMay);
  // At alpha from the inward normal: must iff alpha + theta_v < phi, never iff alpha − theta_v > phi.
  EXPECT_EQ(classify_damper(face, from_down(0.5 * phi), 0.0), StickClass::kMust);
  EXPECT_EQ(classify_damper(face, from_down(1.05 * phi), 0.0), StickClass::kNever);
  EXPECT_EQ(classify_damper(face, from_down(phi + 0.2), 0.25), StickClass::kMay);
  EXPECT_EQ(classify_damper(face, from_down(phi + 0.3), 0.25), StickClass::kNever);
  // Pulling away never sticks.
  EXPECT_EQ(classify_damper(face, kUp, 0.25), StickClass::kNever);
}

TEST(DamperStick, FrictionlessAndLargeFriction) {
  // mu = 0: only the exact normal push is in the cone (a ray): never "must", may on the normal, never off it.
  const FrictionCone slick = FrictionCone::face(kUp, 0.0);
  EXPECT_EQ(classify_damper(slick, -kUp, 0.0), StickClass::kMay);
  EXPECT_EQ(classify_damper(slick, from_down(0.01), 0.0), StickClass::kNever);
  EXPECT_EQ(classify_damper(slick, from_down(0.01), 0.02), StickClass::kMay);
  // mu = 10: phi = 1.4711; alpha = 1.2 with theta_v = .25 stays inside (1.45 < 1.4711).
  const FrictionCone grippy = FrictionCone::face(kUp, 10.0);
  EXPECT_EQ(classify_damper(grippy, from_down(1.2), 0.25), StickClass::kMust);
  EXPECT_EQ(classify_damper(grippy, from_down(1.3), 0.25), StickClass::kMay);
}

TEST(DamperStick, ConcaveEdgeUsesTheSummedCone) {
  // Faces with normals +z and +x (a concave edge along y), mu = .25. The summed cone contains every direction
  // within .2450 of either normal, the whole quarter-plane between them, and out of that plane at the
  // bisector up to atan(y_max / sqrt 2) with y_max = 2 mu / sqrt(1 − mu^2) = .5164: .3502 rad.
  const double phi = std::atan(0.25);
  const FrictionCone edge = FrictionCone::sum({{kUp, phi}, {Vec3::UnitX(), phi}});
  const Vec3 into_corner = -Vec3(1, 0, 1).normalized();
  EXPECT_EQ(classify_damper(edge, into_corner, 0.25), StickClass::kMust);  // .25 < .3502
  EXPECT_EQ(classify_damper(edge, into_corner, 0.40), StickClass::kMay);   // .40 > .3502
  // Pushing only into the floor: the margin toward −x is the floor cone's .2450.
  EXPECT_EQ(classify_damper(edge, -kUp, 0.2), StickClass::kMust);
  EXPECT_EQ(classify_damper(edge, -kUp, 0.3), StickClass::kMay);
  // Along the edge (y): never.
  EXPECT_EQ(classify_damper(edge, Vec3::UnitY(), 0.25), StickClass::kNever);
  // mu = 0 edge: a planar wedge; a push with any y component escapes it.
  const FrictionCone slick = FrictionCone::sum({{kUp, 0}, {Vec3::UnitX(), 0}});
  EXPECT_EQ(classify_damper(slick, -Vec3(1, 0.2, 1).normalized(), 0.1),
            StickClass::kNever);  // 0.1414 rad off
  EXPECT_EQ(classify_damper(slick, -Vec3(1, 0.2, 1).normalized(), 0.15), StickClass::kMay);
}

TEST(DamperStick, VertexOfThreeFaces) {
  // A box corner: the sum of three cones contains the positive octant, whose boundary is asin(1/sqrt 3) =
  // .6155 from (1,1,1): a push into the corner with theta_v = .5 must stick; pulling out never does.
  const double phi = std::atan(0.25);
  const FrictionCone corner = FrictionCone::sum({{Vec3::UnitX(), phi}, {Vec3::UnitY(), phi}, {kUp, phi}});
  EXPECT_EQ(classify_damper(corner, -Vec3(1, 1, 1).normalized(), 0.5), StickClass::kMust);
  EXPECT_EQ(classify_damper(corner, Vec3(1, 1, 1).normalized(), 0.5), StickClass::kNever);
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
  // The rim edge between the top face (+z) and the hole wall (+x): summed cone as for a concave edge, mu =
  // .48. Pushing diagonally into the obstacle corner, −(1,0,1), with theta_v = .25: must (the quarter-plane
  // between the normals has margin pi/4 + phi in-plane and more than theta_v out of plane: for mu = .48 the
  // bisector's out-of-plane reach is atan((2 mu / sqrt(1 − mu^2)) / sqrt 2) = .6587). Straight down (only
  // into the top face) with theta_v = .5 > phi = .4475: the margin toward −x is phi, so may.
  const double phi = std::atan(0.48);
  const FrictionCone rim = FrictionCone::sum({{kUp, phi}, {Vec3::UnitX(), phi}});
  EXPECT_EQ(classify_damper(rim, -Vec3(1, 0, 1).normalized(), 0.25), StickClass::kMust);
  EXPECT_EQ(classify_damper(rim, -Vec3(1, 0, 1).normalized(), 0.64), StickClass::kMust);
  EXPECT_EQ(classify_damper(rim, -Vec3(1, 0, 1).normalized(), 0.68), StickClass::kMay);
  EXPECT_EQ(classify_damper(rim, -kUp, 0.5), StickClass::kMay);
  // Sliding off the rim into the hole (velocity +x, down a little): leaves the cone entirely.
  EXPECT_EQ(classify_damper(rim, Vec3(1, 0, -0.2).normalized(), 0.25), StickClass::kNever);
}

}  // namespace
}  // namespace cmt

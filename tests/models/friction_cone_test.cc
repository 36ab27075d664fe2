#include "models/friction_cone.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cmt {
namespace {

TEST(FrictionCone, FaceConeIsCircular) {
  const FrictionCone c = FrictionCone::face(Vec3::UnitZ(), 0.25);
  const double phi = std::atan(0.25);
  auto at = [](double angle) { return Vec3(std::sin(angle), 0, std::cos(angle)); };
  EXPECT_EQ(c.classify(at(0.95 * phi)), ConeMembership::kInside);
  EXPECT_EQ(c.classify(at(1.05 * phi)), ConeMembership::kOutside);
  EXPECT_NEAR(c.signed_angle(at(0.5 * phi)), -0.5 * phi, 1e-12);
  EXPECT_EQ(c.classify(-Vec3::UnitZ()), ConeMembership::kOutside);
}

TEST(FrictionCone, ZeroFrictionIsARay) {
  const FrictionCone c = FrictionCone::face(Vec3::UnitZ(), 0.0);
  EXPECT_EQ(c.classify(Vec3(0, 0, 2)), ConeMembership::kBoundary);
  EXPECT_EQ(c.classify(Vec3(0.01, 0, 1)), ConeMembership::kOutside);
  // Concave edge of two perpendicular faces with mu = 0: the quarter-plane wedge between the normals.
  const FrictionCone edge = FrictionCone::sum({{Vec3::UnitZ(), 0}, {Vec3::UnitX(), 0}});
  EXPECT_EQ(edge.classify(Vec3(1, 0, 1)), ConeMembership::kInside);
  EXPECT_EQ(edge.classify(Vec3(1, 0.1, 1)), ConeMembership::kOutside);
  EXPECT_EQ(edge.classify(Vec3(-1, 0, 1)), ConeMembership::kOutside);
}

TEST(FrictionCone, ConcaveEdgeConeIsTheSumOfFaceCones) {
  const double mu = 0.25, phi = std::atan(mu);
  const FrictionCone edge = FrictionCone::sum({{Vec3::UnitZ(), phi}, {Vec3::UnitX(), phi}});
  // Bisector: inside. Beyond a face's cone on the far side: outside.
  EXPECT_EQ(edge.classify(Vec3(1, 0, 1)), ConeMembership::kInside);
  EXPECT_EQ(edge.classify(Vec3(-std::tan(1.05 * phi), 0, 1)), ConeMembership::kOutside);
  EXPECT_EQ(edge.classify(Vec3(-std::tan(0.95 * phi), 0, 1)), ConeMembership::kInside);
  // Along the edge: (1, y, 1) = c_z + c_x is feasible up to y = 2 mu / sqrt(1 - mu^2) (worked by hand: each
  // face force leans back against the other face's normal by mu^2 / (1 - mu^2) to gain tangential room).
  const double y_max = 2 * mu / std::sqrt(1 - mu * mu);
  EXPECT_EQ(edge.classify(Vec3(1, 0.99 * y_max, 1)), ConeMembership::kInside);
  EXPECT_EQ(edge.classify(Vec3(1, 1.01 * y_max, 1)), ConeMembership::kOutside);
  EXPECT_EQ(edge.classify(Vec3(1, 2.02 * mu, 1)), ConeMembership::kInside);  // beyond the naive 2 mu
  EXPECT_LT(edge.max_angular_error(), 3e-4);
  EXPECT_GT(edge.signed_angle(Vec3(0, 0, -1)), 0);
  EXPECT_LT(edge.signed_angle(Vec3(1, 0, 1)), 0);
}

TEST(FrictionCone, VertexConeWithLargeFrictionJams) {
  // Three orthogonal faces with mu = 1: the summed cone contains -(1,1,1) (wedging), and with mu = .25 it
  // does not.
  auto vertex = [](double mu) {
    return FrictionCone::sum(
        {{Vec3::UnitX(), std::atan(mu)}, {Vec3::UnitY(), std::atan(mu)}, {Vec3::UnitZ(), std::atan(mu)}});
  };
  EXPECT_EQ(vertex(0.25).classify(Vec3(-1, -1, -1)), ConeMembership::kOutside);
  EXPECT_EQ(vertex(0.25).classify(Vec3(1, 1, 1)), ConeMembership::kInside);
  EXPECT_EQ(vertex(1.0).classify(Vec3(-1, -1, -1)), ConeMembership::kInside);
}

}  // namespace
}  // namespace cmt

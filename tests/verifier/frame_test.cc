// plane_frame turns with the task (verifier/internal/frame.h): under every quarter turn R of the world axes,
// the frame of R n is the turned frame of n up to a common sign, or a quarter turn in the plane where n lies
// along an axis, so a regular 4k-gon laid out in it is the turned 4k-gon.
#include "verifier/internal/frame.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "models/task_transform.h"

namespace cmt {
namespace {

// The 24 proper signed permutations: quarter turns about z, then the six directions of the old z axis.
std::vector<Eigen::Matrix3d> rotations() {
  std::vector<Eigen::Matrix3d> out;
  const std::vector<Eigen::Matrix3d> tilts = {Eigen::Matrix3d::Identity(),
                                              TaskTransform::quarter_turns(0, 1).rotation,
                                              TaskTransform::quarter_turns(0, 2).rotation,
                                              TaskTransform::quarter_turns(0, 3).rotation,
                                              TaskTransform::quarter_turns(1, 1).rotation,
                                              TaskTransform::quarter_turns(1, 3).rotation};
  for (const Eigen::Matrix3d& t : tilts)
    for (int k = 0; k < 4; ++k) out.push_back(t * TaskTransform::quarter_turns(2, k).rotation);
  return out;
}

std::vector<Vec3> polygon(const Vec3& n, int sides) {
  Vec3 u, w;
  plane_frame(n, &u, &w);
  std::vector<Vec3> out;
  for (int k = 0; k < sides; ++k) {
    const double a = 2 * std::numbers::pi * k / sides;
    out.push_back(std::cos(a) * u + std::sin(a) * w);
  }
  return out;
}

// Every point of `a` lies within tol of a point of `b`.
bool same_points(const std::vector<Vec3>& a, const std::vector<Vec3>& b, double tol) {
  for (const Vec3& p : a) {
    double best = 1e300;
    for (const Vec3& q : b) best = std::min(best, (p - q).norm());
    if (best > tol) return false;
  }
  return a.size() == b.size();
}

void expect_turns_with(const Vec3& n) {
  Vec3 u, w;
  plane_frame(n, &u, &w);
  EXPECT_NEAR(u.dot(n), 0, 1e-15);
  EXPECT_NEAR(w.dot(n), 0, 1e-15);
  EXPECT_NEAR(u.norm(), 1, 1e-15);
  EXPECT_NEAR(w.norm(), 1, 1e-15);
  EXPECT_NEAR(u.cross(w).dot(n), 1, 1e-15);  // right-handed about n
  for (const Eigen::Matrix3d& r : rotations()) {
    std::vector<Vec3> turned;
    for (const Vec3& p : polygon(n, 24)) turned.push_back(r * p);
    EXPECT_TRUE(same_points(turned, polygon(r * n, 24), 1e-14)) << n.transpose() << "\n" << r;
  }
}

TEST(PlaneFrame, TurnsWithTheAxes) {
  for (int i = 0; i < 3; ++i) {
    expect_turns_with(Vec3::Unit(i));
    expect_turns_with(-Vec3::Unit(i));
  }
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  for (int k = 0; k < 200; ++k) expect_turns_with(Vec3(g(rng), g(rng), g(rng)).normalized());
}

// The frame the verifier used before for axis-aligned normals (u = n x e_x, or n x e_y for n along x) is
// kept, so axis-aligned faces sample the same directions.
TEST(PlaneFrame, AxisNormalsKeepTheirFrame) {
  Vec3 u, w;
  plane_frame(Vec3::UnitZ(), &u, &w);
  EXPECT_TRUE(u.isApprox(Vec3::UnitY()));
  plane_frame(-Vec3::UnitY(), &u, &w);
  EXPECT_TRUE(u.isApprox(Vec3::UnitZ()));
  plane_frame(Vec3::UnitX(), &u, &w);
  EXPECT_TRUE(u.isApprox(Vec3::UnitZ()));
}

}  // namespace
}  // namespace cmt

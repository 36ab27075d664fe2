// Two sound bounds of the velocity spring model derived by hand (docs/verifier.md, "Invariant half-spaces"
// and "Direction cones of slides"): half-spaces no path of a motion leaves, and the cone of directions a
// slide keeps, which makes a robot whose every admissible velocity crosses a face's boundary leave there.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "models/loaded_task.h"
#include "tests/verifier/test_geometry.h"
#include "verifier/spring_projection.h"

namespace cmt {
namespace {

// The box [-5,5]^2 x [0,5] (its floor z = 0, walls and ceiling), start (3,0,0) on the floor, p = (0,0,-5),
// eps_s = .1, theta_v = .1: the reach bound is 6.03095 (SpringVelocity.ReachBoundHandValue).
std::shared_ptr<const LoadedTask> floor_box() {
  return load_task_from_string(
      "name: t\nunits: in\nfriction: 0.5\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: 0.1, "
      "step: 0.1}\ncspace: []\nbounds: {min: [-5, -5, 0], max: [5, 5, 5]}\nstart: {point: [3, 0, 0]}\ngoal: "
      "{point: [3, 0, 0]}\nmotions:\n  m: {spring: [0, 0, -5]}\nstrategies:\n  s: [m]\n",
      "test");
}

const HalfSpace* find(const std::vector<HalfSpace>& hs, const Vec3& w) {
  for (const HalfSpace& h : hs)
    if ((h.normal - w).norm() < 1e-12) return &h;
  return nullptr;
}

// +z at the start's level 0: free points with z >= 0 have x − p within acos(5 / 6.03095) = .5926 of +z, plus
// theta_v .1 and asin(.1 / 5) = .0200: .7126 < pi/2; on the walls (u = +z) the worst slab point is a corner
// (5,5,0): angle(+z, (5,5,5)) = .9553, + .1 + .0200 = 1.0753 < pi/2; the floor (u = 0) does not count. So the
// robot never rises: z <= 0.
// +x at the start's level 3: free points: acos(3 / 6.03095) = 1.0503, + .1 + asin(.1 / 3) = .0333: 1.1836;
// the floor's slab corner (3,5,0): angle(+x, (3,5,5)) = acos(3 / 7.6811) = 1.1694, + .1333 = 1.3027; the
// walls y = +-5 and the ceiling at (3,5,5): acos(3 / 11.5758) = 1.3087, + .1333 = 1.4420 < pi/2. So x <= 3:
// the robot never moves away from p along x. +y: the start's level 0 is p's own (the pull may point anywhere
// there): no bound at that level.
TEST(VelocityBounds, InvariantHalfSpacesHandValues) {
  const auto task = floor_box();
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  const Vec3 p(0, 0, -5);
  const double reach = velocity_reach_bound(task->cspace, start, p, task->task.uncertainty);
  ASSERT_NEAR(reach, 6.03095, 1e-5);
  const std::vector<HalfSpace> hs =
      velocity_invariant_half_spaces(task->cspace, start, p, task->task.uncertainty, reach);
  const HalfSpace* up = find(hs, Vec3::UnitZ());
  ASSERT_NE(up, nullptr);
  EXPECT_NEAR(up->offset, 0.0, 1e-6);
  const HalfSpace* back = find(hs, Vec3::UnitX());
  ASSERT_NE(back, nullptr);
  EXPECT_NEAR(back->offset, 3.0, 1e-6);
  const HalfSpace* side = find(hs, Vec3::UnitY());
  if (side != nullptr) {
    EXPECT_GT(side->offset, 0.1);  // above p's level plus eps_s, if any
  }
  // Every half-space holds the start and is a bound short of the reach ball.
  for (const HalfSpace& h : hs) {
    EXPECT_GE(h.offset, h.normal.dot(Vec3(3, 0, 0)) - 1e-12);
    EXPECT_LT(h.offset, h.normal.dot(p) + reach);
  }
}

// The projection respects the half-spaces: nothing reached above the floor (z > 0) or beyond x = 3.
TEST(VelocityBounds, ProjectionStaysInTheHalfSpaces) {
  const auto task = floor_box();
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  const SpringProjection pr = forward_project_spring(*task, start, Vec3(0, 0, -5), SpringModel::kVelocity);
  ASSERT_FALSE(pr.reached.pieces().empty());
  for (const ReachedPiece& piece : pr.reached.pieces())
    for (const Vec3& q : piece.polygon) {
      EXPECT_LE(q.z(), 1e-6);
      EXPECT_LE(q.x(), 3 + 1e-6);
    }
}

// hole.yaml (mu .48, eps_s .2, theta_v .25): the top face beside the hole, x >= 1, z = 0, start on its rim
// x = 1, y in [0, .2], p = p2 = (0,2,-1), so p' = (0,2,0) (off this face) and the depth of p* is at most 1.2.
// Every admissible in-plane velocity on the rim strip x in [1, 1.1], y in [0, 1.1] has a component toward
// −x (into the hole): the angle between −x and the direction to p' is at most atan(2 / 1) = 1.1071 (at
// (1,0)), and beta(d) = asin(sin .25 sqrt(d^2 + 1.2^2) / d) with asin(.2 / d) add at most .2850 + .0896 there
// (d = 2.236) — 1.4817 < pi/2 — and at (1, 1.1): .7328 + .3380 + .1494 = 1.2202. So the robot cannot slide
// onto the top from the rim: it leaves at once (before the direction cones, the slide reached y = 1.025 along
// x in [1, 1.023] and the far rim corner, from where p2 slid onto the top behind the hole).
TEST(VelocityBounds, SlideFromARimWhereEveryVelocityLeavesTheFace) {
  const auto task = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/hole.yaml");
  Region rim;
  rim.kind = Region::Kind::kSegment;
  rim.points = {Vec3(1, 0, 0), Vec3(1, 0.2, 0)};
  rim.key = "start";
  const ReachedSet start = ReachedSet::from_region(*task, rim);
  const SpringProjection pr = forward_project_spring(*task, start, Vec3(0, 2, -1), SpringModel::kVelocity);
  const int top = test::face_at(task->cspace, Vec3::UnitZ(), Vec3(2, 0, 0));
  ASSERT_GE(top, 0);
  bool any = false;
  for (const ReachedPiece& piece : pr.reached.pieces()) {
    if (piece.atom != top) continue;
    for (const Vec3& q : piece.polygon) {
      any = true;
      EXPECT_LE(q.x(), 1 + 1e-6) << "slid onto the top beside the hole";
    }
  }
  EXPECT_TRUE(any);  // the start itself (on the rim) is a reached part of the top
  // It ends on the far wall y = 1 below the rim only (hole p2's intended outcome).
  ASSERT_FALSE(pr.termination.pieces().empty());
  for (const ReachedPiece& piece : pr.termination.pieces())
    for (const Vec3& q : piece.polygon) {
      EXPECT_NEAR(q.y(), 1.0, 1e-9);
      EXPECT_LT(q.z(), 0.0);
    }
}

}  // namespace
}  // namespace cmt

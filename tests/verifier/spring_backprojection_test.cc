// Spring backprojections (Buckley §5.4.4, Alg 5.2) under the via-point model, hand-checked on the
// block_shadow task (models/tasks/geometry/block_shadow.yaml: an 8 x 8 x 4 room, a block x in [2.5, 3.5], |y|
// <= .5, z in [0, 1]; mu = .25, eps_s = eps_p = step = .1, theta_v = .1: eps_t = .104, eps_o = .40; spring
// toward p = (0, 0, -1); goal |x|, |y| <= 2 on the floor), and the consistency of the backprojection with the
// forward projection. Every expected value is derived in the comments from the scene.
#include <gtest/gtest.h>

#include <string>

#include "tests/verifier/reached_set_expectations.h"
#include "tests/verifier/test_geometry.h"
#include "verifier/backprojection.h"
#include "verifier/spring.h"
#include "verifier/spring_projection.h"

namespace cmt {
namespace {

using test::expect_in;
using test::expect_out;
using test::face_at;
using test::motion;

const LoadedTask& block_shadow() {
  static const auto task =
      load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/geometry/block_shadow.yaml");
  return *task;
}

// B: where the motion may stop outside the goal. On the block's far wall x = 3.5 (normal +x, p 3.5 in behind
// its plane) the weak sticking disk about p' = (3.5, 0, -1) has radius 3.5 tan(psi) + .1 / cos(psi) = 1.37,
// psi = atan .25 + .1 (face_sticking_radii): the wall's foot up to z = .37 at y = 0 (.38 with the
// circumscribed polygon), and the concave edge at its foot, where the pull presses into the floor and the
// wall at once. W: the floor behind the block (x > 3.5) slides toward p' = (0, 0, 0) into that edge; the
// whole far wall slides down into it (p' below its foot); a flight from the room's wall x = 4 toward p that
// passes within eps_t of the block's far rim (3.5, y, 1) comes down on the far wall: from (4, 0, z) the
// segment to p crosses x = 3.5 at (7 z - 1) / 8, 1 at z = 9/7.
TEST(SpringBackprojection, TheBlockShadowsTheFloorBehindIt) {
  const LoadedTask& t = block_shadow();
  const ReachedSet goal = ReachedSet::from_regions(t, t.task.goal);
  const SpringBackprojection b = backproject_spring(t, goal, motion(t, "down"));
  ASSERT_FALSE(b.fallback);
  ASSERT_FALSE(b.free_rest);  // p lies 1 in below the floor: the rest ball (radius .1) is inside the obstacle
  expect_in(b.base, Vec3(3.5, 0, 0));
  expect_in(b.base, Vec3(3.5, 0, 0.3));
  expect_out(b.base, Vec3(3.5, 0, 0.5));
  expect_out(b.base, Vec3(0, 0, 0));  // sticking at the centre is the goal
  expect_in(b.weak, Vec3(3.8, 0, 0));
  expect_in(b.weak, Vec3(3.5, 0, 0.9));
  expect_in(b.weak, Vec3(4, 0, 9.0 / 7));
  // Past the shadow: from (3.8, 2.5, 0) the slide toward the centre crosses x = 3.5 at y = 2.30, far from the
  // block; the floor presses the robot into it (no flight: p is 1 in below), so under the pointwise model it
  // reaches the goal (the forward projection, which restarts a slide at every flat edge, creeps from there:
  // docs/teaching.md).
  expect_out(b.weak, Vec3(3.8, 2.5, 0));
  // From (4, 0, 3.5) the flight crosses x = 3.5 at z = 2.94 and lands on the floor at x = .89, in the goal.
  expect_out(b.weak, Vec3(4, 0, 3.5));
  expect_in(b.strong, Vec3(-3, 0, 0));  // the task's start
  expect_in(b.strong, Vec3(0, 0, 4));   // the ceiling's centre: the flight lands at the floor's centre
  expect_in(b.strong, Vec3(3.8, 2.5, 0));
  expect_out(b.strong, Vec3(3.8, 0, 0));
  EXPECT_EQ(b.strong.face_area(face_at(t.cspace, Vec3::UnitX(), Vec3(3.5, 0, 0.5))), 0);  // the far wall
}

// The two algorithms agree: from points of S the forward projection of the same model stops only in the goal.
// The points, each derived: the start (slides to the centre); the ceiling's centre and the walls x = -4 and y
// = -4 at mid-height (they fly toward p and land inside the goal); the wall x = 4 beside the block at (4, 2,
// 2) (its flight crosses x = 2.5 at y = 1.25, beside the block, and lands at (1.33, .67), in the goal); the
// ceiling at (3, 3, 4) (lands at x = y = .6); the block's near wall (2.5, 0, .5) (the robot leaves it toward
// p and lands on the floor at x = 1.7). The forward projection also widens nowhere from these points
// (widening, kSpringWideningRounds, is looser than the pointwise fixpoint the backprojection reverses).
TEST(SpringBackprojection, ForwardProjectionFromTheStrongBackprojectionStopsInTheGoal) {
  const LoadedTask& t = block_shadow();
  const CSpace& c = t.cspace;
  const ReachedSet goal = ReachedSet::from_regions(t, t.task.goal);
  const Vec3& p = motion(t, "down");
  const SpringBackprojection b = backproject_spring(t, goal, p);
  const std::vector<std::pair<Vec3, Vec3>> points = {
      {Vec3(-3, 0, 0), Vec3::UnitZ()},    {Vec3(0, 0, 4), -Vec3::UnitZ()}, {Vec3(-4, 0, 2), Vec3::UnitX()},
      {Vec3(0, -4, 2), Vec3::UnitY()},    {Vec3(4, 2, 2), -Vec3::UnitX()}, {Vec3(3, 3, 4), -Vec3::UnitZ()},
      {Vec3(2.5, 0, 0.5), -Vec3::UnitX()}};
  for (const auto& [x, normal] : points) {
    expect_in(b.strong, x);
    ReachedSet start(c);
    start.add_face_point(face_at(c, normal, x), x);
    const SpringProjection f = forward_project_spring(t, start, p, SpringModel::kViaPoint);
    EXPECT_EQ(f.widened, 0) << x.transpose();
    EXPECT_TRUE(f.termination.pieces_outside(goal, t.surface_tolerance()).empty()) << x.transpose();
    EXPECT_FALSE(f.free_termination) << x.transpose();
    EXPECT_TRUE(f.slide_forever.empty()) << x.transpose();
  }
}

}  // namespace
}  // namespace cmt

// Hand-checked damper backprojections (Buckley Alg 5.2, §5.4.3) on the built-in two_blocks task (Fig 4.1:
// blocks A = x[-4.5,-1.5] z[0,2] and B = x[1.5,4.5] z[0,3] across y[-4,4], bounds [-6,6]x[-4,4]x[0,6],
// mu = .25, theta_v = .25), and the consistency of the backprojection with the forward projection. Every
// expected value is derived in the comments from the scene.
#include "verifier/backprojection.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/verifier/reached_set_expectations.h"
#include "tests/verifier/test_geometry.h"
#include "verifier/damper_projection.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

using test::edge_between;
using test::expect_in;
using test::expect_out;
using test::face_at;
using test::motion;

const LoadedTask& two_blocks() {
  static const auto task = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/two_blocks.yaml");
  return *task;
}

// v2 = (-1, 0, -1)/sqrt 2. On the floor (normal +z) every admissible velocity is .535-1.035 rad from -n, past
// phi = atan .25 = .245: it always slides, with the tangential part's azimuth within asin(sin .25 / sin
// 45deg) = .357 rad of -x. Reversed: a floor point z is reached from z + s (cos a, sin a, 0), s >= 0, |a| <=
// .357 (tan .357 = .373). Flight reversed: rays from z along cone(-v2) rise to the right with slopes dz/dx in
// [tan(pi/4 - .25), tan(pi/4 + .25)] = [.587, 1.70] (the polygonal cone adds under .01 rad).
TEST(DamperBackprojection, PointOnTheGapFloorUnderV2) {
  const LoadedTask& t = two_blocks();
  const CSpace& c = t.cspace;
  const AtomCones cones(c);
  ReachedSet from(c);
  from.add_face_point(face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0)), Vec3(0, 0, 0));
  const WeakBackprojection w = weak_backproject_damper(t, cones, from, motion(t, "v2"));
  ASSERT_FALSE(w.fallback);
  expect_in(w.weak, Vec3(0, 0, 0));
  expect_in(w.weak, Vec3(1, 0, 0));    // backslide along the wedge's axis
  expect_in(w.weak, Vec3(1, 0.3, 0));  // .3 < .373
  expect_out(w.weak, Vec3(1, 0.6, 0));
  expect_out(w.weak, Vec3(-1, 0, 0));  // the robot slides left, never right
  // B's left wall (x = 1.5, normal -x: v2 lifts off it): the ray of slope 1 from the point meets it at z
  // = 1.5; the floor wedge's points x0 in [0, 1.5] reach z = (1.5 - x0) slope <= 1.5 x 1.70 = 2.56.
  expect_in(w.weak, Vec3(1.5, 0, 1.5));
  expect_in(w.weak, Vec3(1.5, 0, 0.5));  // from (1, 0, 0) with slope 1
  expect_out(w.weak, Vec3(1.5, 0, 2.9));
  // Occlusion: B's top (3, 0, 3) and the right wall (6, 0, 4) lie in the unoccluded reverse cone (slopes
  // 3/3 = 1 and 4/6 = .67), but those rays cross x = 1.5 at z = 1.5 and 1.0, inside B.
  expect_out(w.weak, Vec3(3, 0, 3));
  expect_out(w.weak, Vec3(6, 0, 4));
  expect_out(w.weak, Vec3(-3, 0, 2));  // A's top: left of the point, out of every reverse ray
}

// The concave edge where A's right wall (x = -1.5, normal +x) meets the gap floor, y in [-1, 1].
TEST(DamperBackprojection, EdgeIntervalUnderV2) {
  const LoadedTask& t = two_blocks();
  const CSpace& c = t.cspace;
  const AtomCones cones(c);
  const int e = edge_between(c, Vec3(-1.5, -4, 0), Vec3(-1.5, 4, 0));
  ASSERT_GE(e, 0);
  ReachedSet from(c);
  from.add_edge_interval(e, 3.0 / 8, 5.0 / 8);
  const WeakBackprojection w = weak_backproject_damper(t, cones, from, motion(t, "v2"));
  ASSERT_FALSE(w.fallback);
  // Floor: the interval swept back by the wedge: |y| <= 1 + .373 (x + 1.5).
  expect_in(w.weak, Vec3(0, 1.5, 0));  // 1.5 <= 1.56
  expect_out(w.weak, Vec3(0, 2, 0));
  // A's right wall: v2 presses into it 45 deg from -n and slides down with azimuths within .357 of -z:
  // reversed, |y| <= 1 + .373 z above the interval.
  expect_in(w.weak, Vec3(-1.5, 0, 1.9));
  expect_out(w.weak, Vec3(-1.5, 3, 1));
  // Flight from the edge (in front of both faces) rises right with slopes [.587, 1.70]: B's left wall at
  // z = 3 x [.587, 1.70] = [1.76, 5.1], cut at its top z = 3; above B to the ceiling z = 6 at x = -1.5 + 6 /
  // slope in [2, 8.7], e.g. (4, 0, 6) (slope 1.09: it crosses x = 1.5 at z = 3.27, above B).
  // The floor strip flies too: from x0 in [-1.5, 1.5] it covers B's left wall up to z = 3 x 1.70 near y = 0,
  // but not at y = 3.5: from the strip's points that reach z = .5 (x0 >= 1.5 - .5 / .587 = .65, |y| <= 1 +
  // .373 x 2.15 = 1.8) the ray's sideways spread over its length of at most 1.3 is under .35.
  expect_in(w.weak, Vec3(1.5, 0, 2.5));
  expect_out(w.weak, Vec3(1.5, 3.5, 0.5));
  expect_in(w.weak, Vec3(4, 0, 6));
  // B's top slides left to its rim (1.5, y, 3), whose slope-1 rays land on the interval: (3, 0, 3) is in W.
  // So is the right wall x = 6 above z = 3 + 1.5 x .587 = 3.88, whose flights land on B's top (they reach z =
  // 3 at x = 6 - (z - 3) / slope <= 4.5); below that they meet B's right wall (x = 4.5, z <= 3.5 - 1.5 x .587
  // < 3), slide down it and stick in the concave edge at its foot, far from the interval.
  expect_in(w.weak, Vec3(3, 0, 3));
  expect_in(w.weak, Vec3(6, 0, 5.5));
  expect_out(w.weak, Vec3(6, 0, 3.5));
}

// S_v2(goal): v2 never sticks on a face; it sticks only at concave edges it presses into at both faces.
// Outside the goal (the gap floor, closed) those are the feet of the walls it presses into: x = -6 (left
// floor) and x = 4.5 (B's right wall, right floor), with their corners; that is B. W(B): the left floor and
// wall x = -6, A's top and left wall (slide or fly off to the left), the right floor and B's right wall
// (slide into its foot). B's top is not in W: flights off its left rim (1.5, y, 3) fall with slopes >=
// .587, reaching x = -1.5 at z <= 3 - 3 x .587 = 1.24 < 2 (A's right wall or the gap floor), never A's top.
TEST(DamperBackprojection, StrongBackprojectionOfTheGoalUnderV2HoldsBsTop) {
  const LoadedTask& t = two_blocks();
  const CSpace& c = t.cspace;
  const AtomCones cones(c);
  const ReachedSet goal = ReachedSet::from_regions(t, t.task.goal);
  const DamperBackprojection b = backproject_damper(t, cones, goal, motion(t, "v2"));
  ASSERT_FALSE(b.fallback);
  const int b_top = face_at(c, Vec3::UnitZ(), Vec3(3, 0, 3));
  const int a_top = face_at(c, Vec3::UnitZ(), Vec3(-3, 0, 2));
  const int left_floor = face_at(c, Vec3::UnitZ(), Vec3(-5, 0, 0));
  const int gap = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  // All of B's top but its right rim x = 4.5: B's right wall (normal +x, pressed at 45 deg) slides down into
  // the concave edge at its foot, a stop outside the goal, and the forward model lets a robot on a convex rim
  // go down either face. S keeps the margin m from W: B's top less a strip m wide along that rim.
  const double m = kBackprojectionRelativeMargin * c.scale();
  EXPECT_NEAR(b.strong.face_area(b_top), 3 * 8 - 8 * m, 1e-3 * m);
  EXPECT_LT(b.strong.distance(Vec3(4.5 - 2 * m, 0, 3)), 1e-9);
  EXPECT_GT(b.strong.distance(Vec3(4.5, 0, 3)), 0.5 * m);
  expect_in(b.weak, Vec3(4.5, 0, 1));                 // B's right wall
  EXPECT_NEAR(b.strong.face_area(gap), 3 * 8, 1e-6);  // sliding left into the goal's edge
  EXPECT_EQ(b.strong.face_area(a_top), 0);
  EXPECT_EQ(b.strong.face_area(left_floor), 0);
  expect_in(b.base, Vec3(-6, 0, 0));
  expect_in(b.base, Vec3(4.5, 0, 0));
  expect_out(b.base, Vec3(-1.5, 0, 0));  // the goal's own edge is no failure
  expect_in(b.strong, Vec3(3, 0, 3));    // the task's start
}

// S_v1(goal): straight down, theta_v = .25 > phi: the robot may stick anywhere on a horizontal face, so B's
// top is in B itself.
TEST(DamperBackprojection, StrongBackprojectionUnderV1ExcludesBsTop) {
  const LoadedTask& t = two_blocks();
  const CSpace& c = t.cspace;
  const AtomCones cones(c);
  const ReachedSet goal = ReachedSet::from_regions(t, t.task.goal);
  const DamperBackprojection b = backproject_damper(t, cones, goal, motion(t, "v1"));
  ASSERT_FALSE(b.fallback);
  EXPECT_EQ(b.strong.face_area(face_at(c, Vec3::UnitZ(), Vec3(3, 0, 3))), 0);
  expect_in(b.base, Vec3(3, 0, 3));
  // The gap floor is in S: the robot sticks on it or slides within it up to its walls, where the concave
  // edges are the goal's own.
  EXPECT_NEAR(b.strong.face_area(face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0))), 3 * 8, 1e-6);
}

// The two algorithms agree: the forward projection of S_m(X) stops only in X (Buckley §5.4: S is a strong
// backprojection), for every damper motion of the task and the goal as X.
TEST(DamperBackprojection, ForwardProjectionOfTheStrongBackprojectionStopsInTheTarget) {
  const LoadedTask& t = two_blocks();
  const AtomCones cones(t.cspace);
  const ReachedSet goal = ReachedSet::from_regions(t, t.task.goal);
  for (const std::string name : {"v1", "v2", "v3"}) {
    const DamperBackprojection b = backproject_damper(t, cones, goal, motion(t, name));
    ASSERT_FALSE(b.fallback) << name;
    ASSERT_FALSE(b.strong.empty()) << name;
    const DamperProjection f = forward_project_damper(t, cones, b.strong, motion(t, name));
    EXPECT_TRUE(f.termination.pieces_outside(goal, t.surface_tolerance()).empty()) << name;
  }
}

// The same on the planar two-block task (a start or goal stands for its extrusion across the y slab).
TEST(DamperBackprojection, PlanarBlocksForwardProjectionOfTheStrongBackprojectionStopsInTheTarget) {
  const auto t = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/planar_blocks.yaml");
  const AtomCones cones(t->cspace);
  const ReachedSet goal = ReachedSet::from_regions(*t, t->task.goal);
  for (const std::string name : {"v1", "v2"}) {
    const DamperBackprojection b = backproject_damper(*t, cones, goal, motion(*t, name));
    ASSERT_FALSE(b.fallback) << name;
    ASSERT_FALSE(b.strong.empty()) << name;
    const DamperProjection f = forward_project_damper(*t, cones, b.strong, motion(*t, name));
    EXPECT_TRUE(f.termination.pieces_outside(goal, t->surface_tolerance()).empty()) << name;
  }
}

}  // namespace
}  // namespace cmt

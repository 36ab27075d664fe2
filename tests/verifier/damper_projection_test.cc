// Hand-checked geometry of the generalized-damper forward projection (Buckley Alg 4.1/4.3; design steps A-F).
// Every expected value is derived in the comments from the scene, not taken from the program's output.
#include "verifier/damper_projection.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "tests/verifier/test_geometry.h"
#include "verifier/atom_cone.h"
#include "verifier/damper.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

constexpr double kPi = std::numbers::pi;

// A C-space task: bounds box, optional obstacles, one point start, the motion v.
std::string scene(double mu, double theta_v, const std::string& obstacles, const std::string& bounds,
                  const std::string& start, const std::string& v) {
  return "name: t\nunits: in\nfriction: " + std::to_string(mu) +
         "\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: " + std::to_string(theta_v) +
         ", theta_f: 0.1}\ncspace: " + obstacles + "\nbounds: " + bounds + "\nstart: {point: " + start +
         "}\ngoal: {point: " + start + "}\nmotions:\n  m: {damper: " + v + "}\nstrategies:\n  s: [m]\n";
}

using test::face_at;

struct Projected {
  std::shared_ptr<const LoadedTask> task;
  DamperProjection projection;
};

Projected project(const std::string& yaml) {
  auto task = load_task_from_string(yaml, "test");
  const AtomCones cones(task->cspace);
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  DamperProjection p = forward_project_damper(*task, cones, start, task->task.motions.at(0).target);
  return {task, std::move(p)};
}

const std::string kRoom = "{min: [-5, -5, 0], max: [5, 5, 5]}";

// The motion v from the scene's start with first-order contact and with the given contact lift and servo
// coast (VerifyOptions).
struct Compared {
  std::shared_ptr<const LoadedTask> task;
  DamperProjection plain, modelled;
};
Compared project_both(const std::string& yaml, const Vec3& v, double lift, double coast) {
  auto task = load_task_from_string(yaml, "test");
  const AtomCones cones(task->cspace);
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  DamperProjection plain = forward_project_damper(*task, cones, start, v, 0, 0, 0);
  DamperProjection modelled = forward_project_damper(*task, cones, start, v, 0, lift, coast);
  return {task, std::move(plain), std::move(modelled)};
}

TEST(ForwardProjection, MustStickPointStartStaysPut) {
  // Floor z = 0, mu = .5 (phi = .4636), theta_v = .1, straight down: cone(-v, .1) is inside the floor's cone
  // (.1 < .4636), so the floor is must-stick: nothing slides, and no velocity leaves the floor (v.n = -1 <
  // -sin .1), so the reached and termination sets are the start point alone.
  const Projected r = project(scene(0.5, 0.1, "[]", kRoom, "[1, 2, 0]", "[0, 0, -1]"));
  const auto pieces = r.projection.termination.pieces();
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].kind, AtomKind::kFace);
  ASSERT_EQ(pieces[0].polygon.size(), 1u);
  EXPECT_NEAR((pieces[0].polygon[0] - Vec3(1, 2, 0)).norm(), 0, 1e-12);
  EXPECT_EQ(r.projection.reached.pieces().size(), 1u);
  EXPECT_FALSE(r.projection.may_not_terminate);
}

TEST(ForwardProjection, VelocityConeWiderThanFrictionConeSlidesOverTheWholeFloor) {
  // Same floor with theta_v = .6 > phi = .4636: the friction cone lies inside the velocity cone (beta = 0),
  // so every tangential direction slides (Alg 4.3 case 1): the whole 10 x 10 floor is reached, and the floor
  // may stick (some velocities lie in its cone): termination has the whole floor, area 100. The walls are
  // never-stick (-v = +z is pi/2 - .6 = .97 > phi from a wall's normal), so none of them terminates.
  const Projected r = project(scene(0.5, 0.6, "[]", kRoom, "[1, 2, 0]", "[0, 0, -1]"));
  const CSpace& c = r.task->cspace;
  const int floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  ASSERT_GE(floor, 0);
  EXPECT_NEAR(r.projection.termination.face_area(floor), 100.0, 1e-9);
  for (const Face& f : c.faces()) {
    if (f.id == floor) continue;
    EXPECT_FALSE(r.projection.termination.contains_atom(f.id)) << c.atom_name(f.id);
  }
}

TEST(ForwardProjection, OcclusionHidesTheFloorBehindAWideBlock) {
  // Start (0,0,5) on the ceiling, damper straight down, theta_v = .4, mu = .5 (phi = .4636: the floor and the
  // block's top are must-stick faces). A floating block |x|,|y| <= 1, 2 <= z <= 3. The velocity cone (our
  // 24-gon circumscribes it: radius factor 1/cos(pi/24) = 1.0086) meets the block top (2 below) within radius
  // 2 tan .4 x 1.0086 = .852 < 1: the rim is never reached, so nothing slides or falls off the block. On the
  // floor the cone reaches radius 5 tan .4 x 1.0086 = 2.133, inside the umbra of the top, |x|,|y| <= 1 x 5/2
  // = 2.5: the floor is not reached at all. The reached top is the cone's footprint: area in [pi
  // .8454^2, 1.0057 x that].
  const Projected r = project(
      scene(0.5, 0.4, "[{box: {min: [-1, -1, 2], max: [1, 1, 3]}}]", kRoom, "[0, 0, 5]", "[0, 0, -1]"));
  const CSpace& c = r.task->cspace;
  const int floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  const int top = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 3));
  ASSERT_GE(floor, 0);
  ASSERT_GE(top, 0);
  EXPECT_EQ(r.projection.reached.face_area(floor), 0.0);
  EXPECT_FALSE(r.projection.reached.face_region_contains(floor, Vec3(2, 0, 0)));
  const double footprint = 2 * std::tan(0.4);
  EXPECT_GE(r.projection.reached.face_area(top), kPi * footprint * footprint);
  // (+1e-6: the cone is widened by kFlightAngleSlack.)
  EXPECT_LE(r.projection.reached.face_area(top), 24 * std::tan(kPi / 24) * footprint * footprint + 1e-6);
}

TEST(ForwardProjection, ARimThatMaySlipLetsTheRobotBendUnderTheBlock) {
  // The same scene with a narrow block |x|,|y| <= .5: the cone's footprint on the top (radius .845) covers
  // the top and its convex rim. At the rim sticking is not unique (the push may tilt off the top, or press
  // the side face and slide down it; verifier/unique_stick.h), so the robot may slide down a side face to the
  // block's bottom edge (z = 2) and continue with a velocity tilted under the block: from (.5, 0, 2) the
  // floor point (0, 0, 0) is atan(.5 / 2) = .245 < theta_v = .4 from straight down. So the floor under the
  // block is reachable (a bent path, Buckley L1040-1076), while (2.2, 0, 0) is not: from the ceiling the cone
  // reaches 2.133, from the block's bottom edges at most .5 + 2 tan .4 x 1.0086 = 1.35.
  const Projected r = project(scene(0.5, 0.4, "[{box: {min: [-0.5, -0.5, 2], max: [0.5, 0.5, 3]}}]", kRoom,
                                    "[0, 0, 5]", "[0, 0, -1]"));
  const CSpace& c = r.task->cspace;
  const int floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  const int top = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 3));
  ASSERT_GE(floor, 0);
  ASSERT_GE(top, 0);
  EXPECT_TRUE(r.projection.reached.face_region_contains(floor, Vec3(0, 0, 0)));
  EXPECT_TRUE(r.projection.reached.face_region_contains(floor, Vec3(2, 0, 0)));  // 2 < 2.114: straight down
  EXPECT_FALSE(r.projection.reached.face_region_contains(floor, Vec3(2.2, 0, 0)));
  EXPECT_NEAR(r.projection.reached.face_area(top), 1.0, 1e-9);
}

TEST(ForwardProjection, SlidingHalfAngleAbovePiOver2ReachesTheWholeFace) {
  // mu = .1 (phi = .0997), theta_v = .5, v at beta = .45 from -z. Then theta_v > phi and the velocity cone
  // reaches past the floor's normal to the far side (beta - theta_v < 0), so the robot can be pushed
  // "backwards" (Fig 4.19): sliding_cone reports all directions or a half-angle above pi/2, and Alg 4.3
  // returns the whole face from a single start point.
  const Vec3 v(std::sin(0.45), 0, -std::cos(0.45));
  const SlidingCone s = sliding_cone(Vec3::UnitZ(), 0.1, v, 0.5);
  ASSERT_TRUE(s.all || s.half_angle > kPi / 2);
  std::ostringstream velocity;  // (not string concatenation: g++ 12 warns falsely there, -Wrestrict)
  velocity << "[" << v.x() << ", 0, " << v.z() << "]";
  const Projected r = project(scene(0.1, 0.5, "[]", kRoom, "[0, 0, 0]", velocity.str()));
  const int floor = face_at(r.task->cspace, Vec3::UnitZ(), Vec3(0, 0, 0));
  EXPECT_NEAR(r.projection.reached.face_area(floor), 100.0, 1e-9);
}

TEST(ForwardProjection, ConcaveCornerStopsTheSlide) {
  // Room [0,4]x[-2,2]x[0,4], mu = .25 (phi = .2450), theta_v = .25, start (2,0,0) on the floor, v down-left
  // at 45 deg. On the floor -v is pi/4 from the normal > phi + theta_v: never sticks; it slides within the
  // sliding cone about -x of half-angle asin(sin .25 / sin(pi/4)) = .35732 (damper.h closed form) and cannot
  // lift off (v.n = -.707 < -sin .25). It reaches the wall x = 0 along the concave edge for
  // |y| <= 2 tan .35732 = .7467. The edge's summed cone contains cone(-v, .25) (.25 < .3502, damper_test):
  // must stick. The wall is never-stick (pi/4 from its normal). Termination: that edge interval only.
  const Projected r =
      project(scene(0.25, 0.25, "[]", "{min: [0, -2, 0], max: [4, 2, 4]}", "[2, 0, 0]", "[-1, 0, -1]"));
  const auto pieces = r.projection.termination.pieces();
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].kind, AtomKind::kEdge);
  ASSERT_EQ(pieces[0].polygon.size(), 2u);
  const double half = 2 * std::tan(std::asin(std::sin(0.25) / std::sin(kPi / 4)));
  double lo = pieces[0].polygon[0].y(), hi = pieces[0].polygon[1].y();
  if (lo > hi) std::swap(lo, hi);
  EXPECT_NEAR(lo, -half, 1e-6);
  EXPECT_NEAR(hi, half, 1e-6);
  EXPECT_NEAR(pieces[0].polygon[0].x(), 0, 1e-12);
  EXPECT_NEAR(pieces[0].polygon[0].z(), 0, 1e-12);
}

// ---- the built-in two_blocks task (Buckley Fig 4.1) ----

const LoadedTask& two_blocks() {
  static const auto task = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/two_blocks.yaml");
  return *task;
}

TEST(TwoBlocks, DownIsUnreliable) {
  // v1 straight down, theta_v = .25 > phi = .2450: the robot may stick anywhere on B's top but may also slide
  // off it in any direction (friction cone inside the velocity cone). From B's left edge (1.5, y, 3) the cone
  // drops 3 in onto the gap floor within x >= 1.5 - 3 tan .25 = .734, sliding there reaches the whole gap
  // floor; from the right edge it reaches the right floor x in [4.5, 6]. A's top (z = 2, x <= -1.5) is out
  // of reach: from the gap floor nothing lifts off (v.n = -1), and A's right wall only slides down.
  const LoadedTask& t = two_blocks();
  const VerifyResult r = verify_strategy(t, *t.task.find_strategy("down"),
                                         {SpringModel::kViaPoint, test::kRolloutStopRelativeSpeed});
  EXPECT_FALSE(r.reliable);
  ASSERT_EQ(r.steps.size(), 1u);
  const ReachedSet& term = r.steps[0].termination;
  const CSpace& c = t.cspace;
  const int b_top = face_at(c, Vec3::UnitZ(), Vec3(3, 0, 3));
  const int a_top = face_at(c, Vec3::UnitZ(), Vec3(-3, 0, 2));
  const int gap = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  const int right_floor = face_at(c, Vec3::UnitZ(), Vec3(5, 0, 0));
  EXPECT_NEAR(term.face_area(b_top), 3 * 8, 1e-9);  // the whole top of B (3 x 8)
  EXPECT_NEAR(term.face_area(gap), 3 * 8, 1e-9);
  EXPECT_NEAR(term.face_area(right_floor), 1.5 * 8, 1e-9);
  EXPECT_FALSE(term.contains_atom(a_top));
  // Offending pieces: B's top and the right floor are outside the goal; the gap floor is not.
  bool b_top_outside = false;
  for (const ReachedPiece& p : r.outside_goal) {
    b_top_outside = b_top_outside || p.atom == b_top;
    EXPECT_NE(p.atom, gap);
  }
  EXPECT_TRUE(b_top_outside);
}

// A point start within the contact lift of B's right rim (x = 4.5, z = 3): the rollouts' contact cannot tell
// it from a start on the rim, where v3 (down, tilted left) may also slide down B's right wall (it presses
// into it: v3 . (+x) < 0) into the concave edge at its foot, outside the goal. So (v3, v2) from there is
// unreliable with the lift and reliable without it (from B's top proper v3 sticks or slides left, then v2
// slides into the gap); 0.1 in from the rim it is reliable with the lift too.
TEST(TwoBlocks, StartWithinTheContactLiftOfARimHoldsTheRim) {
  const auto base = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/two_blocks.yaml");
  auto at = [&](double x) {
    LoadedTask t = *base;
    t.task.start.points = {Vec3(x, 0, 3)};
    return t;
  };
  const int rim = test::edge_between(base->cspace, Vec3(4.5, -4, 3), Vec3(4.5, 4, 3));
  ASSERT_GE(rim, 0);
  VerifyOptions lift;
  lift.contact_lift = 0.0078;  // two_blocks' rollout_contact_lift
  const Strategy chain = Strategy::sequence("", {"v3", "v2"});
  const LoadedTask near = at(4.5 - 3e-5), inside = at(4.4);
  EXPECT_TRUE(start_set(near, lift).contains_atom(rim));
  EXPECT_FALSE(start_set(near, {}).contains_atom(rim));
  EXPECT_FALSE(start_set(inside, lift).contains_atom(rim));
  EXPECT_FALSE(verify_strategy(near, chain, lift).reliable);
  EXPECT_TRUE(verify_strategy(near, chain).reliable);
  EXPECT_TRUE(verify_strategy(inside, chain, lift).reliable);
}

TEST(TwoBlocks, SlideIsReliable) {
  // v2 down-left at 45 deg never sticks on a face (task file comment: >= .535 rad > phi from every face's
  // into-obstacle normal it can touch); it slides off B's left edge, flies down-left with slopes dz/dx in
  // [.59, 1.68] (so it meets A's right wall at z <= 3 - 3 * .59 = 1.23 < 2, never A's top) and ends in the
  // concave edge x = -1.5, z = 0 (must stick) and its corner vertices, inside the closed goal rectangle.
  const LoadedTask& t = two_blocks();
  const VerifyResult r = verify_strategy(t, *t.task.find_strategy("slide"));
  EXPECT_TRUE(r.reliable) << r.failure;
  ASSERT_EQ(r.steps.size(), 1u);
  const CSpace& c = t.cspace;
  bool corner_edge = false;
  for (const ReachedPiece& p : r.steps[0].termination.pieces()) {
    EXPECT_NE(p.kind, AtomKind::kFace) << c.atom_name(p.atom);  // no face can stick under v2
    if (p.kind == AtomKind::kEdge)
      corner_edge =
          corner_edge || (std::abs(p.polygon[0].x() + 1.5) < 1e-12 && std::abs(p.polygon[0].z()) < 1e-12);
  }
  EXPECT_TRUE(corner_edge);
}

TEST(Verify, CubeSpringStickIsReliable) {
  // cube: inside [-1,1]^3, mu = .25, theta_v = .25, eps_s = eps_p = .2; p1 = (0,0,-3), 2 below the floor.
  // Only the floor and its edges can stick: every wall and the ceiling have p strictly in front (the pull
  // leaves them: no weak sticking), the vertical edges and the ceiling edges have p in front of both faces.
  // The floor's weak disk about (0,0,-1) (h = 2, radius 2 tan(.245 + .25) + .2 / cos(.495) = 1.31) and the
  // floor-wall edges lie in the closed goal (the floor); p is 2 > max(eps_p, eps_s) from free space: no free
  // rest. Reliable.
  const auto t = load_task(std::string(CMT_SOURCE_DIR) + "/models/tasks/cube.yaml");
  const VerifyResult r = verify_strategy(*t, *t->task.find_strategy("stick"),
                                         {SpringModel::kViaPoint, test::kRolloutStopRelativeSpeed});
  EXPECT_TRUE(r.reliable) << r.failure;
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_FALSE(r.steps[0].free_termination);
  for (const ReachedPiece& p : r.steps[0].termination.pieces())
    for (const Vec3& q : p.polygon) EXPECT_NEAR(q.z(), -1, 1e-9) << t->cspace.atom_name(p.atom);
}

}  // namespace
}  // namespace cmt

namespace cmt {
namespace {

// Contact lift (VerifyOptions::contact_lift): floor z = 0 of a room, mu = .75 (phi = .6435), theta_v = .1,
// the damper v = (0, .8, -.6). On the floor the command is acos(.6) = .9273 from -z, beyond phi + theta_v =
// .7435: it slides toward the wall y = 5. On the wall (inward normal +y) it is acos(.8) = .6435 from the
// normal, within phi + theta_v (may stick) but not within phi - theta_v = .5435 (must). Without lift the
// motion ends on the floor-wall edge only; with lift .01 the robot may meet the wall up to .01 above the edge
// and stick there.
TEST(ForwardProjection, ContactLiftSeedsTheWallStripAboveAConcaveEdge) {
  const Compared r =
      project_both(scene(0.75, 0.1, "[]", kRoom, "[0, 0, 0]", "[0, 0.8, -0.6]"), Vec3(0, 0.8, -0.6), 0.01, 0);
  const DamperProjection& plain = r.plain;
  const DamperProjection& lifted = r.modelled;
  EXPECT_GT(plain.termination.distance(Vec3(0, 5, 0.005)), 0.004);   // first-order contact: the edge only
  EXPECT_LE(lifted.termination.distance(Vec3(0, 5, 0.005)), 1e-9);   // inside the strip
  EXPECT_GE(lifted.termination.distance(Vec3(0, 5, 0.02)), 0.0099);  // above it: not reached
}

}  // namespace
}  // namespace cmt

namespace cmt {
namespace {

// Servo coast at an impact (VerifyOptions::servo_coast): from the floor of a room 5 high, mu = .5 (phi =
// .4636), theta_v = .1, straight up. The ceiling (normal -z) holds the command (angle 0 < phi - theta_v):
// must stick, so first-order landings stay where they land: the section of the flight cone at height 5,
// between the disks of radius 5 tan(.1) = .5017 and .5017 / cos(pi/24) = .5060 (24 circumscribing rays). With
// coast c = 1 each landing grows by c times the tangential part of the unit cone velocities: a polygon
// between radius .0998 and .1007 (t = tan(.1) / cos(pi/24) = .1012, t / sqrt(1 + t^2) = .1007, times
// cos(pi/24)). So the ceiling's termination reaches radius .59 (> .5060 + grid) with the coast only, and not
// radius .62 (> .5060 + .1007).
TEST(ForwardProjection, ServoCoastGrowsALandingAlongTheFaceItSticksOn) {
  const Compared r =
      project_both(scene(0.5, 0.1, "[]", kRoom, "[0, 0, 0]", "[0, 0, 1]"), Vec3(0, 0, 1), 0, 1.0);
  const DamperProjection& plain = r.plain;
  const DamperProjection& coasted = r.modelled;
  EXPECT_LE(plain.termination.distance(Vec3(0.5, 0, 5)), 1e-9);
  EXPECT_GT(plain.termination.distance(Vec3(0.59, 0, 5)), 0.08);
  EXPECT_LE(coasted.termination.distance(Vec3(0.59, 0, 5)), 1e-9);
  EXPECT_LE(coasted.termination.distance(Vec3(0, -0.59, 5)), 1e-9);
  EXPECT_GT(coasted.termination.distance(Vec3(0.62, 0, 5)), 0.01);
}

// Servo coast past a convex rim: a 2 x 2 x 1 box on the floor, a room wall at x = 1.5 (normal -x), mu = .5
// (phi = .4636), theta_v = .1, v = (cos .3, 0, -sin .3). On the box top the command is pi/2 - .3 = 1.2708
// from -z, beyond phi + theta_v: the robot slides along +x (the wedge's axis) to the rim x = 1; v.n = -.2955
// < -sin .1, so it cannot fly off before the rim. On the wall the command is .3 from the wall's -normal,
// within phi - theta_v = .3636: must stick. First order, the flight from the rim (1, y, 1) crosses .5 to the
// wall descending tan(.3 - .1012) = .2015 per unit at least (.1012: the 24 circumscribing rays' widest
// angle), so it lands at most at z = 1 - .5 x .2015 = .8993. With coast c = .2 the robot keeps its sliding
// velocity for up to c past the rim: flights start as far as (1.2, 0, 1) and land as high as z = 1 - .3 x
// .2015 = .9396. The landing coast only moves down (every cone velocity descends) or along y, so nothing
// above .9396 + grid.
TEST(ForwardProjection, ServoCoastCarriesAFlightPastARim) {
  const Vec3 v(0.955336489, 0, -0.295520207);
  const Compared r = project_both(
      scene(0.5, 0.1, "[{box: {min: [-1, -1, 0], max: [1, 1, 1]}}]", "{min: [-5, -5, 0], max: [1.5, 5, 5]}",
            "[0.9, 0, 1]", "[0.955336489, 0, -0.295520207]"),
      v, 0, 0.2);
  const DamperProjection& plain = r.plain;
  const DamperProjection& coasted = r.modelled;
  EXPECT_LE(plain.termination.distance(Vec3(1.5, 0, 0.89)), 1e-9);
  EXPECT_GT(plain.termination.distance(Vec3(1.5, 0, 0.92)), 0.015);
  EXPECT_LE(coasted.termination.distance(Vec3(1.5, 0, 0.93)), 1e-9);
  EXPECT_GT(coasted.termination.distance(Vec3(1.5, 0, 0.95)), 0.005);
}

// A narrow slot (models/tasks/geometry/slot.yaml): blocks x <= -.05 and x >= .05, tops z = 0, floor z = -1,
// mu = .3, theta_v = .08, v = (sin 60 deg, 0, -cos 60 deg) from (-1, 0, 0) on the left top. The robot slides
// to the left rim along +x near y = 0 and leaves it descending at least tan(30 deg - .0807) = .4747 per unit
// (.0807: the 24 circumscribing rays' widest angle). First order it meets the right wall at most at z = -.1 x
// .4747 = -.0475. With lift .0047 and coast .0156 (the prism reaches at most .0157 past the rim) at most at
// z = .0047 - (.1 - .0157) x .4747 = -.0353: the right block's top (z = 0) stays out of reach. The rim
// coast's hits on the slot's own left wall are the rim segment rounded to the region grid (a sliver on the
// rim's line), not landings, so the rim's reach stays near y = 0 rather than creeping along the rim round
// after round. The coast itself still applies: the right wall is reached at z = -.04 with it and not without.
TEST(ForwardProjection, RimCoastDoesNotCreepAlongTheRimOfASlot) {
  const Compared r = project_both(
      scene(0.3, 0.08,
            "[{box: {min: [-3, -2, -1], max: [-0.05, 2, 0]}}, {box: {min: [0.05, -2, -1], max: [3, 2, 0]}}]",
            "{min: [-3, -2, -1], max: [3, 2, 2]}", "[-1, 0, 0]", "[0.8660254037844386, 0, -0.5]"),
      Vec3(0.8660254037844386, 0, -0.5), 0.0047, 0.0156);
  for (const DamperProjection* p : {&r.plain, &r.modelled}) {
    EXPECT_GT(p->reached.distance(Vec3(0.06, 0, 0)), 0.01);  // the right block's top, beside its rim
    EXPECT_GT(p->reached.distance(Vec3(1, 0, 0)), 0.5);
    EXPECT_GT(p->reached.distance(Vec3(-0.05, 0.5, 0)), 0.3);     // the left rim far from y = 0
    EXPECT_LE(p->termination.distance(Vec3(0.05, 0, -1)), 1e-9);  // the slot's bottom right corner
  }
  EXPECT_LE(r.modelled.reached.distance(Vec3(0.05, 0, -0.04)), 1e-9);
  EXPECT_GT(r.plain.reached.distance(Vec3(0.05, 0, -0.04)), 0.005);
}

}  // namespace
}  // namespace cmt

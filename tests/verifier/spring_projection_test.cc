// Hand-checked geometry of the generalized-spring forward projection (Buckley §3.3, §4.4, Alg 4.4). Every
// expected value is derived in the comments from the scene, not taken from the program's output.
//
// Common numbers (eps_s = eps_p = step = .1, theta_v = .1, mu = .5, phi = atan .5 = .4636):
//   eps_t = .1 + .1 e^{-t_t} sin .1, t_t = .1 / tan .1 = .99667: eps_t = .1 + .1 (.3691) (.09983) = .10368;
//   eps_o = .1 + (.1 + .2)(1 + e^{-t_o} sin .1), t_o = (.1 + pi/2) / tan .1 = 16.65: eps_o = .4000;
//   free-space rest radius max(eps_p, eps_s) = .1.
#include "verifier/spring_projection.h"

#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "tests/verifier/test_geometry.h"
#include "verifier/spring.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

std::string scene(const std::string& start, const std::string& p) {
  return "name: t\nunits: in\nfriction: 0.5\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: "
         "0.1, "
         "step: 0.1}\ncspace: []\nbounds: {min: [-5, -5, 0], max: [5, 5, 5]}\nstart: {point: " +
         start + "}\ngoal: {point: " + start + "}\nmotions:\n  m: {spring: " + p +
         "}\nstrategies:\n  s: [m]\n";
}

using test::face_at;

struct Projected {
  std::shared_ptr<const LoadedTask> task;
  SpringProjection projection;
  int floor = -1, wall = -1;  // z = 0, y = 5
};

Projected project(const std::string& yaml) {
  auto task = load_task_from_string(yaml, "test");
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  SpringProjection p = forward_project_spring(*task, start, task->task.motions.at(0).target);
  Projected out{task, std::move(p)};
  out.floor = face_at(task->cspace, Vec3(0, 0, 1), Vec3(0, 0, 0));
  out.wall = face_at(task->cspace, Vec3(0, -1, 0), Vec3(0, 5, 1));
  return out;
}

TEST(SpringProjection, ToleranceValues) {
  const Uncertainty u{0.1, 0.1, 0.1, 0.1, 0.1};
  EXPECT_NEAR(eps_t(u), 0.10368, 1e-5);
  EXPECT_NEAR(eps_o(u), 0.4000, 1e-4);
  EXPECT_DOUBLE_EQ(spring_rest_radius(u), 0.1);
}

TEST(SpringProjection, StartInsideStrongDiskStaysPut) {
  // p = (0,0,-5), 5 below the floor. Strong disk (Fig 3.16): alpha = phi - theta_v = .3636, radius (5 -
  // .1 / sin .3636) tan .3636 = (5 - .2800)(.3805) = 1.796 about the origin. The start (.5,0,0) is inside:
  // it sticks, nothing slides; it cannot leave either ((5 - .1) > tan(.1)(.5 + .1) = .06). Termination: the
  // start point alone; p is 5 from free space (> .1): no free rest.
  const Projected r = project(scene("[0.5, 0, 0]", "[0, 0, -5]"));
  const auto pieces = r.projection.termination.pieces();
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].atom, r.floor);
  ASSERT_EQ(pieces[0].polygon.size(), 1u);
  EXPECT_NEAR((pieces[0].polygon[0] - Vec3(0.5, 0, 0)).norm(), 0, 1e-12);
  EXPECT_FALSE(r.projection.free_termination);
  EXPECT_FALSE(r.projection.may_not_terminate);
}

TEST(SpringProjection, SlidesTowardProjectionWithinStrip) {
  // Start (3,0,0) is outside the strong disk (1.796): it slides toward p' = (0,0,0) within eps_t = .1037 of
  // the x axis (Fig 3.14), overshooting p' by the projection of the free-space overshoot eps_o = .4: at most
  // eps_o d / sqrt(d^2 + h^2) with d = 3 + eps_s = 3.1 (the farthest entry, plus the sensing error) and h = 5
  // - eps_s = 4.9, i.e. .4 (3.1 / 5.798) = .2139. The strip is x in [-.2139 - .1037, 3 + .1037] = [-.3176,
  // 3.104], |y| <= .104 (the circumscribed 24-gon adds < 1 %: -.3185 at most). Weak disk radius: h tan(phi +
  // theta_v) + eps_s / cos(psi) = 5 (.6325) + .1 / .8453 = 3.28 > 3.11: the whole strip may stick. No
  // flight: the largest tangential distance 3.11 gives tan(.1)(3.11 + .1) = .32 < 4.9, so nothing reaches the
  // walls.
  const Projected r = project(scene("[3, 0, 0]", "[0, 0, -5]"));
  const ReachedSet& t = r.projection.termination;
  EXPECT_EQ(t.atoms(), std::vector<int>{r.floor});
  for (double x : {-0.31, 0.0, 1.5, 3.05}) EXPECT_TRUE(t.face_region_contains(r.floor, Vec3(x, 0, 0))) << x;
  EXPECT_TRUE(t.face_region_contains(r.floor, Vec3(1.5, 0.1, 0)));
  EXPECT_FALSE(t.face_region_contains(r.floor, Vec3(1.5, 0.12, 0)));
  EXPECT_FALSE(t.face_region_contains(r.floor, Vec3(3.12, 0, 0)));
  // The full eps_o = .4 overshoot in the plane (the earlier model) would reach -.504.
  EXPECT_FALSE(t.face_region_contains(r.floor, Vec3(-0.33, 0, 0)));
  EXPECT_FALSE(r.projection.free_termination);
}

TEST(SpringProjection, SlidesAlongFloorIntoWallCorner) {
  // p = (0,7,-1): 1 below the floor, 2 behind the wall y = 5. From (0,0,0) the robot slides along +y (p' =
  // (0,7,0) is beyond the floor) in |x| <= .104 to the floor-wall edge y = 5. No lift-off: on the floor (1 -
  // .1) > tan(.1)(7.1 + .1) = .72. Floor weak disk: radius 1 (.6325) + .118 = .75 about (0,7): no floor point
  // (y <= 5) may stick. The corner edge may stick (p - x = (-x, 2, -1) lies in -(cone(-y) + cone(z))).
  // Along the edge: q = (0,5,0), |p - q| = 2.236, either-way zone s - .1 <= sin(.1)(sqrt(5 + s^2) + .1):
  // s = .33 < eps_o = .4, so the edge interval is |x| <= .4 (+ the strip's .104 inside it). Onto the wall:
  // the in-wall direction away from the edge is +z and (p - x).z + eps_s + sin(.1)(|p - x| + eps_s) = -1 +
  // .1 + .0998 (2.27 + .1) = -.66 < 0 at x = +-.4: the pull never climbs the wall. No flight from the
  // concave edge (the floor cannot be left). Termination: the edge interval alone.
  const Projected r = project(scene("[0, 0, 0]", "[0, 7, -1]"));
  const ReachedSet& t = r.projection.termination;
  EXPECT_EQ(t.face_area(r.floor), 0);
  EXPECT_FALSE(t.contains_atom(r.wall));
  bool edge = false;
  for (const ReachedPiece& piece : t.pieces()) {
    if (piece.kind != AtomKind::kEdge) continue;
    edge = true;
    for (const Vec3& q : piece.polygon) {
      EXPECT_NEAR(q.y(), 5, 1e-12);
      EXPECT_NEAR(q.z(), 0, 1e-12);
      EXPECT_LE(std::abs(q.x()), 0.41);
      EXPECT_GE(std::abs(q.x()), 0.39);
    }
  }
  EXPECT_TRUE(edge);
  EXPECT_FALSE(r.projection.free_termination);
}

// Staying on an edge (spring_projection.cc, edge_leave_halfwidth): the robot slides along an edge only where
// it may push into the faces that hold it there. theta_v = 0 and eps_p = 0 make eps_t = 0 (eq. 3.21), so the
// flights from the start touch the faces only at the start itself and the edge's reach is the edge rule's
// alone: eps_o = eps_p + step + 2 eps_p = .1, and along the edge the either-way zone is s* = eps_s = .1.
std::string edge_scene(const std::string& cspace, const std::string& start, const std::string& p) {
  return "name: t\nunits: in\nfriction: 0.5\nuncertainty: {eps_s: 0.1, eps_p: 0, theta_v: 0, theta_f: 0.1, "
         "step: 0.1}\ncspace:" +
         cspace + "\nbounds: {min: [-5, -5, 0], max: [5, 5, 5]}\nstart: {point: " + start +
         "}\ngoal: {point: " + start + "}\nmotions:\n  m: {spring: " + p + "}\nstrategies:\n  s: [m]\n";
}

// Flight sections and edge intervals are rounded outward (docs/verifier.md); the spans below move by < 1e-3
// (measured 8.5e-5 and 6.1e-4 in the concave case), far below the effects tested (.1 to 7).
inline constexpr double kOutwardRounding = 1e-3;

// The reached parameter span of edge `edge` along coordinate `axis` (lowest, highest), or {inf, -inf}.
std::pair<double, double> edge_span(const ReachedSet& reached, int edge, int axis) {
  std::pair<double, double> span{1e300, -1e300};
  for (const ReachedPiece& piece : reached.pieces())
    if (piece.atom == edge)
      for (const Vec3& q : piece.polygon) {
        span.first = std::min(span.first, q[axis]);
        span.second = std::max(span.second, q[axis]);
      }
  return span;
}

TEST(SpringProjection, RobotDoesNotSlideAlongAConvexEdgeItMustLeave) {
  // A block [-2,2] x [-2,2] x [0,1]; start on its convex top rim x = 2, z = 1 at y = -1; p = (4,3,2), 1 above
  // the top and 2 in front of the side x = 2. Along the rim the robot would move toward q = (2,3,1), beyond
  // the corner y = 2. On a convex edge it stays only while it may push into both faces; with theta_v = 0 the
  // pull p - x̂ points away from the side face whenever (p - x).n - eps_s = 2 - .1 > 0, at every rim point.
  // So it leaves at once: the rim is reached at the start only, and the corner (2,2,1) is not reached.
  auto task = load_task_from_string(
      edge_scene("\n  - box: {min: [-2, -2, 0], max: [2, 2, 1]}", "[2, -1, 1]", "[4, 3, 2]"), "test");
  const SpringProjection p = forward_project_spring(*task, ReachedSet::from_region(*task, task->task.start),
                                                    task->task.motions.at(0).target);
  const int rim = test::edge_between(task->cspace, Vec3(2, -2, 1), Vec3(2, 2, 1));
  ASSERT_GE(rim, 0);
  const auto [lo, hi] = edge_span(p.reached, rim, 1);
  EXPECT_NEAR(lo, -1, kOutwardRounding);
  EXPECT_NEAR(hi, -1, kOutwardRounding);
  const int corner = test::vertex_at(task->cspace, Vec3(2, 2, 1));
  ASSERT_GE(corner, 0);
  EXPECT_FALSE(p.reached.contains_atom(corner));
}

TEST(SpringProjection, RobotSlidesAlongAConcaveEdgeOnlyWhilePushingIntoBothFaces) {
  // The concave edge between the floor z = 0 and a wall block y >= 3 (its face y = 3), start (-4,3,0).
  // (i) p = (3,4,-.5) lies behind the wall and below the floor: the pull pushes into both faces at every edge
  // point, so the robot slides along the edge toward q = (3,3,0) and, with theta_v = 0, either way within s*
  // = eps_s = .1 of it (eps_o = .1 too): x up to 3.1. (ii) p = (3,1,.1) lies 2 in front of the wall: the pull
  // leaves the wall at every edge point ((p - x).n - eps_s = 2 - .1 > 0), so the robot leaves the edge at
  // once (onto the floor, which it still pushes into: .1 - eps_s = 0) and the edge is reached at the start
  // only.
  const std::string wall = "\n  - box: {min: [-5, 3, 0], max: [5, 5, 5]}";
  const int axis_x = 0;
  for (const auto& [p, hi_expected] : {std::pair<std::string, double>{"[3, 4, -0.5]", 3.1},
                                       std::pair<std::string, double>{"[3, 1, 0.1]", -4}}) {
    auto task = load_task_from_string(edge_scene(wall, "[-4, 3, 0]", p), "test");
    const SpringProjection proj = forward_project_spring(
        *task, ReachedSet::from_region(*task, task->task.start), task->task.motions.at(0).target);
    const int edge = test::edge_between(task->cspace, Vec3(-5, 3, 0), Vec3(5, 3, 0));
    ASSERT_GE(edge, 0);
    const auto [lo, hi] = edge_span(proj.reached, edge, axis_x);
    EXPECT_NEAR(lo, -4, kOutwardRounding) << p;
    EXPECT_NEAR(hi, hi_expected, kOutwardRounding) << p;
  }
}

TEST(SpringProjection, CreepingReachIsWidenedToTheWholeAtom) {
  // The block of RobotDoesNotSlideAlongAConvexEdgeItMustLeave with theta_v = .1 (eps_t = .1037) and p =
  // (4,3,1), level with the top (h = 0: the robot may slide on the top toward p' = p, and may leave it
  // anywhere). From the rim at y = -1 a flight toward p lands on the top within eps_t of its source, behind
  // the rim too (the cylinder holds the ball about its source); the top's strip toward p' then reaches the
  // rim again up to ~eps_t further along (+y), and so on: the reach creeps along the rim by a fraction of
  // eps_t per round, toward the corner y = 2 (4 in away). Widening takes the top face and the rim whole after
  // kSpringWideningRounds growths, which contains every later round of the creep: the corner (2,2,1) is
  // reached, as the unwidened creep reaches it (measured: in ~37 s instead of < 1 s).
  const std::string yaml =
      "name: t\nunits: in\nfriction: 0.5\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: 0.1, "
      "step: 0.1}\ncspace:\n  - box: {min: [-2, -2, 0], max: [2, 2, 1]}\nbounds: {min: [-5, -5, 0], max: [5, "
      "5, "
      "5]}\nstart: {point: [2, -1, 1]}\ngoal: {point: [2, -1, 1]}\nmotions:\n  m: {spring: [4, 3, 1]}\n"
      "strategies:\n  s: [m]\n";
  auto task = load_task_from_string(yaml, "test");
  const SpringProjection p = forward_project_spring(*task, ReachedSet::from_region(*task, task->task.start),
                                                    task->task.motions.at(0).target);
  EXPECT_GT(p.widened, 0);
  EXPECT_FALSE(p.fallback);
  const int top = face_at(task->cspace, Vec3(0, 0, 1), Vec3(0, 0, 1));
  ASSERT_GE(top, 0);
  EXPECT_NEAR(p.reached.face_area(top), 16, 1e-9);  // the whole 4 x 4 top
  const int corner = test::vertex_at(task->cspace, Vec3(2, 2, 1));
  ASSERT_GE(corner, 0);
  EXPECT_TRUE(p.reached.contains_atom(corner));
}

TEST(SpringProjection, FreeSpaceCommandRestsInFreeSpace) {
  // p = (0,0,2): 2 above the floor, in free space. On the floor the pull always leaves ((2 - .1) > tan(.1)(0
  // + .1)), so nothing slides; the robot flies toward p and may rest within max(eps_p, eps_s) = .1 of it. The
  // flight volume (eps_t = .104 about the segment, overshoot .4) reaches no other face (z <= 2.51, |x|,|y| <=
  // .51). No contact termination (p above the floor: no weak sticking).
  const Projected r = project(scene("[0, 0, 0]", "[0, 0, 2]"));
  EXPECT_TRUE(r.projection.free_termination);
  EXPECT_DOUBLE_EQ(r.projection.free_radius, 0.1);
  EXPECT_TRUE(r.projection.termination.empty());
  EXPECT_FALSE(r.projection.may_not_terminate);
  EXPECT_EQ(r.projection.reached.atoms(), std::vector<int>{r.floor});
  // verify: the strategy fails at that motion.
  const VerifyResult v = verify_motions(*r.task, {"m"});
  EXPECT_FALSE(v.reliable);
  EXPECT_EQ(v.failed_step, 0);
  EXPECT_TRUE(v.steps[0].free_termination);
}

}  // namespace
}  // namespace cmt

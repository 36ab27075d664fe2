// Conditional strategies (Buckley §4.2, Fig 4.2; docs/verifier.md "Conditional strategies"): removing the
// points that surely pass a test (ReachedSet::without_box, without_strongly_consistent) and the verification
// of strategy trees. Expected values are derived by hand in the comments; the room is the sensing room of
// tests/verifier/sensing_tasks.h (10 x 10 x 5 in, eps_s = theta_v = theta_f = .1, mu = .25).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "models/task_loader.h"
#include "tests/verifier/sensing_tasks.h"
#include "tests/verifier/test_geometry.h"
#include "verifier/atom_cone.h"
#include "verifier/sensing_termination.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

using test::edge_between;

using test::face_at;

// Shrinking by kSensingBoxRelativeSlack x scale (diagonal 15) moves each side by 1.5e-8: areas within 1e-6.
constexpr double kAreaTolerance = 1e-6;

struct Room {
  std::shared_ptr<const LoadedTask> task;
  int floor = -1, wall = -1, edge = -1;
  ReachedSet all;
  explicit Room(const std::string& yaml = test::sensing_room(""))
      : task(load_task_from_string(yaml, "room")), all(task->cspace) {
    const CSpace& c = task->cspace;
    floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
    wall = face_at(c, -Vec3::UnitX(), Vec3(5, 0, 1));
    edge = edge_between(c, Vec3(5, -5, 0), Vec3(5, 5, 0));  // floor meets the wall x = 5
    for (int id = 0; id < c.atom_count(); ++id) all.add_whole_atom(id);
  }
  // The edge's parameter t of a point (5, y, 0) on it.
  double t_of(double y) const {
    const Edge& e = task->cspace.edges()[task->cspace.atom_index(edge)];
    return (Vec3(5, y, 0) - e.a).dot(e.b - e.a) / (e.b - e.a).squaredNorm();
  }
};

TEST(WithoutBox, RemovesExactlyTheClosedBoxPart) {
  const Room r;
  ASSERT_GE(r.floor, 0);
  ASSERT_GE(r.wall, 0);
  ASSERT_GE(r.edge, 0);
  // Box x in [4, 6], |y| <= 1, z in [-1, .5]: the floor loses [4, 5] x [-1, 1] (area 2 of 100), the wall x =
  // 5 loses |y| <= 1, z <= .5 (area 1 of 50), the edge x = 5 loses y in [-1, 1] (t in [.4, .6], shrunk by the
  // slack), no vertex is inside.
  const ReachedSet rest = r.all.without_box({Vec3(4, -1, -1), Vec3(6, 1, 0.5)});
  EXPECT_NEAR(rest.face_area(r.floor), 98.0, 1e-12);
  EXPECT_NEAR(rest.face_area(r.wall), 49.0, 1e-12);
  const auto iv = rest.edge_intervals(r.edge);
  ASSERT_EQ(iv.size(), 2u);
  EXPECT_EQ(iv[0].t0, 0.0);
  EXPECT_NEAR(iv[0].t1, std::min(r.t_of(-1), r.t_of(1)), 1e-11);
  EXPECT_NEAR(iv[1].t0, std::max(r.t_of(-1), r.t_of(1)), 1e-11);
  EXPECT_EQ(iv[1].t1, 1.0);
  for (const Vertex& v : r.task->cspace.vertices()) EXPECT_TRUE(rest.has_vertex(v.id));
  // The region is closed: the box's boundary stays (x = 4 on the floor), its inside does not.
  EXPECT_TRUE(rest.face_region_contains(r.floor, Vec3(4, 0, 0)));
  EXPECT_FALSE(rest.face_region_contains(r.floor, Vec3(4.5, 0, 0)));
  EXPECT_TRUE(rest.face_region_contains(r.floor, Vec3(4.5, 1.01, 0)));
  // A box touching the floor plane (max z = 0) holds the floor's closed part: it goes. A box above it does
  // not.
  EXPECT_NEAR(r.all.without_box({Vec3(-1, -1, -1), Vec3(1, 1, 0)}).face_area(r.floor), 96.0, 1e-12);
  EXPECT_NEAR(r.all.without_box({Vec3(-1, -1, 0.1), Vec3(1, 1, 1)}).face_area(r.floor), 100.0, 1e-12);
  // A box holding the room removes everything.
  EXPECT_TRUE(r.all.without_box({Vec3(-6, -6, -1), Vec3(6, 6, 6)}).empty());
}

TEST(WithoutBox, CutsSegmentsAndDropsPointsInside) {
  const Room r;
  ReachedSet s(r.task->cspace);
  s.add_face_segment(r.floor, Vec3(-4, 0, 0), Vec3(4, 0, 0));
  s.add_face_point(r.floor, Vec3(1.5, 0.5, 0));
  s.add_face_point(r.floor, Vec3(0, 3, 0));
  // Box x in [1, 2], |y| <= 1: the segment keeps x in [-4, 1] and [2, 4]; (1.5, .5) goes; (0, 3) stays.
  const ReachedSet rest = s.without_box({Vec3(1, -1, -1), Vec3(2, 1, 1)});
  EXPECT_NEAR(rest.distance(Vec3(1.5, 0, 0)), 0.5, 1e-12);
  EXPECT_NEAR(rest.distance(Vec3(1, 0, 0)), 0, 1e-12);
  EXPECT_NEAR(rest.distance(Vec3(2, 0, 0)), 0, 1e-12);
  EXPECT_NEAR(rest.distance(Vec3(-4, 0, 0)), 0, 1e-12);
  EXPECT_NEAR(rest.distance(Vec3(1.5, 0.5, 0)), std::sqrt(0.25 + 0.25), 1e-12);  // nearest (1, 0) or (2, 0)
  EXPECT_NEAR(rest.distance(Vec3(0, 3, 0)), 0, 1e-12);
}

TEST(StronglyConsistent, PositionShrinksTheBoxByEpsS) {
  const Room r;
  const AtomCones cones(r.task->cspace);
  // P = x in [4, 6], |y| <= 1, z in [-1, .5]; shrunk by eps_s = .1: x in [4.1, 5.9], |y| <= .9, z in [-.9,
  // .4]. Every reading at those points is inside P; the floor loses .9 x 1.8 = 1.62, the wall |y| <= .9 by z
  // in [0, .4] = .72.
  MotionTermination test;
  test.position.push_back({Vec3(4, -1, -1), Vec3(6, 1, 0.5)});
  const ReachedSet rest = without_strongly_consistent(*r.task, cones, test, r.all);
  EXPECT_NEAR(rest.face_area(r.floor), 100 - 1.62, kAreaTolerance);
  EXPECT_NEAR(rest.face_area(r.wall), 50 - 0.72, kAreaTolerance);
  EXPECT_TRUE(rest.face_region_contains(r.floor, Vec3(4.05, 0, 0)));  // a reading may fall at x < 4
  EXPECT_FALSE(rest.face_region_contains(r.floor, Vec3(4.15, 0, 0)));
  // A box narrower than the sensing ball (x in [0, .15] < 2 eps_s) is never surely passed.
  MotionTermination thin;
  thin.position.push_back({Vec3(0, -1, -1), Vec3(0.15, 1, 1)});
  EXPECT_NEAR(without_strongly_consistent(*r.task, cones, thin, r.all).area(), r.all.area(), 1e-9);
}

// A planar task (tests/experiments/data/ridge_planar.yaml: the ridge in x-z, eps_s = .1): the sensing error
// lies in the x-z plane, so a box read from the file (spanning the clip slab in y) is surely passed across
// the whole slab. The right floor x in [.5, 3] (area 2.5 over the slab's depth 1) inside x in [0, 4], |z| <=
// 1 shrunk by eps_s goes whole; shrinking y as well would keep two strips of 2.5 x .1.
TEST(StronglyConsistent, PlanarBoxesAreSurelyPassedAcrossTheSlab) {
  const auto task = load_task(std::string(CMT_SOURCE_DIR) + "/tests/experiments/data/ridge_planar.yaml");
  const AtomCones cones(task->cspace);
  const Region right_floor = task->task.goal.back();
  const ReachedSet floor = ReachedSet::from_region(*task, right_floor);
  ASSERT_NEAR(floor.area(), 2.5, kAreaTolerance);
  MotionTermination test;
  test.position.push_back({Vec3(0, -kPlanarClipHalfDepth, -1), Vec3(4, kPlanarClipHalfDepth, 1)});
  EXPECT_NEAR(without_strongly_consistent(*task, cones, test, floor).area(), 0, kAreaTolerance);
  // x in [1, 2] only: the floor keeps x in [.5, 1.1] and [1.9, 3], 0.6 + 1.1, across the slab.
  MotionTermination part;
  part.position.push_back({Vec3(1, -kPlanarClipHalfDepth, -1), Vec3(2, kPlanarClipHalfDepth, 1)});
  EXPECT_NEAR(without_strongly_consistent(*task, cones, part, floor).area(), 1.7, kAreaTolerance);
}

TEST(StronglyConsistent, ForceTakesOnlyFacesWhoseWidenedConeFits) {
  const Room r;
  const AtomCones cones(r.task->cspace);
  // The floor's cone widened by theta_f: cone(+z, atan .25 + .1 = .3450). Inside F_s = cone(+z, .6): every
  // floor point surely passes, and nothing else does (the wall's axis is pi/2 away; edges and vertices are
  // never taken). Inside cone(+z, .3)? No: .345 > .3, nothing is removed.
  MotionTermination up;
  up.force.push_back({Vec3::UnitZ(), 0.6});
  const ReachedSet rest = without_strongly_consistent(*r.task, cones, up, r.all);
  EXPECT_EQ(rest.face_area(r.floor), 0.0);
  EXPECT_NEAR(rest.face_area(r.wall), 50.0, 1e-12);
  EXPECT_EQ(rest.edge_intervals(r.edge).size(), 1u);
  MotionTermination narrow;
  narrow.force.push_back({Vec3::UnitZ(), 0.3});
  EXPECT_NEAR(without_strongly_consistent(*r.task, cones, narrow, r.all).area(), r.all.area(), 1e-9);
  // Position and force: the box of the position test on the faces that surely pass the force (the floor):
  // the floor loses 1.62 as above, the wall keeps all of its 50.
  MotionTermination both = up;
  both.position.push_back({Vec3(4, -1, -1), Vec3(6, 1, 0.5)});
  const ReachedSet rest2 = without_strongly_consistent(*r.task, cones, both, r.all);
  EXPECT_NEAR(rest2.face_area(r.floor), 100 - 1.62, kAreaTolerance);
  EXPECT_NEAR(rest2.face_area(r.wall), 50.0, 1e-12);
}

// The room with strategy `s` replaced by `strategy` (YAML under "strategies:").
std::string room_with(const std::string& strategy, const std::string& terminate = "") {
  std::string yaml = test::sensing_room(terminate);
  return yaml.substr(0, yaml.find("strategies:")) + "strategies:\n" + strategy;
}

// The motion m slides from the start square to the edge x = 5 and sticks there only: its termination set is
// that edge for |y| <= 1 + 9.5 t, t = tan(asin(sin .1 / sin 45deg)) = .142616 (1 + 9.5 t = 2.3549), which is
// the goal.
TEST(ConditionalVerify, ATestEveryEndSurelyPassesIsReliable) {
  // Test: x in [4, 6], |y| <= 4, |z| <= 1, shrunk: |y| <= 3.9 holds the whole termination set.
  const Room r(
      room_with("  c:\n    - m\n    - branch:\n        - when: {position: {box: {min: [4, -4, -1], max: "
                "[6, 4, 1]}}}\n          then: [m]\n"));
  const VerifyResult v = verify_strategy(*r.task, *r.task->task.find_strategy("c"));
  EXPECT_TRUE(v.reliable) << v.failure;
  ASSERT_EQ(v.steps.size(), 2u);
  EXPECT_EQ(v.steps[0].node, 0);
  EXPECT_EQ(v.steps[0].parent, -1);
  ASSERT_EQ(v.steps[0].branches.size(), 1u);
  EXPECT_EQ(v.steps[0].branches[0].step, 1);
  ASSERT_NE(v.steps[0].unmatched, nullptr);
  EXPECT_TRUE(v.steps[0].unmatched->empty());
  // Branch 0 starts from the whole termination set; m from the sticking edge sticks there again.
  EXPECT_EQ(v.steps[0].branches[0].start->atoms(), v.steps[0].termination.atoms());
  EXPECT_EQ(v.steps[1].node, 1);
  EXPECT_EQ(v.steps[1].parent, 0);
  EXPECT_EQ(v.steps[1].branch, 0);
  EXPECT_EQ(v.node_step, (std::vector<int>{0, 1}));
  EXPECT_EQ(v.steps[1].termination.atoms(), std::vector<int>{r.edge});
}

TEST(ConditionalVerify, EndsThatMayPassNoTestFailWithoutElse) {
  // Test |y| <= 2, shrunk |y| <= 1.9: the edge ends with 1.9 < |y| <= 2.3549 may read outside it.
  const std::string test = "{position: {box: {min: [4, -2, -1], max: [6, 2, 1]}}}";
  const Room r(room_with("  c:\n    - m\n    - branch: [{when: " + test +
                         ", then: []}]\n  e:\n    - m\n    - "
                         "branch: [{when: " +
                         test + ", then: []}, {else: []}]\n"));
  const VerifyResult v = verify_strategy(*r.task, *r.task->task.find_strategy("c"));
  EXPECT_FALSE(v.reliable);
  EXPECT_EQ(v.failed_step, 0);
  EXPECT_NE(v.failure.find("may pass no branch test"), std::string::npos) << v.failure;
  const auto iv = v.steps[0].unmatched->edge_intervals(r.edge);
  ASSERT_EQ(iv.size(), 2u);
  const double reach = 1 + 9.5 * std::tan(std::asin(std::sin(0.1) / std::sin(std::numbers::pi / 4)));
  const double lo = std::min(r.t_of(-reach), r.t_of(reach)), hi = std::max(r.t_of(-reach), r.t_of(reach));
  const double a = std::min(r.t_of(-1.9), r.t_of(1.9)), b = std::max(r.t_of(-1.9), r.t_of(1.9));
  EXPECT_NEAR(iv[0].t0, lo, 1e-6);
  EXPECT_NEAR(iv[0].t1, a, 1e-6);
  EXPECT_NEAR(iv[1].t0, b, 1e-6);
  EXPECT_NEAR(iv[1].t1, hi, 1e-6);
  // With `else: []` those ends stop there, on the goal edge: reliable, and the else branch starts from them.
  const VerifyResult e = verify_strategy(*r.task, *r.task->task.find_strategy("e"));
  EXPECT_TRUE(e.reliable) << e.failure;
  ASSERT_EQ(e.steps.at(0).branches.size(), 2u);
  EXPECT_EQ(e.steps[0].unmatched, nullptr);
  EXPECT_EQ(e.steps[0].branches[1].start->edge_intervals(r.edge).size(), 2u);
  EXPECT_EQ(e.steps[0].branches[1].step, -1);
}

TEST(ConditionalVerify, ABranchThatStopsOutsideTheGoalFailsAndUnreachableBranchesAreSkipped) {
  // m also terminates by sensing in P_s = x in [0, 1], |y|, |z| <= .5 (the floor rectangle 1.2 x 1.2 grown by
  // eps_s, see sensing_termination_test.cc). Branch 0 (x <= 2) stops there: outside the goal edge. Branch 1
  // (a box up at z >= 3) holds no termination point: not reachable, not simulated. Branch 2 (else) starts
  // from the edge and runs m, which sticks there again.
  const Room r(
      room_with("  c:\n    - m\n    - branch:\n        - when: {position: {box: {min: [-2, -2, -1], "
                "max: [2, 2, 1]}}}\n          then: []\n        - when: {position: {box: {min: [-5, -5, "
                "3], max: [5, 5, 5]}}}\n          then: [m]\n        - else: [m]\n",
                "{position: {box: {min: [0, -0.5, -0.5], max: [1, 0.5, 0.5]}}}"));
  const VerifyResult v = verify_strategy(*r.task, *r.task->task.find_strategy("c"));
  EXPECT_FALSE(v.reliable);
  EXPECT_EQ(v.failed_step, 0);
  EXPECT_NE(v.failure.find("which stops there"), std::string::npos) << v.failure;
  ASSERT_EQ(v.steps[0].branches.size(), 3u);
  EXPECT_NEAR(v.steps[0].branches[0].start->face_area(r.floor), 1.44, kAreaTolerance);
  EXPECT_TRUE(v.steps[0].branches[1].start->empty());
  EXPECT_EQ(v.steps[0].branches[1].step, -1);
  // The else branch: the floor rectangle surely passes test 0 (shrunk x in [-1.9, 1.9] holds x in [-.1, 1.1])
  // and goes; the edge stays and is simulated (sibling branches run after a failure).
  EXPECT_EQ(v.steps[0].branches[2].start->face_area(r.floor), 0.0);
  EXPECT_EQ(v.steps[0].branches[2].start->atoms(), std::vector<int>{r.edge});
  EXPECT_EQ(v.steps[0].branches[2].step, 1);
  ASSERT_EQ(v.steps.size(), 2u);
  EXPECT_EQ(v.steps[1].node, 2);
  EXPECT_EQ(v.node_step, (std::vector<int>{0, -1, 1}));
  EXPECT_EQ(v.step_of_node(1), nullptr);
  EXPECT_EQ(v.step_of_node(2), &v.steps[1]);
}

// The gap floor that v3 reaches from B's top centre (3, 0, 3) in two_blocks, constructed by hand
// (docs/verifier.md "Damper forward projection"): on a horizontal face v3 (beta = atan .3 from the inward
// normal, theta_v = .25, phi = atan .25) slides within the wedge of half-angle omega about -x where the
// velocity cone's rim crosses the friction cone (the sliding cone's second regime: cos omega = (cos theta -
// cos phi cos beta) / (sin phi sin beta), omega = .965); it reaches B's left rim x = 1.5 for |y| <= 1.5 tan
// omega (the rim is convex and v3 leaves B's left face, so the robot does not slide along it); flights along
// the 24-gon circumscribing cone(v3, theta_v) (damper_flight.h's rays) land 3 below; on the gap floor the
// robot slides left within the same wedge to A's wall. The area of that convex set clipped to the gap floor
// [-1.5, 1.5] x [-4, 4].
double two_blocks_tilt_gap_area() {
  const Vec3 v = Vec3(-0.3, 0, -1).normalized();
  const double theta = 0.25, phi = std::atan(0.25), beta = std::acos(-v.z());
  const double omega =
      std::acos((std::cos(theta) - std::cos(phi) * std::cos(beta)) / (std::sin(phi) * std::sin(beta)));
  const double rim = 1.5 * std::tan(omega);
  const Vec3 e1 = Vec3::UnitX().cross(v).normalized(), e2 = v.cross(e1);
  const double radius = std::tan(theta) / std::cos(std::numbers::pi / 24);
  std::vector<Eigen::Vector2d> pts;
  for (double y0 : {-rim, rim})
    for (int k = 0; k < 24; ++k) {
      const double a = 2 * std::numbers::pi * k / 24;
      const Vec3 ray = v + radius * (std::cos(a) * e1 + std::sin(a) * e2);
      const Eigen::Vector2d land(1.5 + 3 * ray.x() / -ray.z(), y0 + 3 * ray.y() / -ray.z());
      pts.push_back(land);
      for (double side : {-1.0, 1.0})
        pts.push_back(land + 20 * Eigen::Vector2d(-std::cos(omega), side * std::sin(omega)));
    }
  // Convex hull (monotone chain), then clip to the gap floor (Sutherland-Hodgman), then the shoelace area.
  std::sort(pts.begin(), pts.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  auto cross = [](const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
  };
  std::vector<Eigen::Vector2d> hull(2 * pts.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
    hull[k++] = pts[i];
  }
  hull.resize(k - 1);
  // Half-planes n . p <= c of the gap floor.
  for (const auto& [n, c] : std::vector<std::pair<Eigen::Vector2d, double>>{
           {{-1, 0}, 1.5}, {{1, 0}, 1.5}, {{0, -1}, 4}, {{0, 1}, 4}}) {
    std::vector<Eigen::Vector2d> out;
    for (std::size_t i = 0; i < hull.size(); ++i) {
      const Eigen::Vector2d& a = hull[(i + hull.size() - 1) % hull.size()];
      const Eigen::Vector2d& b = hull[i];
      const double da = n.dot(a) - c, db = n.dot(b) - c;
      if ((da <= 0) != (db <= 0)) out.push_back(a + (b - a) * (da / (da - db)));
      if (db <= 0) out.push_back(b);
    }
    hull = out;
  }
  double area = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Eigen::Vector2d& a = hull[(i + hull.size() - 1) % hull.size()];
    area += a.x() * hull[i].y() - hull[i].x() * a.y();
  }
  return std::abs(area) / 2;
}

TEST(ConditionalVerify, TwoBlocksProbeIsReliableWhereTiltAloneIsNot) {
  // models/tasks/two_blocks.yaml: v3 may stick on B's top or slide into the gap (tilt alone: unreliable).
  // probe stops when the sensed position is near the gap floor, else runs v2 (slide): reliable. v3 is
  // atan .3 = .2915 rad from vertical, so every admissible velocity moves left: flights off B's left rim
  // (1.5, y, 3) land on the gap floor at x <= x_max = 1.5 - 3 tan(.2915 - .2521) = 1.3818 (.2521: theta_v
  // through the flight cone's circumscribed 24-gon), and nothing reaches the strip beside B's left wall
  // (the robot cannot slide down the wall's vertical edges: v3 leaves that wall). The reached gap floor
  // (two_blocks_tilt_gap_area: 21.27, short of the y walls' corners) surely passes the
  // test (the box shrunk by eps_s = .2 is x in [-1.8, 1.8], |y| <= 4.8, z in [-.8, .3]), and so is absent
  // from the else branch, which starts on B's top (z = 3: more than eps_s above the box, so branch 0 holds
  // none of it).
  const auto task = load_task(std::filesystem::path(CMT_SOURCE_DIR) / "models/tasks/two_blocks.yaml");
  const CSpace& c = task->cspace;
  const int gap = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0)), top = face_at(c, Vec3::UnitZ(), Vec3(3, 0, 3));
  ASSERT_GE(gap, 0);
  ASSERT_GE(top, 0);
  EXPECT_FALSE(verify_strategy(*task, *task->task.find_strategy("tilt")).reliable);
  const VerifyResult v = verify_strategy(*task, *task->task.find_strategy("probe"));
  EXPECT_TRUE(v.reliable) << v.failure;
  ASSERT_EQ(v.steps.size(), 2u);
  const VerifyStep& s = v.steps[0];
  const double reached_gap = two_blocks_tilt_gap_area();
  EXPECT_NEAR(s.termination.face_area(gap), reached_gap, 0.01);
  EXPECT_LT(reached_gap, 8 * (1.5 + 1.5 - 3 * std::tan(std::atan(0.3) - 0.2521)) - 1);  // not to the corners
  EXPECT_GT(s.termination.face_area(top), 0.0);
  ASSERT_EQ(s.branches.size(), 2u);
  EXPECT_NEAR(s.branches[0].start->face_area(gap), s.termination.face_area(gap), 1e-9);
  EXPECT_EQ(s.branches[0].start->face_area(top), 0.0);
  EXPECT_EQ(s.branches[0].step, -1);
  EXPECT_EQ(s.branches[1].start->face_area(gap), 0.0);
  EXPECT_NEAR(s.branches[1].start->face_area(top), s.termination.face_area(top), 1e-12);
  for (const ReachedPiece& p : s.branches[1].start->pieces())  // faces, edges and vertices: all on B's top
    for (const Vec3& q : p.polygon) EXPECT_NEAR(q.z(), 3.0, 1e-9) << c.atom_name(p.atom);
  EXPECT_EQ(v.steps[1].motion, "v2");
  EXPECT_EQ(v.steps[1].branch, 1);
}

}  // namespace
}  // namespace cmt

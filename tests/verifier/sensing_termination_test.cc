// Sensing termination (Buckley §3.1.2 types 2 and 3, §4.5): ReachedSet::within_box and the weakly consistent
// sets added to a motion's termination. Expected values are derived by hand in the comments.
#include "verifier/sensing_termination.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tests/verifier/sensing_tasks.h"
#include "tests/verifier/test_geometry.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

using test::edge_between;

using test::face_at;

// Slack of the grown box: kSensingBoxRelativeSlack x scale (room diagonal 15) per side, far below 1e-6 in
// area for the boxes below (perimeter < 20 in).
constexpr double kAreaTolerance = 1e-6;

TEST(WithinBox, ClipsFacesEdgesAndVerticesExactly) {
  const auto task = load_task_from_string(test::sensing_room(""), "room");
  const CSpace& c = task->cspace;
  const int floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  const int edge = edge_between(c, Vec3(5, -5, 0), Vec3(5, 5, 0));  // floor meets the wall x = 5
  ASSERT_GE(floor, 0);
  ASSERT_GE(edge, 0);
  ReachedSet all(c);
  for (int id = 0; id < c.atom_count(); ++id) all.add_whole_atom(id);

  // Box x in [4, 6], y in [-1, 1], z in [-1, 0.5]: the floor part [4, 5] x [-1, 1] (area 2), the edge x = 5
  // between y = -1 and 1 (a fifth of its length 10), the wall x = 5 for y in [-1, 1], z in [0, .5] (area 1),
  // and no vertex (the corners have |y| = 5).
  const ReachedSet in = all.within_box({Vec3(4, -1, -1), Vec3(6, 1, 0.5)});
  EXPECT_NEAR(in.face_area(floor), 2.0, 1e-12);
  const int wall = face_at(c, -Vec3::UnitX(), Vec3(5, 0, 1));
  EXPECT_NEAR(in.face_area(wall), 1.0, 1e-12);
  const auto iv = in.edge_intervals(edge);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_NEAR(iv[0].t1 - iv[0].t0, 0.2, 1e-11);
  EXPECT_NEAR(0.5 * (iv[0].t0 + iv[0].t1), 0.5, 1e-11);
  for (const Vertex& v : c.vertices()) EXPECT_FALSE(in.has_vertex(v.id));
  EXPECT_NEAR(in.area(), 3.0, 1e-12);  // no other face meets the box
  EXPECT_TRUE(in.face_region_contains(floor, Vec3(4.5, 0.9, 0)));
  EXPECT_FALSE(in.face_region_contains(floor, Vec3(3.9, 0, 0)));

  // A box above the floor (z >= .1) holds no floor point; a box touching it (max z = 0) holds its closed
  // part.
  EXPECT_EQ(all.within_box({Vec3(-1, -1, 0.1), Vec3(1, 1, 1)}).face_area(floor), 0.0);
  EXPECT_NEAR(all.within_box({Vec3(-1, -1, -1), Vec3(1, 1, 0)}).face_area(floor), 4.0, 1e-12);
  // A box outside the room: nothing.
  EXPECT_TRUE(all.within_box({Vec3(6, 6, 6), Vec3(7, 7, 7)}).empty());
}

TEST(WithinBox, KeepsSegmentsAndPointsInside) {
  const auto task = load_task_from_string(test::sensing_room(""), "room");
  const CSpace& c = task->cspace;
  const int floor = face_at(c, Vec3::UnitZ(), Vec3(0, 0, 0));
  ReachedSet s(c);
  s.add_face_segment(floor, Vec3(-4, 0, 0), Vec3(4, 0, 0));
  s.add_face_point(floor, Vec3(0, 3, 0));
  s.add_face_point(floor, Vec3(0, -0.5, 0));
  // Box x in [1, 2], |y| <= 1: the segment part x in [1, 2] and the point (0, -.5) is outside (x = 0).
  const ReachedSet in = s.within_box({Vec3(1, -1, -1), Vec3(2, 1, 1)});
  EXPECT_NEAR(in.distance(Vec3(1.5, 0, 0)), 0, 1e-12);
  EXPECT_NEAR(in.distance(Vec3(0, 0, 0)), 1, 1e-12);                     // nearest kept point (1, 0, 0)
  EXPECT_NEAR(in.distance(Vec3(3, 0, 0)), 1, 1e-12);                     // nearest kept point (2, 0, 0)
  EXPECT_NEAR(in.distance(Vec3(0, 3, 0)), std::sqrt(1.0 + 9.0), 1e-12);  // (0, 3) was not kept
}

struct Verified {
  std::shared_ptr<const LoadedTask> task;
  VerifyResult result;
  int floor = -1, wall = -1;
};

Verified verify_room(const std::string& terminate) {
  Verified v;
  v.task = load_task_from_string(test::sensing_room(terminate), "room");
  v.result = verify_motions(*v.task, {"m"});
  v.floor = face_at(v.task->cspace, Vec3::UnitZ(), Vec3(0, 0, 0));
  v.wall = face_at(v.task->cspace, -Vec3::UnitX(), Vec3(5, 0, 1));
  return v;
}

TEST(SensingTermination, WithoutSetsTheFloorNeverTerminates) {
  // Control case: sticking only. The floor and the wall x = 5 never stick, the edge between them does.
  const Verified v = verify_room("");
  ASSERT_EQ(v.result.steps.size(), 1u);
  const VerifyStep& s = v.result.steps[0];
  EXPECT_EQ(s.termination.face_area(v.floor), 0.0);
  EXPECT_EQ(s.sensing, nullptr);
  EXPECT_FALSE(s.may_not_terminate);
  EXPECT_TRUE(v.result.reliable);  // the goal is that edge
}

TEST(SensingTermination, PositionBoxAddsTheReachedFloorInsideTheGrownBox) {
  // P_s: x in [0, 1], |y| <= .5, |z| <= .5. Grown by eps_s = .1: x in [-.1, 1.1], |y| <= .6, the floor in z.
  // The slide from the start square covers |y| <= 1 + (x + 3.5) tan w >= 1 there, so the floor's part of the
  // grown box is all reached: termination on the floor = the rectangle 1.2 x 1.2, area 1.44. It touches no
  // wall, so no edge or vertex is added. The floor part is not inside the goal (the edge x = 5): unreliable.
  const Verified v = verify_room("{position: {box: {min: [0, -0.5, -0.5], max: [1, 0.5, 0.5]}}}");
  ASSERT_EQ(v.result.steps.size(), 1u);
  const VerifyStep& s = v.result.steps[0];
  ASSERT_NE(s.sensing, nullptr);
  EXPECT_NEAR(s.sensing->face_area(v.floor), 1.44, kAreaTolerance);
  EXPECT_NEAR(s.termination.face_area(v.floor), 1.44, kAreaTolerance);
  EXPECT_NEAR(s.sensing->area(), 1.44, kAreaTolerance);
  for (const Vec3& p : {Vec3(-0.0999, -0.5999, 0), Vec3(1.0999, 0.5999, 0), Vec3(0.5, 0, 0)})
    EXPECT_TRUE(s.termination.face_region_contains(v.floor, p)) << p.transpose();
  for (const Vec3& p : {Vec3(-0.1001, 0, 0), Vec3(1.1001, 0, 0), Vec3(0.5, 0.6001, 0)})
    EXPECT_FALSE(s.termination.face_region_contains(v.floor, p)) << p.transpose();
  EXPECT_TRUE(s.sensing->edge_intervals(edge_between(v.task->cspace, Vec3(5, -5, 0), Vec3(5, 5, 0))).empty());
  // Sticking termination is still there (the edge x = 5).
  EXPECT_FALSE(
      s.termination.edge_intervals(edge_between(v.task->cspace, Vec3(5, -5, 0), Vec3(5, 5, 0))).empty());
  EXPECT_FALSE(s.may_not_terminate);
  EXPECT_FALSE(v.result.reliable);
  EXPECT_NEAR(s.termination.distance(Vec3(0.5, 0, 0)), 0, 1e-12);
}

TEST(SensingTermination, WideBoxKeepsTheSlideWedge) {
  // P_s: x in [0, 1], |y| <= 3. Grown: x in [-.1, 1.1], |y| <= 3.1, wider than the slide. The slide is the
  // start square swept by the wedge of half-angle w about +x (Minkowski sum), whose sides are the rays from
  // the back corners (-4.5, +-1): |y| <= 1 + (x + 4.5) t, t = tan w (<= 1.80 at x = 1.1). Kept area =
  // integral over x in [-.1, 1.1] of 2 (1 + (x + 4.5) t) = 2.4 + t (5.6^2 - 4.4^2) = 2.4 + 12 t, t =
  // tan(asin(sin .1 / sin(pi/4))) = .142616: 4.111390.
  const Verified v = verify_room("{position: {box: {min: [0, -3, -0.5], max: [1, 3, 0.5]}}}");
  const VerifyStep& s = v.result.steps.at(0);
  const double t = std::tan(std::asin(std::sin(0.1) / std::sin(std::numbers::pi / 4)));
  EXPECT_NEAR(s.sensing->face_area(v.floor), 2.4 + 12 * t, kAreaTolerance);
  EXPECT_TRUE(s.termination.face_region_contains(v.floor, Vec3(1.0999, 1 + 5.5999 * t, 0)));
  EXPECT_FALSE(s.termination.face_region_contains(v.floor, Vec3(1.0999, 1 + 5.6001 * t + 1e-4, 0)));
}

TEST(SensingTermination, ForceConeKeepsOnlyAtomsWhoseSensedForcesMayMatch) {
  // The slide reaches the floor and the floor/wall edge x = 5 (|y| <= 1 + 9.5 t), not the wall's face.
  // F_s = cone(+z, .2): the floor's cone widened by theta_f is cone(+z, .245 + .1), which meets it, so every
  // reached floor point may terminate (type 3 needs no position set); the edge's cone (the sum of the floor's
  // and the wall's) holds the floor's, so it is kept too.
  const int edge = [] {
    const auto task = load_task_from_string(test::sensing_room(""), "room");
    return edge_between(task->cspace, Vec3(5, -5, 0), Vec3(5, 5, 0));
  }();
  const Verified up = verify_room("{force: {direction: [0, 0, 1], angle: 0.2}}");
  const VerifyStep& s = up.result.steps.at(0);
  EXPECT_GT(s.reached->face_area(up.floor), 0.0);
  EXPECT_NEAR(s.sensing->face_area(up.floor), s.reached->face_area(up.floor), 1e-12);
  ASSERT_EQ(s.sensing->edge_intervals(edge).size(), 1u);
  EXPECT_EQ(s.sensing->edge_intervals(edge)[0].t0, s.reached->edge_intervals(edge).at(0).t0);
  // F_s = cone(-x, .2): the floor (cone(+z, .345), pi/2 - .345 - .2 > 0 away) is excluded; the edge, whose
  // cone holds the wall's cone(-x, .245), is kept.
  const Verified side = verify_room("{force: {direction: [-1, 0, 0], angle: 0.2}}");
  const VerifyStep& w = side.result.steps.at(0);
  EXPECT_EQ(w.sensing->face_area(side.floor), 0.0);
  EXPECT_EQ(w.sensing->atoms(), std::vector<int>{edge});
  // Both sets (type 3 with a position): the floor rectangle of the first position test.
  const Verified both = verify_room(
      "{position: {box: {min: [0, -0.5, -0.5], max: [1, 0.5, 0.5]}}, force: {direction: [0, 0, 1], angle: "
      "0.2}}");
  EXPECT_NEAR(both.result.steps.at(0).sensing->area(), 1.44, kAreaTolerance);
  // ... and with the sideways cone: the box holds only floor points, whose forces cannot match: nothing.
  const Verified none = verify_room(
      "{position: {box: {min: [0, -0.5, -0.5], max: [1, 0.5, 0.5]}}, force: {direction: [-1, 0, 0], angle: "
      "0.2}}");
  EXPECT_TRUE(none.result.steps.at(0).sensing->empty());
  // Force pointing into the floor (-z): 1.23 rad or more from every reached atom's widened cone: nothing.
  const Verified down = verify_room("{force: {direction: [0, 0, -1], angle: 0.2}}");
  EXPECT_TRUE(down.result.steps.at(0).sensing->empty());
}

}  // namespace
}  // namespace cmt

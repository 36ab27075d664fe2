// ReachedSet::distance (verifier/reached_set_distance.cc) on hand-computed cases: face regions (above,
// beside, inside a hole, on a tilted face whose chart is not distance-preserving), face segments and points,
// edge intervals, vertices, the empty set.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "models/loaded_task.h"
#include "tests/verifier/test_geometry.h"
#include "verifier/reached_set.h"

namespace cmt {
namespace {

using test::edge_between;

using test::face_at;

using test::room;

int vertex_at(const CSpace& c, const Vec3& p) {
  for (const Vertex& v : c.vertices())
    if ((v.point - p).norm() < 1e-12) return v.id;
  return -1;
}

std::vector<Vec3> square(double x0, double y0, double x1, double y1) {
  return {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
}

TEST(ReachedSetDistance, EmptySetIsInfinitelyFar) {
  const auto t = room();
  EXPECT_EQ(ReachedSet(t->cspace).distance(Vec3(0, 0, 1)), std::numeric_limits<double>::infinity());
}

TEST(ReachedSetDistance, SquareRegionOnTheFloor) {
  const auto t = room();
  const int floor = face_at(t->cspace, Vec3::UnitZ(), Vec3(0, 0, 0));
  ASSERT_GE(floor, 0);
  ReachedSet s(t->cspace);
  s.add_face_polygon(floor, square(-1, -1, 1, 1));
  EXPECT_DOUBLE_EQ(s.distance(Vec3(0.5, 0.5, 0)), 0);           // inside
  EXPECT_DOUBLE_EQ(s.distance(Vec3(1, 0.3, 0)), 0);             // on its side
  EXPECT_DOUBLE_EQ(s.distance(Vec3(0.5, 0.5, 2)), 2);           // straight above: the height
  EXPECT_DOUBLE_EQ(s.distance(Vec3(3, 0, 0)), 2);               // beside: 3 - 1
  EXPECT_DOUBLE_EQ(s.distance(Vec3(3, 0, 1)), std::sqrt(5.0));  // beside and above: sqrt(2^2 + 1^2)
  EXPECT_DOUBLE_EQ(s.distance(Vec3(2, 2, 0)), std::sqrt(2.0));  // off the corner (1, 1)
  EXPECT_DOUBLE_EQ(s.distance(Vec3(2, 3, 2)), 3);               // corner: sqrt(1 + 4 + 4)
}

TEST(ReachedSetDistance, InsideAHoleTheNearestPointIsOnTheHolesBoundary) {
  // A frame [-2,2]^2 minus (-1,1)^2, built from four rectangles: the union has a hole.
  const auto t = room();
  const int floor = face_at(t->cspace, Vec3::UnitZ(), Vec3(0, 0, 0));
  ReachedSet s(t->cspace);
  s.add_face_polygon(floor, square(-2, 1, 2, 2));
  s.add_face_polygon(floor, square(-2, -2, 2, -1));
  s.add_face_polygon(floor, square(-2, -1, -1, 1));
  s.add_face_polygon(floor, square(1, -1, 2, 1));
  ASSERT_EQ(s.pieces().at(0).holes.size(), 1u);
  EXPECT_DOUBLE_EQ(s.distance(Vec3(0, 0, 0)), 1);               // hole centre: 1 to each side
  EXPECT_DOUBLE_EQ(s.distance(Vec3(0.5, 0, 0)), 0.5);           // nearer the side x = 1
  EXPECT_DOUBLE_EQ(s.distance(Vec3(0, 0, 1)), std::sqrt(2.0));  // above the hole centre
  EXPECT_DOUBLE_EQ(s.distance(Vec3(1.5, 0, 3)), 3);             // above the frame
  EXPECT_DOUBLE_EQ(s.distance(Vec3(0.5, 0.5, 0)), 0.5);         // hole: nearest side at distance .5
}

TEST(ReachedSetDistance, TiltedFaceUsesTrueInPlaneDistances) {
  // A prism under the plane z = x (x in [0, 4]): its slope is a face with normal (-1, 0, 1)/sqrt 2 and
  // x in [0, 4], y in [-4, 4]. Its chart drops one axis, which shrinks in-plane lengths by 1/sqrt 2: the
  // distance must come from the 3-D geometry.
  const auto t = room("[{convex: {vertices: [[0,-4,0],[4,-4,0],[4,-4,4],[0,4,0],[4,4,0],[4,4,4]]}}]");
  const Vec3 n = Vec3(-1, 0, 1).normalized();
  const int slope = face_at(t->cspace, n, Vec3(2, 0, 2));
  ASSERT_GE(slope, 0);
  ReachedSet s(t->cspace);
  s.add_whole_atom(slope);
  // (0,0,2): offset 2/sqrt 2 = sqrt 2 in front of the plane, foot (1,0,1) on the face.
  EXPECT_NEAR(s.distance(Vec3(0, 0, 2)), std::sqrt(2.0), 1e-12);
  // (-3,0,1): offset (3 + 1)/sqrt 2 = 2 sqrt 2, foot (-1,0,-1), which is sqrt 2 (in the plane) beyond the
  // face's side x = 0 (nearest point (0,0,0)): sqrt(8 + 2) = sqrt 10, i.e. the distance to the origin.
  EXPECT_NEAR(s.distance(Vec3(-3, 0, 1)), std::sqrt(10.0), 1e-12);
}

TEST(ReachedSetDistance, FaceSegmentsAndPoints) {
  const auto t = room();
  const int floor = face_at(t->cspace, Vec3::UnitZ(), Vec3(0, 0, 0));
  ReachedSet s(t->cspace);
  s.add_face_segment(floor, Vec3(0, 0, 0), Vec3(2, 0, 0));
  EXPECT_DOUBLE_EQ(s.distance(Vec3(1, 1, 0)), 1);                // beside its middle
  EXPECT_DOUBLE_EQ(s.distance(Vec3(3, 0, 4)), std::sqrt(17.0));  // beyond its end (2,0,0), 4 up
  s.add_face_point(floor, Vec3(-2, -2, 0));
  EXPECT_DOUBLE_EQ(s.distance(Vec3(-2, -2, 0.5)), 0.5);
}

TEST(ReachedSetDistance, EdgeIntervalsAndVertices) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const int edge = edge_between(c, Vec3(-4, -4, 0), Vec3(4, -4, 0));  // floor meets the wall y = -4
  const int corner = vertex_at(c, Vec3(-4, 4, 0));
  ASSERT_GE(edge, 0);
  ASSERT_GE(corner, 0);
  ReachedSet s(c);
  s.add_edge_interval(edge, 0.25, 0.75);                          // x in [-2, 2] whichever way the edge runs
  EXPECT_DOUBLE_EQ(s.distance(Vec3(0, -3, 1)), std::sqrt(2.0));   // beside the middle
  EXPECT_DOUBLE_EQ(s.distance(Vec3(3, -4, 0)), 1);                // along the edge past x = 2
  EXPECT_DOUBLE_EQ(s.distance(Vec3(-3, -3, 0)), std::sqrt(2.0));  // past x = -2 and 1 off
  s.add_vertex(corner);
  EXPECT_DOUBLE_EQ(s.distance(Vec3(-3, 3, 1)), std::sqrt(3.0));  // the corner (-4, 4, 0)
  EXPECT_DOUBLE_EQ(s.distance(Vec3(-4, 4, 0)), 0);
}

}  // namespace
}  // namespace cmt

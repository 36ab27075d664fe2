// Convex planar polygons in 3-D (verifier/convex_polygon.h): clip_convex_polygon on overlapping, nested,
// disjoint and edge-touching polygons, in the floor and in tilted and vertical planes; polygon_area signed by
// the orientation about the normal. Areas are worked out by hand in the comments.
#include "verifier/convex_polygon.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace cmt {
namespace {

const Vec3 kZ = Vec3::UnitZ();

// Axis rectangle [x0,x1] x [y0,y1] at height z, counter-clockwise about +z.
std::vector<Vec3> rect(double x0, double y0, double x1, double y1, double z = 0) {
  return {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
}

bool has_point(const std::vector<Vec3>& poly, const Vec3& p) {
  return std::any_of(poly.begin(), poly.end(), [&](const Vec3& q) { return (q - p).norm() < 1e-12; });
}

TEST(ConvexPolygon, AreaOfACounterClockwiseSquareIsPositive) {
  EXPECT_DOUBLE_EQ(polygon_area(rect(0, 0, 1, 1), kZ), 1);
  // The formula does not depend on the origin: a 2 x 3 rectangle far away at height 5.
  EXPECT_DOUBLE_EQ(polygon_area(rect(10, 20, 12, 23, 5), kZ), 6);
}

TEST(ConvexPolygon, AreaIsSignedByTheOrientationAboutTheNormal) {
  std::vector<Vec3> cw = rect(0, 0, 2, 1);
  std::reverse(cw.begin(), cw.end());
  EXPECT_DOUBLE_EQ(polygon_area(cw, kZ), -2);  // clockwise about +z
  EXPECT_DOUBLE_EQ(polygon_area(rect(0, 0, 2, 1), -kZ),
                   -2);  // counter-clockwise about +z is clockwise about -z
  EXPECT_DOUBLE_EQ(polygon_area(cw, -kZ), 2);
}

TEST(ConvexPolygon, AreaOfATiltedTriangle) {
  // (1,0,0), (0,1,0), (0,0,1): equilateral with side sqrt 2, area (sqrt 3 / 4) 2 = sqrt 3 / 2,
  // counter-clockwise about (1,1,1)/sqrt 3.
  const std::vector<Vec3> tri = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  EXPECT_NEAR(polygon_area(tri, Vec3(1, 1, 1).normalized()), std::sqrt(3.0) / 2, 1e-15);
}

TEST(ConvexPolygon, ClipByHalfPlaneKeepsTheInnerPart) {
  // The unit square clipped by x <= .5 (a large rectangle whose right side is x = .5) has area .5.
  const auto out = clip_convex_polygon(rect(0, 0, 1, 1), rect(-10, -10, 0.5, 10), kZ);
  EXPECT_NEAR(polygon_area(out, kZ), 0.5, 1e-15);
  for (const Vec3& p : out) EXPECT_LE(p.x(), 0.5);
  EXPECT_TRUE(has_point(out, Vec3(0.5, 0, 0)));
  EXPECT_TRUE(has_point(out, Vec3(0.5, 1, 0)));
}

TEST(ConvexPolygon, ClipOfOverlappingSquaresIsTheirIntersection) {
  // [0,1]^2 and [.5,1.5]^2 meet in [.5,1]^2: area .25.
  const auto out = clip_convex_polygon(rect(0, 0, 1, 1), rect(0.5, 0.5, 1.5, 1.5), kZ);
  EXPECT_NEAR(polygon_area(out, kZ), 0.25, 1e-15);
  for (const Vec3& p : {Vec3(0.5, 0.5, 0), Vec3(1, 0.5, 0), Vec3(1, 1, 0), Vec3(0.5, 1, 0)})
    EXPECT_TRUE(has_point(out, p)) << p.transpose();
}

TEST(ConvexPolygon, ClipOfATriangleByASquareCutsBothCorners) {
  // The triangle x, y >= 0, x + y <= 2 (area 2) inside [0,1.5]^2 loses the corners x > 1.5 and y > 1.5, each
  // a right triangle with legs .5 (area .125): a pentagon of area 1.75.
  const std::vector<Vec3> tri = {{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  const auto out = clip_convex_polygon(tri, rect(0, 0, 1.5, 1.5), kZ);
  EXPECT_EQ(out.size(), 5u);
  EXPECT_NEAR(polygon_area(out, kZ), 1.75, 1e-15);
  for (const Vec3& p :
       {Vec3(0, 0, 0), Vec3(1.5, 0, 0), Vec3(1.5, 0.5, 0), Vec3(0.5, 1.5, 0), Vec3(0, 1.5, 0)})
    EXPECT_TRUE(has_point(out, p)) << p.transpose();
}

TEST(ConvexPolygon, ClipOfANestedPolygonKeepsIt) {
  // Subject inside the clip: unchanged. Clip inside the subject: the clip.
  const auto inner = rect(1, 1, 2, 3);
  const auto a = clip_convex_polygon(inner, rect(0, 0, 5, 5), kZ);
  EXPECT_NEAR(polygon_area(a, kZ), 2, 1e-15);
  for (const Vec3& p : inner) EXPECT_TRUE(has_point(a, p));
  EXPECT_NEAR(polygon_area(clip_convex_polygon(rect(0, 0, 5, 5), inner, kZ), kZ), 2, 1e-15);
}

TEST(ConvexPolygon, ClipOfDisjointPolygonsIsEmpty) {
  EXPECT_TRUE(clip_convex_polygon(rect(0, 0, 1, 1), rect(2, 2, 3, 3), kZ).empty());
  EXPECT_TRUE(clip_convex_polygon(rect(0, 0, 1, 1), rect(0, 1.5, 1, 2), kZ).empty());
}

TEST(ConvexPolygon, ClipOfSquaresSharingAnEdgeHasNoArea) {
  // [0,1]^2 and [1,2] x [0,1] meet in the segment x = 1: whatever comes back encloses no area.
  const auto out = clip_convex_polygon(rect(0, 0, 1, 1), rect(1, 0, 2, 1), kZ);
  EXPECT_NEAR(polygon_area(out, kZ), 0, 1e-15);
  for (const Vec3& p : out) EXPECT_NEAR(p.x(), 1, 1e-15);
}

TEST(ConvexPolygon, ClipInAVerticalPlane) {
  // In the plane x = 2 with normal +x, counter-clockwise about +x runs from +y toward +z. The unit square
  // (y, z) in [0,1]^2 clipped by the triangle (0,0), (1,0), (0,1) is that triangle: area .5.
  const Vec3 n = Vec3::UnitX();
  const std::vector<Vec3> square = {{2, 0, 0}, {2, 1, 0}, {2, 1, 1}, {2, 0, 1}};
  const std::vector<Vec3> tri = {{2, 0, 0}, {2, 1, 0}, {2, 0, 1}};
  ASSERT_DOUBLE_EQ(polygon_area(square, n), 1);  // the orientation is right
  const auto out = clip_convex_polygon(square, tri, n);
  EXPECT_NEAR(polygon_area(out, n), 0.5, 1e-15);
  for (const Vec3& p : out) EXPECT_LE(p.y() + p.z(), 1 + 1e-15);
}

TEST(ConvexPolygon, ClipInATiltedPlane) {
  // The plane z = x (normal (−1,0,1)/sqrt 2). A rectangle over x in [0,2], y in [0,1] (length 2 sqrt 2 along
  // the slope, area 2 sqrt 2) clipped by the one over x in [1,3], y in [-1, 0.5]: x in [1,2], y in [0,.5],
  // area sqrt 2 * .5.
  const Vec3 n = Vec3(-1, 0, 1).normalized();
  auto on_slope = [](double x0, double y0, double x1, double y1) {
    // Counter-clockwise about n: (x0,y0) -> (x1,y0) -> (x1,y1) -> (x0,y1), since (1,0,1) x (0,1,0) =
    // (−1,0,1).
    return std::vector<Vec3>{{x0, y0, x0}, {x1, y0, x1}, {x1, y1, x1}, {x0, y1, x0}};
  };
  const auto subject = on_slope(0, 0, 2, 1);
  ASSERT_NEAR(polygon_area(subject, n), 2 * std::sqrt(2.0), 1e-14);
  const auto out = clip_convex_polygon(subject, on_slope(1, -1, 3, 0.5), n);
  EXPECT_NEAR(polygon_area(out, n), 0.5 * std::sqrt(2.0), 1e-14);
  for (const Vec3& p : out) EXPECT_NEAR(p.z(), p.x(), 1e-14);  // stays in the plane
}

}  // namespace
}  // namespace cmt

// Face charts (verifier/internal/face_regions.h) of degenerate faces: a sliver face left by C-obstacle planes
// that coincide only up to rounding (decimal coordinates far from the origin) has a 2-point polygon. Its
// chart falls back to the face's own plane, so lifting a chart point is defined (a chart through a 2-point
// polygon's "plane" would divide by zero in exact arithmetic: SIGFPE).
#include <gtest/gtest.h>

#include "verifier/internal/face_regions.h"

namespace cmt {
namespace {

TEST(FaceChart, DegenerateFaceLiftsOntoItsOwnPlane) {
  Face f;
  f.normal = Vec3(0, 0, 1);
  f.offset = 5;
  f.polygon = {Vec3(0, 0, 5), Vec3(1, 0, 5)};
  const face_geometry::FaceChart chart = face_geometry::make_chart(f);
  EXPECT_EQ(chart.drop, 2);
  const face_geometry::Point3 p = chart.lift(face_geometry::Point2(0.5, 0.25));
  EXPECT_EQ(CGAL::to_double(p.z()), 5.0);
  EXPECT_EQ(CGAL::to_double(p.x()), 0.5);
}

TEST(FaceChart, CollinearCornersUseTheFacePlane) {
  Face f;
  f.normal = Vec3(1, 0, 0);
  f.offset = -2;
  f.polygon = {Vec3(-2, 0, 0), Vec3(-2, 1, 1), Vec3(-2, 2, 2)};  // collinear: no plane through them
  const face_geometry::FaceChart chart = face_geometry::make_chart(f);
  const face_geometry::Point3 p = chart.lift(face_geometry::Point2(3, 4));
  EXPECT_EQ(CGAL::to_double(p.x()), -2.0);
}

}  // namespace
}  // namespace cmt

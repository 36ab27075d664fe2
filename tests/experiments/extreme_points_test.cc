// The points of §6.3.4's extreme-point experiment (experiments/plan/extreme_points.h): a cell's vertices,
// and the vertices of the cell grown by a distance, each at least that far outside every piece.
#include "experiments/plan/extreme_points.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace {

using cmt::AxisBox;
using cmt::PlannedMotionCell;
using cmt::Vec3;
using cmt::planner::CPositionSet;

const AxisBox kDomain{Vec3(-10, -10, -10), Vec3(10, 10, 10)};

CPositionSet box_cell(const Vec3& lo, const Vec3& hi) {
  return CPositionSet::convex(cmt::planner::box_halfspaces({lo, hi}), kDomain);
}

// Euclidean distance from p to an axis box.
double distance_to_box(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return (p - p.cwiseMax(lo).cwiseMin(hi)).norm();
}

// Vertices come from clipping with each half-space relaxed by kPieceSlack x the domain's diagonal
// (cposition_set.h): within 1e-8 here.
constexpr double kVertexTolerance = 1e-8;

bool has_point(const std::vector<Vec3>& points, const Vec3& p) {
  return std::any_of(points.begin(), points.end(),
                     [&](const Vec3& q) { return (q - p).norm() < kVertexTolerance; });
}

TEST(ExtremePoints, ABoxCellHasItsEightCornersAndGrowsIntoTheCornersOfTheBiggerBox) {
  const PlannedMotionCell cell{"m", Vec3(0.5, 0.5, 0.5), box_cell(Vec3(0, 0, 0), Vec3(1, 1, 1))};
  const std::vector<Vec3> v = cmt::cell_vertices(cell);
  EXPECT_EQ(v.size(), 8u);
  EXPECT_TRUE(has_point(v, Vec3(0, 0, 0)));
  EXPECT_TRUE(has_point(v, Vec3(1, 1, 1)));
  EXPECT_TRUE(has_point(v, Vec3(1, 0, 1)));
  const std::vector<Vec3> g = cmt::grown_vertices(cell, 0.25);
  EXPECT_EQ(g.size(), 8u);
  EXPECT_TRUE(has_point(g, Vec3(-0.25, -0.25, -0.25)));
  EXPECT_TRUE(has_point(g, Vec3(1.25, -0.25, 1.25)));
  for (const Vec3& p : g)
    EXPECT_GE(distance_to_box(p, Vec3(0, 0, 0), Vec3(1, 1, 1)), 0.25 - kVertexTolerance);
}

TEST(ExtremePoints, AMotionThatClaimsOnePointGrowsIntoTheCubeAboutIt) {
  const Vec3 p(1, 2, 3);
  const PlannedMotionCell cell{"m", p, CPositionSet()};
  EXPECT_EQ(cmt::cell_vertices(cell), std::vector<Vec3>{p});
  const std::vector<Vec3> g = cmt::grown_vertices(cell, 0.5);
  ASSERT_EQ(g.size(), 8u);
  for (const Vec3& q : g) EXPECT_NEAR((q - p).cwiseAbs().minCoeff(), 0.5, kVertexTolerance);
  EXPECT_TRUE(has_point(g, Vec3(0.5, 2.5, 2.5)));
}

// Two boxes side by side: their shared corners are listed once; every grown corner is at least the
// distance outside both boxes.
TEST(ExtremePoints, APiecewiseCellListsSharedCornersOnceAndEveryGrownCornerIsOutsideTheUnion) {
  const CPositionSet left = box_cell(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const CPositionSet right = box_cell(Vec3(1, 0, 0), Vec3(2, 1, 1));
  const PlannedMotionCell cell{"m", Vec3(1, 0.5, 0.5), left.unite(right)};
  EXPECT_EQ(cmt::cell_vertices(cell).size(), 12u);
  const std::vector<Vec3> g = cmt::grown_vertices(cell, 0.25);
  EXPECT_EQ(g.size(), 16u);
  EXPECT_TRUE(has_point(g, Vec3(2.25, 1.25, -0.25)));
  for (const Vec3& p : g)
    EXPECT_GE(std::min(distance_to_box(p, Vec3(0, 0, 0), Vec3(1, 1, 1)),
                       distance_to_box(p, Vec3(1, 0, 0), Vec3(2, 1, 1))),
              0.25 - kVertexTolerance);
}

// A grown corner of one piece strictly inside another grown piece is not outside the union by the distance:
// it is dropped.
TEST(ExtremePoints, AGrownCornerInsideAnotherGrownPieceIsDropped) {
  const CPositionSet small = box_cell(Vec3(0, 0, 0), Vec3(1, 1, 1));
  const CPositionSet wide = box_cell(Vec3(0.5, -1, -1), Vec3(2, 2, 2));
  const PlannedMotionCell cell{"m", Vec3(1, 0.5, 0.5), small.unite(wide)};
  const std::vector<Vec3> g = cmt::grown_vertices(cell, 0.25);
  EXPECT_EQ(g.size(), 12u);  // the small box's four corners at x = 1.25 lie inside the grown wide box
  EXPECT_FALSE(has_point(g, Vec3(1.25, 1.25, 1.25)));
  EXPECT_TRUE(has_point(g, Vec3(-0.25, 1.25, 1.25)));
  for (const Vec3& p : g)
    EXPECT_GE(std::min(distance_to_box(p, Vec3(0, 0, 0), Vec3(1, 1, 1)),
                       distance_to_box(p, Vec3(0.5, -1, -1), Vec3(2, 2, 2))),
              0.25 - kVertexTolerance);
}

}  // namespace

// The region kernel (verifier/internal/face_regions.h, class ChartRegion): integer-grid overlays compared
// with CGAL's exact polygon sets, outward rounding, growth below the grid's resolution, the range check.
#include <CGAL/Polygon_set_2.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "verifier/internal/face_regions.h"

namespace cmt::face_geometry {
namespace {

using ExactSet = CGAL::Polygon_set_2<Kernel>;
constexpr double kCell = 0x1p-36;  // the grid of a scene of scale in [1/2, 1): region_cell(0.75)

std::vector<Polygon2> read_polygons(const std::string& path) {
  std::ifstream in(path);
  std::vector<Polygon2> out;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream words(line);
    Polygon2 p;
    double u = 0, v = 0;
    while (words >> u >> v) p.push_back(Point2(u, v));
    out.push_back(p);
  }
  return out;
}

double exact_area(const ExactSet& set) {
  std::vector<PolygonWithHoles2> parts;
  set.polygons_with_holes(std::back_inserter(parts));
  FT total = 0;
  for (const PolygonWithHoles2& p : parts) {
    total += p.outer_boundary().area();
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h) total += h->area();  // holes are clockwise
  }
  return CGAL::to_double(total);
}

bool all_simple(const ChartRegion& set) {
  for (const PolygonWithHoles2& p : set.polygons_with_holes()) {
    if (!p.outer_boundary().is_simple()) return false;
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h)
      if (!h->is_simple()) return false;
  }
  return true;
}

double perimeter(const Polygon2& p) {
  double total = 0;
  for (auto e = p.edges_begin(); e != p.edges_end(); ++e)
    total += std::sqrt(CGAL::to_double(e->squared_length()));
  return total;
}

// Every vertex of every polygon is inside the (closed) region.
bool holds_vertices(const ChartRegion& region, const std::vector<Polygon2>& polygons) {
  for (const Polygon2& p : polygons)
    for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v)
      if (region.oriented_side(*v) == CGAL::ON_NEGATIVE_SIDE) return false;
  return true;
}

Polygon2 box(double a, double b, double c = 0, double d = 1) {
  return to_polygon({Point2(a, c), Point2(b, c), Point2(b, d), Point2(a, d)});
}

// The 32 pieces of one slide (soundness campaign seed 3, task 322) share edges on the face boundary and on
// cutting lines; CGAL 5.5's aggregated join of them was non-simple in about one run in six. The kernel's
// union is simple, contains every piece, and its area is the exact union's up to a few cells per unit of
// boundary length.
TEST(ChartRegion, PiecesOverlappingOnCommonLinesGiveTheExactUnionUpToTheGrid) {
  const std::vector<Polygon2> pieces =
      read_polygons(CMT_SOURCE_DIR "/tests/verifier/data/overlapping_slide_pieces.txt");
  ASSERT_EQ(pieces.size(), 32u);
  ExactSet exact;
  double boundary = 0;
  for (const Polygon2& p : pieces) {
    exact.join(p);
    boundary += perimeter(p);
  }
  const ChartRegion u = union_of(pieces, kCell);
  ASSERT_TRUE(all_simple(u));
  EXPECT_TRUE(holds_vertices(u, pieces));
  const double expected = exact_area(exact);
  EXPECT_GE(u.area(), expected - 1e-9 * expected);
  EXPECT_LE(u.area(), expected + 4 * kCell * boundary);
  ChartRegion one_at_a_time;
  for (const Polygon2& p : pieces) one_at_a_time.join(p, kCell);
  EXPECT_NEAR(one_at_a_time.area(), u.area(), 4 * kCell * boundary);
}

TEST(ChartRegion, OfNothingIsEmptyAndOfOneIsItselfRoundedOutward) {
  EXPECT_TRUE(union_of(std::vector<Polygon2>{}, kCell).is_empty());
  const ChartRegion u = union_of(std::vector<Polygon2>{box(0, 1)}, kCell);
  EXPECT_DOUBLE_EQ(u.area(), 1.0);  // grid points: no rounding
  const ChartRegion third(box(0, 1.0 / 3), kCell);
  EXPECT_GT(third.area(), 1.0 / 3);
  EXPECT_LT(third.area(), 1.0 / 3 + 2 * kCell);
}

TEST(ChartRegion, ThreeSquaresOnALineShareEdges) {
  const ChartRegion u = union_of(std::vector<Polygon2>{box(0, 1), box(1, 2), box(0.5, 2.5)}, kCell);
  EXPECT_DOUBLE_EQ(u.area(), 2.5);
  EXPECT_EQ(u.polygons_with_holes().size(), 1u);
}

TEST(ChartRegion, DifferenceLeavesAHoleAndIntersectionTheOverlap) {
  ChartRegion r(box(0, 4, 0, 4), kCell);
  r.difference(box(1, 2, 1, 2));
  const std::vector<PolygonWithHoles2> parts = r.polygons_with_holes();
  ASSERT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts[0].number_of_holes(), 1u);
  EXPECT_EQ(parts[0].outer_boundary().orientation(), CGAL::COUNTERCLOCKWISE);
  EXPECT_EQ(parts[0].holes_begin()->orientation(), CGAL::CLOCKWISE);
  EXPECT_DOUBLE_EQ(r.area(), 15.0);  // grid points: no rounding
  EXPECT_EQ(r.oriented_side(Point2(1.5, 1.5)), CGAL::ON_NEGATIVE_SIDE);
  EXPECT_EQ(r.oriented_side(Point2(1, 1.5)), CGAL::ON_ORIENTED_BOUNDARY);
  EXPECT_EQ(r.oriented_side(Point2(3, 3)), CGAL::ON_POSITIVE_SIDE);
  r.intersection(box(3, 5, 0, 4));
  EXPECT_DOUBLE_EQ(r.area(), 4.0);
}

// Minkowski sum with the triangle of the origin, (.1, 0) and (0, .1) (the servo coast's landing growth): the
// unit square becomes the pentagon (0,0) (1.1,0) (1.1,1) (1,1.1) (0,1.1) of area 1.21 - .005 = 1.205; the
// pattern is rounded outward (.1 is not a grid point), so up to a few cells more. A hole [1, 2]^2 in [0, 3]^2
// keeps what no translate reaches, the intersection of the hole moved by every pattern vector: [1.1, 2]^2;
// the ring's area becomes 3.1^2 - .005 - .9^2.
TEST(ChartRegion, MinkowskiSumWithAPatternGrowsOuterBoundariesAndShrinksHoles) {
  const std::vector<std::pair<double, double>> pattern = {{0.1, 0}, {0, 0.1}};
  const ChartRegion sum = ChartRegion(box(0, 1), kCell).minkowski_sum(pattern);
  EXPECT_GE(sum.area(), 1.205);
  EXPECT_LE(sum.area(), 1.205 + 10 * kCell);
  EXPECT_EQ(sum.oriented_side(Point2(1.04, 1.04)), CGAL::ON_POSITIVE_SIDE);
  EXPECT_EQ(sum.oriented_side(Point2(1.06, 1.06)), CGAL::ON_NEGATIVE_SIDE);
  EXPECT_EQ(sum.oriented_side(Point2(-0.01, 0.5)), CGAL::ON_NEGATIVE_SIDE);  // nothing moves toward -x
  ChartRegion ring(box(0, 3, 0, 3), kCell);
  ring.difference(box(1, 2, 1, 2));
  const ChartRegion ring_sum = ring.minkowski_sum(pattern);
  EXPECT_NEAR(ring_sum.area(), 3.1 * 3.1 - 0.005 - 0.9 * 0.9, 20 * kCell);
  EXPECT_EQ(ring_sum.oriented_side(Point2(1.05, 1.5)), CGAL::ON_POSITIVE_SIDE);
  EXPECT_EQ(ring_sum.oriented_side(Point2(1.5, 1.5)), CGAL::ON_NEGATIVE_SIDE);
  EXPECT_EQ(ring_sum.oriented_side(Point2(1.95, 1.95)), CGAL::ON_NEGATIVE_SIDE);
}

// Random convex polygons with coordinates that are not grid points, against the exact polygon sets: the
// kernel's union holds the exact one (every exact vertex inside) and exceeds it by at most a few cells along
// the boundary.
TEST(ChartRegion, RandomUnionsContainTheExactUnion) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(-0.05, 0.05);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<Polygon2> polygons;
    double boundary = 0;
    ExactSet exact;
    for (int k = 0; k < 6; ++k) {
      Points2 pts;
      for (int i = 0; i < 7; ++i) pts.push_back(Point2(coord(rng), coord(rng)));
      const Points2 hull = convex_hull(pts);
      if (hull.size() < 3) continue;
      polygons.push_back(to_polygon(hull));
      boundary += perimeter(polygons.back());
      exact.join(polygons.back());
    }
    const ChartRegion u = union_of(polygons, kCell);
    EXPECT_TRUE(holds_vertices(u, polygons)) << "trial " << trial;
    const double expected = exact_area(exact);
    EXPECT_GE(u.area(), expected) << "trial " << trial;
    EXPECT_LE(u.area(), expected + 4 * kCell * boundary) << "trial " << trial;
  }
}

// A part that adds only a sliver of a few cells is not growth; one cell-wide strip more than that is.
TEST(ChartRegion, GrowthNarrowerThanTheThresholdIsRounding) {
  ChartRegion sliver(box(0, 1, 0, 1), kCell);
  sliver.difference(box(0, 1, 0, 1 - kCell));
  EXPECT_FALSE(sliver.is_empty());
  EXPECT_FALSE(sliver.wider_than(kRegionGrowthCells));
  ChartRegion strip(box(0, 1, 0, 1), kCell);
  strip.difference(box(0, 1, 0, 1 - 16 * kCell));
  EXPECT_TRUE(strip.wider_than(kRegionGrowthCells));
}

TEST(ChartRegion, CoordinatesBeyondTheRangeAreAClearError) {
  const double far = kRegionRangeCells * kCell;
  EXPECT_THROW(ChartRegion(box(0, 2 * far), kCell), std::range_error);
  EXPECT_NO_THROW(ChartRegion(box(far / 2, far / 2 + 1), kCell));
}

TEST(ChartRegion, OperandsOnDifferentGridsAreALogicError) {
  ChartRegion a(box(0, 1), kCell);
  EXPECT_THROW(a.join(ChartRegion(box(0.5, 2), 2 * kCell)), std::logic_error);
  EXPECT_THROW(ChartRegion(box(0, 1), 3 * kCell), std::logic_error);  // not a power of two
}

// The grid is 2^-36 of the scene scale rounded up to a power of two: the same relative resolution for a
// scene in metres and one in micrometres.
TEST(ChartRegion, TheCellFollowsTheSceneScale) {
  EXPECT_EQ(region_cell(1.0), 0x1p-35);
  EXPECT_EQ(region_cell(0.75), 0x1p-36);
  EXPECT_EQ(region_cell(0.05), 0x1p-40);
  for (double scale : {1e-6, 0.05, 1.0, 300.0, 2e6}) {
    EXPECT_GT(region_cell(scale), 0x1p-37 * scale) << scale;
    EXPECT_LE(region_cell(scale), 0x1p-35 * scale) << scale;
  }
}

}  // namespace
}  // namespace cmt::face_geometry

// ReachedSet (verifier/reached_set.h, reached_set.cc and reached_set_clip.cc) in an empty 8 x 8 x 4 room and
// on a 45-degree ramp: building blocks (regions, segments, points, edge intervals, vertices), boundary
// closure, unite/restricted, areas and piece orientation, pieces_outside, locating task regions, and the
// within_box / without_box split. Distances are in reached_set_distance_test.cc.
#include "verifier/reached_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "models/loaded_task.h"
#include "models/task_error.h"
#include "tests/verifier/test_geometry.h"
#include "verifier/convex_polygon.h"

namespace cmt {
namespace {

using test::edge_between;
using test::face_at;
using test::vertex_at;

const Vec3 kX = Vec3::UnitX(), kY = Vec3::UnitY(), kZ = Vec3::UnitZ();

// Edge intervals are rounded outward by kEdgeParamSlack = 1e-12 (verifier/internal/face_regions.h): on the
// room's 8-long edges that is 8e-12 in position, plus rounding.
constexpr double kPositionSlack = 1e-11;

using test::room;

// A ramp z = x for x in [0, 2] (normal (−1,0,1)/sqrt 2, y in [-4, 4]) on the room's floor.
std::shared_ptr<const LoadedTask> ramp_room() {
  return room("[{convex: {vertices: [[0,-4,0],[2,-4,0],[2,-4,2],[0,4,0],[2,4,0],[2,4,2]]}}]");
}

// The room's atoms used below.
struct Room {
  explicit Room(const CSpace& c)
      : floor(face_at(c, kZ, Vec3(0, 0, 0))),
        ceiling(face_at(c, -kZ, Vec3(0, 0, 4))),
        wall_x(face_at(c, kX, Vec3(-4, 0, 1))),                   // x = -4
        wall_y(face_at(c, kY, Vec3(0, -4, 1))),                   // y = -4
        front(edge_between(c, Vec3(-4, -4, 0), Vec3(4, -4, 0))),  // floor meets y = -4
        side(edge_between(c, Vec3(-4, -4, 0), Vec3(-4, 4, 0))),   // floor meets x = -4
        upright(edge_between(c, Vec3(-4, -4, 0), Vec3(-4, -4, 4))),
        corner(vertex_at(c, Vec3(-4, -4, 0))),
        far_corner(vertex_at(c, Vec3(4, 4, 0))) {}
  bool ok() const {
    return std::min({floor, ceiling, wall_x, wall_y, front, side, upright, corner, far_corner}) >= 0;
  }
  int floor, ceiling, wall_x, wall_y, front, side, upright, corner, far_corner;
};

std::vector<Vec3> square(double x0, double y0, double x1, double y1) {
  return {{x0, y0, 0}, {x1, y0, 0}, {x1, y1, 0}, {x0, y1, 0}};
}

// The range of coordinate k over an edge interval's two end points.
std::pair<double, double> range(const CSpace& c, int edge, const EdgeInterval& iv, int k) {
  const Edge& e = c.edges()[c.atom_index(edge)];
  const double a = e.a[k] + iv.t0 * (e.b[k] - e.a[k]), b = e.a[k] + iv.t1 * (e.b[k] - e.a[k]);
  return {std::min(a, b), std::max(a, b)};
}

// The interval covers [lo, hi] along coordinate k (sound side) and exceeds it by at most kPositionSlack.
void expect_covers(const CSpace& c, int edge, const EdgeInterval& iv, int k, double lo, double hi) {
  const auto [a, b] = range(c, edge, iv, k);
  EXPECT_LE(a, lo);
  EXPECT_GE(b, hi);
  EXPECT_NEAR(a, lo, kPositionSlack);
  EXPECT_NEAR(b, hi, kPositionSlack);
}

std::vector<int> sorted(std::vector<int> v) {
  std::sort(v.begin(), v.end());
  return v;
}

bool has_point(const std::vector<Vec3>& pts, const Vec3& p) {
  return std::any_of(pts.begin(), pts.end(), [&](const Vec3& q) { return (q - p).norm() < 1e-12; });
}

Region region(Region::Kind kind, std::vector<Vec3> points) {
  Region r;
  r.kind = kind;
  r.points = std::move(points);
  r.key = "goal";
  return r;
}

// ---- building blocks ----

TEST(ReachedSet, NewSetIsEmpty) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  const ReachedSet s(t->cspace);
  EXPECT_TRUE(s.empty());
  EXPECT_TRUE(s.atoms().empty());
  EXPECT_TRUE(s.pieces().empty());
  EXPECT_EQ(s.area(), 0.0);
  EXPECT_FALSE(s.contains_atom(r.floor));
  EXPECT_TRUE(s.edge_intervals(r.front).empty());
  EXPECT_FALSE(s.has_vertex(r.corner));
  EXPECT_FALSE(s.face_region_contains(r.floor, Vec3(0, 0, 0)));
}

TEST(ReachedSet, WholeAtomsOfEachKind) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  s.add_whole_atom(r.floor);
  s.add_whole_atom(r.front);
  s.add_whole_atom(r.corner);
  EXPECT_DOUBLE_EQ(s.face_area(r.floor), 64);  // 8 x 8
  EXPECT_DOUBLE_EQ(s.area(), 64);              // faces only
  const auto iv = s.edge_intervals(r.front);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_EQ(iv[0].t0, 0.0);
  EXPECT_EQ(iv[0].t1, 1.0);
  EXPECT_TRUE(s.has_vertex(r.corner));
  EXPECT_FALSE(s.has_vertex(r.far_corner));
  EXPECT_EQ(s.atoms(), sorted({r.floor, r.front, r.corner}));
  EXPECT_FALSE(s.empty());
}

TEST(ReachedSet, FacePolygonsUniteIntoOneClosedRegion) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  s.add_face_polygon(r.floor, square(0, 0, 2, 2));
  s.add_face_polygon(r.floor, square(1, 0, 3, 2));  // overlaps: the union is [0,3] x [0,2], area 6
  EXPECT_DOUBLE_EQ(s.face_area(r.floor), 6);
  s.add_face_polygon(r.floor, square(0.5, 0.5, 1.5, 1.5));  // already covered
  EXPECT_DOUBLE_EQ(s.face_area(r.floor), 6);
  const auto pieces = s.pieces();
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].atom, r.floor);
  EXPECT_EQ(pieces[0].kind, AtomKind::kFace);
  EXPECT_DOUBLE_EQ(pieces[0].area, 6);
  EXPECT_TRUE(pieces[0].holes.empty());
  EXPECT_TRUE(s.face_region_contains(r.floor, Vec3(2.5, 1.5, 0)));
  EXPECT_TRUE(s.face_region_contains(r.floor, Vec3(3, 1, 0)));  // on the boundary: closed
  EXPECT_FALSE(s.face_region_contains(r.floor, Vec3(3.01, 1, 0)));
  // A point above the floor is judged by its projection into the floor's chart.
  EXPECT_TRUE(s.face_region_contains(r.floor, Vec3(2.5, 1.5, 3)));
}

TEST(ReachedSet, FacePolygonInputIsItsConvexHull) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  // Corners of [0,2]^2 out of order plus an interior point: the square, area 4.
  s.add_face_polygon(r.floor, {{0, 0, 0}, {2, 2, 0}, {2, 0, 0}, {1, 1, 0}, {0, 2, 0}});
  EXPECT_DOUBLE_EQ(s.face_area(r.floor), 4);
  // Collinear points make a segment (no area), a single point a point.
  ReachedSet seg(t->cspace);
  seg.add_face_polygon(r.floor, {{-3, 0, 0}, {-1, 0, 0}, {-2, 0, 0}});
  seg.add_face_polygon(r.floor, {{-3, 3, 0}});
  EXPECT_TRUE(seg.contains_atom(r.floor));
  EXPECT_EQ(seg.face_area(r.floor), 0.0);
  const auto pieces = seg.pieces();
  ASSERT_EQ(pieces.size(), 2u);
  ASSERT_EQ(pieces[0].polygon.size(), 2u);
  EXPECT_TRUE(has_point(pieces[0].polygon, Vec3(-3, 0, 0)));
  EXPECT_TRUE(has_point(pieces[0].polygon, Vec3(-1, 0, 0)));
  ASSERT_EQ(pieces[1].polygon.size(), 1u);
  EXPECT_TRUE(has_point(pieces[1].polygon, Vec3(-3, 3, 0)));
}

TEST(ReachedSet, SegmentsAndPointsInsideARegionAddNothing) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  s.add_face_polygon(r.floor, square(0, 0, 2, 2));
  s.add_face_segment(r.floor, Vec3(0.5, 0.5, 0), Vec3(1.5, 1.5, 0));  // inside
  s.add_face_segment(r.floor, Vec3(0, 0, 0), Vec3(2, 0, 0));          // along the closed boundary
  s.add_face_point(r.floor, Vec3(1, 1, 0));
  s.add_face_point(r.floor, Vec3(2, 2, 0));  // a corner
  EXPECT_EQ(s.pieces().size(), 1u);
  // From the region's side outward: kept as a segment; a point outside: kept.
  s.add_face_segment(r.floor, Vec3(2, 1, 0), Vec3(3, 1, 0));
  s.add_face_point(r.floor, Vec3(3, 3, 0));
  const auto pieces = s.pieces();
  ASSERT_EQ(pieces.size(), 3u);
  EXPECT_EQ(pieces[1].polygon.size(), 2u);
  EXPECT_EQ(pieces[2].polygon.size(), 1u);
  EXPECT_DOUBLE_EQ(s.face_area(r.floor), 4);  // segments and points add no area
}

TEST(ReachedSet, RegionAddedLaterSwallowsEarlierSegmentsAndPoints) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  s.add_face_segment(r.floor, Vec3(0.5, 1, 0), Vec3(1.5, 1, 0));
  s.add_face_point(r.floor, Vec3(1, 1.5, 0));
  ASSERT_EQ(s.pieces().size(), 2u);
  s.add_face_polygon(r.floor, square(0, 0, 2, 2));
  const auto pieces = s.pieces();
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_EQ(pieces[0].polygon.size(), 4u);
}

// A segment that leaves the region is kept whatever its midpoint: (1,1)-(3,1) has its midpoint (2,1) on the
// boundary of [0,2]^2 but reaches x = 3. Dropping it hid the part beyond x = 2 from pieces_outside, so a goal
// check could pass with a reached segment outside the goal (the segment was stored: distance() found it).
TEST(ReachedSet, ASegmentLeavingTheRegionIsKeptWhateverItsMidpoint) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet region_first(t->cspace), segment_first(t->cspace), goal(t->cspace);
  region_first.add_face_polygon(r.floor, square(0, 0, 2, 2));
  region_first.add_face_segment(r.floor, Vec3(1, 1, 0), Vec3(3, 1, 0));
  segment_first.add_face_segment(r.floor, Vec3(1, 1, 0), Vec3(3, 1, 0));
  segment_first.add_face_polygon(r.floor, square(0, 0, 2, 2));
  goal.add_face_polygon(r.floor, square(0, 0, 2, 2));
  for (const ReachedSet* s : {&region_first, &segment_first}) {
    ASSERT_EQ(s->pieces().size(), 2u);
    const auto out = s->pieces_outside(goal, 1e-9);
    ASSERT_EQ(out.size(), 1u);
    ASSERT_EQ(out[0].polygon.size(), 2u);  // the segment
    EXPECT_DOUBLE_EQ(std::max(out[0].polygon[0].x(), out[0].polygon[1].x()), 3);
  }
}

TEST(ReachedSet, EdgeIntervalsMergeClampAndOrder) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  s.add_edge_interval(r.front, 0.1, 0.3);
  s.add_edge_interval(r.front, 0.2, 0.5);  // overlaps: [.1, .5]
  s.add_edge_interval(r.front, 0.5, 0.6);  // touches: [.1, .6]
  s.add_edge_interval(r.front, 0.8, 0.7);  // reversed ends: [.7, .8]
  s.add_edge_interval(r.front, -1, 0.05);  // clamped to [0, .05]
  s.add_edge_interval(r.front, 2, 3);      // beyond the end: the point t = 1
  const auto iv = s.edge_intervals(r.front);
  ASSERT_EQ(iv.size(), 4u);
  const double want[4][2] = {{0, 0.05}, {0.1, 0.6}, {0.7, 0.8}, {1, 1}};
  for (int k = 0; k < 4; ++k) {
    EXPECT_EQ(iv[k].t0, want[k][0]) << k;
    EXPECT_EQ(iv[k].t1, want[k][1]) << k;
  }
  // A degenerate interval is one point: a 1-point piece; the others are 2-point pieces.
  std::vector<std::size_t> sizes;
  for (const ReachedPiece& p : s.pieces()) {
    EXPECT_EQ(p.kind, AtomKind::kEdge);
    sizes.push_back(p.polygon.size());
  }
  EXPECT_EQ(sizes, (std::vector<std::size_t>{2, 2, 2, 1}));
}

TEST(ReachedSet, BoundaryClosureAddsTheEdgesAndCornerAFaceRegionTouches) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  // [-4,-2]^2 in the floor's corner: it covers x in [-4,-2] of the front edge, y in [-4,-2] of the side edge,
  // and the corner (-4,-4,0); not the upright edge (not on the floor) nor the far corner.
  ReachedSet s(c);
  s.add_face_polygon(r.floor, square(-4, -4, -2, -2));
  s.add_boundary_closure();
  EXPECT_EQ(s.atoms(), sorted({r.floor, r.front, r.side, r.corner}));
  ASSERT_EQ(s.edge_intervals(r.front).size(), 1u);
  expect_covers(c, r.front, s.edge_intervals(r.front)[0], 0, -4, -2);
  ASSERT_EQ(s.edge_intervals(r.side).size(), 1u);
  expect_covers(c, r.side, s.edge_intervals(r.side)[0], 1, -4, -2);
  EXPECT_TRUE(s.edge_intervals(r.upright).empty());
  EXPECT_FALSE(s.has_vertex(r.far_corner));
  // A region inside the floor touches no edge.
  ReachedSet inner(c);
  inner.add_face_polygon(r.floor, square(-1, -1, 1, 1));
  inner.add_boundary_closure();
  EXPECT_EQ(inner.atoms(), std::vector<int>{r.floor});
}

TEST(ReachedSet, BoundaryClosureOfAnEdgeIntervalReachingAnEndAddsTheVertex) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  ReachedSet s(c);
  const Edge& e = c.edges()[c.atom_index(r.front)];
  // The half of the front edge that ends at the corner (-4,-4,0), whichever way the edge runs.
  if (e.vertex_a == r.corner)
    s.add_edge_interval(r.front, 0, 0.5);
  else
    s.add_edge_interval(r.front, 0.5, 1);
  s.add_boundary_closure();
  EXPECT_TRUE(s.has_vertex(r.corner));
  EXPECT_FALSE(s.has_vertex(vertex_at(c, Vec3(4, -4, 0))));
}

TEST(ReachedSet, UniteMergesEveryKindOfPiece) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet a(t->cspace), b(t->cspace);
  a.add_face_polygon(r.floor, square(0, 0, 1, 1));
  a.add_edge_interval(r.front, 0, 0.5);
  b.add_face_polygon(r.floor, square(1, 0, 2, 1));  // shares the side x = 1: one region of area 2
  b.add_edge_interval(r.front, 0.25, 1);
  b.add_vertex(r.corner);
  b.add_face_point(r.ceiling, Vec3(0, 0, 4));
  a.unite(b);
  EXPECT_DOUBLE_EQ(a.face_area(r.floor), 2);
  const auto iv = a.edge_intervals(r.front);
  ASSERT_EQ(iv.size(), 1u);
  EXPECT_EQ(iv[0].t0, 0.0);
  EXPECT_EQ(iv[0].t1, 1.0);
  EXPECT_TRUE(a.has_vertex(r.corner));
  EXPECT_EQ(a.atoms(), sorted({r.floor, r.ceiling, r.front, r.corner}));
  // b is unchanged.
  EXPECT_DOUBLE_EQ(b.face_area(r.floor), 1);
}

TEST(ReachedSet, RestrictedKeepsOnlyTheChosenAtoms) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  ReachedSet s(c);
  s.add_face_polygon(r.floor, square(0, 0, 1, 1));
  s.add_face_point(r.ceiling, Vec3(0, 0, 4));
  s.add_whole_atom(r.front);
  s.add_vertex(r.corner);
  std::vector<bool> keep(c.atom_count(), false);
  keep[r.floor] = true;
  keep[r.corner] = true;
  const ReachedSet kept = s.restricted(keep);
  EXPECT_EQ(kept.atoms(), sorted({r.floor, r.corner}));
  EXPECT_DOUBLE_EQ(kept.face_area(r.floor), 1);
  EXPECT_TRUE(kept.edge_intervals(r.front).empty());
  EXPECT_EQ(s.atoms(), sorted({r.floor, r.ceiling, r.front, r.corner}));  // the original is untouched
}

// ---- areas and pieces ----

TEST(ReachedSet, FaceAreaOfATiltedFaceIsItsTrueArea) {
  // The slope spans y in [-4, 4] and 2 sqrt 2 along the incline: 16 sqrt 2. Its chart drops an axis and
  // shrinks areas by 1/sqrt 2, which face_area must undo.
  const auto t = ramp_room();
  const CSpace& c = t->cspace;
  const int slope = face_at(c, Vec3(-1, 0, 1).normalized(), Vec3(1, 0, 1));
  ASSERT_GE(slope, 0);
  ReachedSet s(c);
  s.add_whole_atom(slope);
  EXPECT_NEAR(s.face_area(slope), 16 * std::sqrt(2.0), 1e-12);
  ReachedSet part(c);
  part.add_face_polygon(slope, {{0, -1, 0}, {2, -1, 2}, {2, 1, 2}, {0, 1, 0}});  // 2 wide: 4 sqrt 2
  EXPECT_NEAR(part.face_area(slope), 4 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(part.area(), 4 * std::sqrt(2.0), 1e-12);
  ASSERT_EQ(part.pieces().size(), 1u);
  EXPECT_NEAR(part.pieces()[0].area, 4 * std::sqrt(2.0), 1e-12);
}

TEST(ReachedSet, RegionPiecesAreCounterClockwiseAboutTheFaceNormal) {
  // On the floor (+z), the ceiling (−z, whose chart is flipped) and the slope the outer loop has positive
  // signed area about the face's own normal, equal to the piece's area.
  const auto t = ramp_room();
  const CSpace& c = t->cspace;
  const int floor = face_at(c, kZ, Vec3(-2, 0, 0));
  const int ceiling = face_at(c, -kZ, Vec3(0, 0, 4));
  const Vec3 n = Vec3(-1, 0, 1).normalized();
  const int slope = face_at(c, n, Vec3(1, 0, 1));
  ASSERT_GE(floor, 0);
  ASSERT_GE(ceiling, 0);
  ASSERT_GE(slope, 0);
  ReachedSet s(c);
  s.add_face_polygon(floor, square(-3, -1, -1, 1));                           // 4
  s.add_face_polygon(ceiling, {{0, 0, 4}, {1, 0, 4}, {1, 3, 4}, {0, 3, 4}});  // 3
  s.add_whole_atom(slope);                                                    // 16 sqrt 2
  const auto pieces = s.pieces();
  ASSERT_EQ(pieces.size(), 3u);
  for (const ReachedPiece& p : pieces) {
    const Vec3 normal = c.faces()[p.atom].normal;
    EXPECT_NEAR(polygon_area(p.polygon, normal), p.area, 1e-12) << c.atom_name(p.atom);
    EXPECT_GT(p.area, 0);
  }
  EXPECT_NEAR(s.area(), 4 + 3 + 16 * std::sqrt(2.0), 1e-12);
}

TEST(ReachedSet, PiecesOfARegionWithAHoleReportTheNetArea) {
  // The frame [-2,2]^2 less (-1,1)^2 from four rectangles: area 16 − 4 = 12, one piece with one hole.
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  s.add_face_polygon(r.floor, square(-2, 1, 2, 2));
  s.add_face_polygon(r.floor, square(-2, -2, 2, -1));
  s.add_face_polygon(r.floor, square(-2, -1, -1, 1));
  s.add_face_polygon(r.floor, square(1, -1, 2, 1));
  EXPECT_DOUBLE_EQ(s.face_area(r.floor), 12);
  const auto pieces = s.pieces();
  ASSERT_EQ(pieces.size(), 1u);
  ASSERT_EQ(pieces[0].holes.size(), 1u);
  EXPECT_DOUBLE_EQ(pieces[0].area, 12);
  EXPECT_NEAR(std::abs(polygon_area(pieces[0].holes[0], kZ)), 4, 1e-12);
  EXPECT_FALSE(s.face_region_contains(r.floor, Vec3(0, 0, 0)));
  EXPECT_TRUE(s.face_region_contains(r.floor, Vec3(1, 0, 0)));  // the hole's rim belongs to the region
}

TEST(ReachedSet, PiecesOutsideReportsWhatTheContainerMisses) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace), half(t->cspace);
  s.add_face_polygon(r.floor, square(0, 0, 2, 2));
  half.add_face_polygon(r.floor, square(0, 0, 1, 2));
  // [0,2]^2 less [0,1] x [0,2] is [1,2] x [0,2]: one piece of area 2.
  auto out = s.pieces_outside(half, 1e-9);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_DOUBLE_EQ(out[0].area, 2);
  for (const Vec3& p : out[0].polygon) EXPECT_GE(p.x(), 1);
  EXPECT_TRUE(s.pieces_outside(s, 0).empty());
  EXPECT_TRUE(half.pieces_outside(s, 0).empty());
  // A segment 1e-4 beyond the container's side y = 2: contained within 1e-3, not within 1e-5.
  ReachedSet seg(t->cspace);
  seg.add_face_segment(r.floor, Vec3(0, 2.0001, 0), Vec3(1, 2.0001, 0));
  EXPECT_TRUE(seg.pieces_outside(half, 1e-3).empty());
  EXPECT_EQ(seg.pieces_outside(half, 1e-5).size(), 1u);
  // Edge intervals and vertices on the closed boundary of a container region count as contained.
  ReachedSet whole_floor(t->cspace), rim(t->cspace);
  whole_floor.add_whole_atom(r.floor);
  rim.add_whole_atom(r.front);
  rim.add_vertex(r.corner);
  EXPECT_TRUE(rim.pieces_outside(whole_floor, 1e-9).empty());
  // The far corner (4,4,0) is 4 sqrt 2 from the quarter [-4,0]^2: reported.
  ReachedSet quarter(t->cspace), far(t->cspace);
  quarter.add_face_polygon(r.floor, square(-4, -4, 0, 0));
  far.add_vertex(r.far_corner);
  out = far.pieces_outside(quarter, 1e-9);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].kind, AtomKind::kVertex);
  EXPECT_EQ(out[0].atom, r.far_corner);
}

// Rounding slivers beside a goal atom within the tolerance are contained (issue: a corner goal must be
// verifiable); anything reaching farther than the tolerance is still reported.
TEST(ReachedSet, PiecesOutsideAcceptsSliversWithinTheToleranceOfAVertexOrEdge) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet corner(t->cspace);
  corner.add_vertex(r.corner);  // (-4, -4, 0)
  // An upright interval 4e-12 long from the corner (t in [0, 1e-12] of the 4-long edge): within 1e-9.
  ReachedSet edge_sliver(t->cspace);
  edge_sliver.add_edge_interval(r.upright, 0, 1e-12);
  EXPECT_TRUE(edge_sliver.pieces_outside(corner, 1e-9).empty());
  // 4e-4 long: its far end is 4e-4 from the corner, beyond 1e-9 and beyond 1e-5, within 1e-3.
  ReachedSet edge_piece(t->cspace);
  edge_piece.add_edge_interval(r.upright, 0, 1e-4);
  EXPECT_EQ(edge_piece.pieces_outside(corner, 1e-5).size(), 1u);
  EXPECT_TRUE(edge_piece.pieces_outside(corner, 1e-3).empty());
  // An interval that passes the corner's 1e-9 ball without ending in it: [0, 1e-12] is near, [0.5, 1] not.
  ReachedSet two(t->cspace);
  two.add_edge_interval(r.upright, 0, 1e-12);
  two.add_edge_interval(r.upright, 0.5, 1);
  EXPECT_EQ(two.pieces_outside(corner, 1e-9).size(), 1u);
  // A floor triangle of legs 1e-10 at the corner: every point within 1.5e-10 of it.
  ReachedSet face_sliver(t->cspace);
  face_sliver.add_face_polygon(r.floor, {{-4, -4, 0}, {-4 + 1e-10, -4, 0}, {-4, -4 + 1e-10, 0}});
  EXPECT_TRUE(face_sliver.pieces_outside(corner, 1e-9).empty());
  // Legs 1e-3: reported, with its area.
  ReachedSet face_piece(t->cspace);
  face_piece.add_face_polygon(r.floor, {{-4, -4, 0}, {-4 + 1e-3, -4, 0}, {-4, -4 + 1e-3, 0}});
  const auto out = face_piece.pieces_outside(corner, 1e-9);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].atom, r.floor);
  // Rounded outward onto the region kernel's grid: at most a cell along its 3.4e-3 boundary more.
  EXPECT_GE(out[0].area, 5e-7);
  EXPECT_LE(out[0].area, 5e-7 + 3.5e-3 * region_cell(t->cspace.scale()));
  // A floor strip 2e-10 wide along the whole front edge (y = -4): within 1e-9 of the edge, not of a vertex.
  ReachedSet front_edge(t->cspace), strip(t->cspace);
  front_edge.add_whole_atom(r.front);
  strip.add_face_polygon(r.floor, square(-4, -4, 4, -4 + 2e-10));
  EXPECT_TRUE(strip.pieces_outside(front_edge, 1e-9).empty());
  EXPECT_EQ(strip.pieces_outside(corner, 1e-9).size(), 1u);
  // The same strip 1e-6 wide: beyond 1e-9 of the edge.
  ReachedSet wide_strip(t->cspace);
  wide_strip.add_face_polygon(r.floor, square(-4, -4, 4, -4 + 1e-6));
  EXPECT_EQ(wide_strip.pieces_outside(front_edge, 1e-9).size(), 1u);
}

// ---- task regions ----

TEST(ReachedSet, FromRegionLocatesAPointOnAFaceAnEdgeOrAVertex) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  const ReachedSet on_floor = ReachedSet::from_region(*t, region(Region::Kind::kPoint, {{1, 1, 0}}));
  EXPECT_EQ(on_floor.atoms(), std::vector<int>{r.floor});
  EXPECT_EQ(on_floor.distance(Vec3(1, 1, 0)), 0.0);
  // (0,-4,0) is the middle of the front edge: the point t = .5 there, and in both faces' closures.
  const ReachedSet on_edge = ReachedSet::from_region(*t, region(Region::Kind::kPoint, {{0, -4, 0}}));
  EXPECT_EQ(on_edge.atoms(), sorted({r.floor, r.wall_y, r.front}));
  ASSERT_EQ(on_edge.edge_intervals(r.front).size(), 1u);
  EXPECT_EQ(on_edge.edge_intervals(r.front)[0].t0, 0.5);
  EXPECT_EQ(on_edge.edge_intervals(r.front)[0].t1, 0.5);
  // The corner: the vertex and its three faces, but no open edge.
  const ReachedSet at_corner = ReachedSet::from_region(*t, region(Region::Kind::kPoint, {{-4, -4, 0}}));
  EXPECT_TRUE(at_corner.has_vertex(r.corner));
  EXPECT_TRUE(at_corner.contains_atom(r.floor));
  EXPECT_TRUE(at_corner.contains_atom(r.wall_x));
  EXPECT_TRUE(at_corner.contains_atom(r.wall_y));
  EXPECT_TRUE(at_corner.edge_intervals(r.front).empty());
  EXPECT_TRUE(at_corner.edge_intervals(r.upright).empty());
}

TEST(ReachedSet, FromRegionRejectsRegionsOffTheSurface) {
  const auto t = room();
  // In free space, 2 above the floor.
  EXPECT_THROW(ReachedSet::from_region(*t, region(Region::Kind::kPoint, {{0, 0, 2}})), TaskError);
  // In the floor's plane but half outside the room (x < -4): samples there are 1 from every face.
  EXPECT_THROW(ReachedSet::from_region(
                   *t, region(Region::Kind::kPolygon, {{-5, 0, 0}, {-3, 0, 0}, {-3, 1, 0}, {-5, 1, 0}})),
               TaskError);
}

TEST(ReachedSet, FromRegionClipsAPolygonToItsFaceAndAddsTheClosure) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  const ReachedSet s = ReachedSet::from_region(
      *t, region(Region::Kind::kPolygon, {{-4, -4, 0}, {-2, -4, 0}, {-2, -2, 0}, {-4, -2, 0}}));
  EXPECT_DOUBLE_EQ(s.face_area(r.floor), 4);
  EXPECT_DOUBLE_EQ(s.area(), 4);  // the walls' planes do not hold the polygon
  EXPECT_EQ(s.atoms(), sorted({r.floor, r.front, r.side, r.corner}));
  ASSERT_EQ(s.edge_intervals(r.front).size(), 1u);
  expect_covers(c, r.front, s.edge_intervals(r.front)[0], 0, -4, -2);
}

TEST(ReachedSet, FromRegionSegmentAlongAnEdgeIsOnTheEdgeAndBothFaces) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  // (-2,-4,0)-(2,-4,0) lies on the front edge (x in [-2, 2]), in the planes of the floor and of the wall y =
  // -4.
  const ReachedSet s = ReachedSet::from_region(*t, region(Region::Kind::kSegment, {{-2, -4, 0}, {2, -4, 0}}));
  EXPECT_EQ(s.atoms(), sorted({r.floor, r.wall_y, r.front}));
  ASSERT_EQ(s.edge_intervals(r.front).size(), 1u);
  expect_covers(c, r.front, s.edge_intervals(r.front)[0], 0, -2, 2);
  EXPECT_EQ(s.area(), 0.0);
  EXPECT_NEAR(s.distance(Vec3(0, -3, 0)), 1, 1e-12);  // 1 in from the edge on the floor
}

TEST(ReachedSet, FromRegionsUnitesTheRegions) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  const ReachedSet s = ReachedSet::from_regions(
      *t, {region(Region::Kind::kPolygon, {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}),
           region(Region::Kind::kPolygon, {{0, 0, 4}, {2, 0, 4}, {2, 2, 4}, {0, 2, 4}}),
           region(Region::Kind::kPoint, {{3, 3, 0}})});
  EXPECT_DOUBLE_EQ(s.face_area(r.floor), 1);
  EXPECT_DOUBLE_EQ(s.face_area(r.ceiling), 4);
  EXPECT_EQ(s.atoms(), sorted({r.floor, r.ceiling}));
  EXPECT_EQ(s.pieces().size(), 3u);  // two regions and the point
}

// ---- within_box / without_box ----

TEST(ReachedSet, WithinBoxKeepsThePartInsideTheBox) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  ReachedSet s(c);
  s.add_whole_atom(r.floor);
  s.add_whole_atom(r.front);
  s.add_vertex(r.corner);
  s.add_vertex(r.far_corner);
  // Around the corner (-4,-4,0): the floor's [-4,-3]^2 (area 1), x in [-4,-3] of the front edge, the corner.
  const ReachedSet in = s.within_box({Vec3(-5, -5, -1), Vec3(-3, -3, 1)});
  EXPECT_DOUBLE_EQ(in.face_area(r.floor), 1);
  EXPECT_TRUE(in.face_region_contains(r.floor, Vec3(-3, -3, 0)));  // the box is closed
  ASSERT_EQ(in.edge_intervals(r.front).size(), 1u);
  expect_covers(c, r.front, in.edge_intervals(r.front)[0], 0, -4, -3);
  EXPECT_TRUE(in.has_vertex(r.corner));
  EXPECT_FALSE(in.has_vertex(r.far_corner));
  // In the middle: [-1,1]^2 of the floor only.
  const ReachedSet mid = s.within_box({Vec3(-1, -1, -1), Vec3(1, 1, 1)});
  EXPECT_DOUBLE_EQ(mid.face_area(r.floor), 4);
  EXPECT_EQ(mid.atoms(), std::vector<int>{r.floor});
  // Above the floor: nothing.
  EXPECT_TRUE(s.within_box({Vec3(-1, -1, 0.5), Vec3(1, 1, 1)}).empty());
}

TEST(ReachedSet, WithinBoxClipsSegmentsAndPoints) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  s.add_face_segment(r.floor, Vec3(-2, 0, 0), Vec3(2, 0, 0));
  s.add_face_point(r.floor, Vec3(0, 0.5, 0));
  s.add_face_point(r.floor, Vec3(3, 3, 0));
  const ReachedSet in = s.within_box({Vec3(-1, -1, -1), Vec3(1, 1, 1)});
  const auto pieces = in.pieces();
  ASSERT_EQ(pieces.size(), 2u);  // the segment's middle x in [-1, 1] and the point (0, .5)
  ASSERT_EQ(pieces[0].polygon.size(), 2u);
  EXPECT_TRUE(has_point(pieces[0].polygon, Vec3(-1, 0, 0)));
  EXPECT_TRUE(has_point(pieces[0].polygon, Vec3(1, 0, 0)));
  ASSERT_EQ(pieces[1].polygon.size(), 1u);
  EXPECT_TRUE(has_point(pieces[1].polygon, Vec3(0, 0.5, 0)));
}

TEST(ReachedSet, WithinBoxKeepsTheWholeContactWhereTheBoxOnlyTouchesAFace) {
  // The box [1,2] x [-1,1] x [0,1] lies under the slope z = x and touches it only along x = z = 1, y in
  // [-1,1]: that whole segment is kept (an over-approximation of a contact without area).
  const auto t = ramp_room();
  const CSpace& c = t->cspace;
  const int slope = face_at(c, Vec3(-1, 0, 1).normalized(), Vec3(1, 0, 1));
  ASSERT_GE(slope, 0);
  ReachedSet s(c);
  s.add_whole_atom(slope);
  const ReachedSet in = s.within_box({Vec3(1, -1, 0), Vec3(2, 1, 1)});
  EXPECT_TRUE(in.contains_atom(slope));
  EXPECT_EQ(in.face_area(slope), 0.0);
  const auto pieces = in.pieces();
  ASSERT_EQ(pieces.size(), 1u);
  ASSERT_EQ(pieces[0].polygon.size(), 2u);
  EXPECT_TRUE(has_point(pieces[0].polygon, Vec3(1, -1, 1)));
  EXPECT_TRUE(has_point(pieces[0].polygon, Vec3(1, 1, 1)));
}

TEST(ReachedSet, WithoutBoxRemovesOnlyThePartInsideTheBox) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  ReachedSet s(c);
  s.add_whole_atom(r.floor);
  s.add_whole_atom(r.front);
  s.add_vertex(r.corner);
  s.add_vertex(r.far_corner);
  // The box [-1,1] x [-5,-3] x [-1,1] covers the floor's [-1,1] x [-4,-3] (area 2) and x in [-1,1] of the
  // front edge: two intervals are left, each reaching at least to the box's side (removing only what is
  // surely inside).
  const ReachedSet out = s.without_box({Vec3(-1, -5, -1), Vec3(1, -3, 1)});
  EXPECT_DOUBLE_EQ(out.face_area(r.floor), 62);
  EXPECT_FALSE(out.face_region_contains(r.floor, Vec3(0, -3.5, 0)));
  EXPECT_TRUE(out.face_region_contains(r.floor, Vec3(0, -3, 0)));  // the box's boundary stays
  EXPECT_TRUE(out.face_region_contains(r.floor, Vec3(1, -3.5, 0)));
  const auto iv = out.edge_intervals(r.front);
  ASSERT_EQ(iv.size(), 2u);
  const auto [a0, a1] = range(c, r.front, iv[0], 0);
  const auto [b0, b1] = range(c, r.front, iv[1], 0);
  // Sorted by parameter, not by x: order the two pieces by x.
  const double lo_hi = std::min(a1, b1), hi_lo = std::max(a0, b0);
  EXPECT_EQ(std::min(a0, b0), -4.0);
  EXPECT_EQ(std::max(a1, b1), 4.0);
  EXPECT_GE(lo_hi, -1.0);
  EXPECT_NEAR(lo_hi, -1.0, kPositionSlack);
  EXPECT_LE(hi_lo, 1.0);
  EXPECT_NEAR(hi_lo, 1.0, kPositionSlack);
  EXPECT_TRUE(out.has_vertex(r.corner));
  EXPECT_TRUE(out.has_vertex(r.far_corner));
}

TEST(ReachedSet, WithoutBoxTakesAnEdgeEndAndAVertexInsideTheBox) {
  const auto t = room();
  const CSpace& c = t->cspace;
  const Room r(c);
  ASSERT_TRUE(r.ok());
  ReachedSet s(c);
  s.add_whole_atom(r.front);
  s.add_vertex(r.corner);
  s.add_vertex(r.far_corner);
  // The box around the corner holds x in [-4,-3] of the front edge, the edge's end among it: what is left
  // runs from x = -3 (or a hair into the box) to 4; the corner goes, the far corner stays.
  const ReachedSet out = s.without_box({Vec3(-5, -5, -1), Vec3(-3, -3, 1)});
  const auto iv = out.edge_intervals(r.front);
  ASSERT_EQ(iv.size(), 1u);
  const auto [x0, x1] = range(c, r.front, iv[0], 0);
  EXPECT_LE(x0, -3.0);
  EXPECT_NEAR(x0, -3.0, kPositionSlack);
  EXPECT_EQ(x1, 4.0);
  EXPECT_FALSE(out.has_vertex(r.corner));
  EXPECT_TRUE(out.has_vertex(r.far_corner));
}

TEST(ReachedSet, WithoutBoxSplitsSegmentsAndDropsPointsInside) {
  const auto t = room();
  const Room r(t->cspace);
  ASSERT_TRUE(r.ok());
  ReachedSet s(t->cspace);
  s.add_face_segment(r.floor, Vec3(-2, 0, 0), Vec3(2, 0, 0));
  s.add_face_point(r.floor, Vec3(0, 0.5, 0));
  s.add_face_point(r.floor, Vec3(3, 3, 0));
  const ReachedSet out = s.without_box({Vec3(-1, -1, -1), Vec3(1, 1, 1)});
  // Left: (-2..-1) and (1..2) with their closed ends at the box's sides, and the point (3, 3).
  int segments = 0, points = 0;
  for (const ReachedPiece& p : out.pieces()) {
    if (p.polygon.size() == 2) {
      ++segments;
      const double lo = std::min(p.polygon[0].x(), p.polygon[1].x()),
                   hi = std::max(p.polygon[0].x(), p.polygon[1].x());
      EXPECT_TRUE((lo == -2 && hi == -1) || (lo == 1 && hi == 2)) << lo << " " << hi;
    } else {
      ++points;
      EXPECT_TRUE(has_point(p.polygon, Vec3(3, 3, 0)));
    }
  }
  EXPECT_EQ(segments, 2);
  EXPECT_EQ(points, 1);
}

}  // namespace
}  // namespace cmt

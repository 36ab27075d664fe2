// Private to verifier/ .cc files (CGAL stays out of public headers): exact 2-D charts of faces, convex
// polygon clipping, and the representation behind ReachedSet.
#pragma once

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_with_holes_2.h>

#include <vector>

#include "models/cspace.h"
#include "verifier/reached_set.h"

namespace cmt::fp {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = Kernel::FT;
using Point2 = Kernel::Point_2;
using Vector2 = Kernel::Vector_2;
using Segment2 = Kernel::Segment_2;
using Point3 = Kernel::Point_3;
using Vector3 = Kernel::Vector_3;
using Plane3 = Kernel::Plane_3;
using Polygon2 = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles2 = CGAL::Polygon_with_holes_2<Kernel>;
using PolygonSet2 = CGAL::Polygon_set_2<Kernel>;
using Points2 = std::vector<Point2>;

inline Point3 exact(const Vec3& p) { return Point3(p.x(), p.y(), p.z()); }
inline Vec3 to_vec(const Point3& p) {
  return Vec3(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}
inline FT coord(const Point3& p, int i) { return i == 0 ? p.x() : (i == 1 ? p.y() : p.z()); }

// A face's 2-D chart (as in models/cspace_builder.cc, copied here because models/ keeps it private): drop the
// axis of the largest normal component; chart coordinates are the other two in cyclic order, so chart
// coordinates of double points are exact. `plane` is the exact plane through three corners of the face's
// double polygon, oriented by the face normal; lifting a chart point onto it is exact.
struct FaceChart {
  int drop = 2, u = 0, v = 1;
  Plane3 plane;
  bool flips = false;  // counter-clockwise in the chart is clockwise about the face normal

  Point2 project(const Vec3& p) const { return Point2(p[u], p[v]); }
  Point2 project(const Point3& p) const { return Point2(coord(p, u), coord(p, v)); }
  Vector2 project_direction(const Vec3& d) const { return Vector2(d[u], d[v]); }
  Point3 lift(const Point2& q) const;
  Vec3 lift_double(const Point2& q) const { return to_vec(lift(q)); }
};
FaceChart make_chart(const Face& face);

// A half-plane a u + b v + c >= 0 in a chart.
struct HalfPlane2 {
  FT a, b, c;
  bool contains(const Point2& p) const { return a * p.x() + b * p.y() + c >= 0; }
  bool trivial() const { return a == 0 && b == 0; }  // all or nothing, by the sign of c
};
// The half-space {y : plane(y) >= 0} (positive side) restricted to a chart.
HalfPlane2 restrict_to_chart(const Plane3& plane, const FaceChart& chart);

// Convex polygon helpers (counter-clockwise point lists in a chart, exact).
Points2 convex_hull(const Points2& points);  // counter-clockwise, collinear points removed
Points2 clip(const Points2& convex, const HalfPlane2& h);
Points2 clip(const Points2& convex, const Points2& convex_clip);
bool inside_closed(const Points2& convex, const Point2& p);
// Parameters [t0, t1] of the part of segment a + t (b - a), t in [0, 1], inside the closed convex polygon
// (2+ points; a 2-point "polygon" is a segment, a 1-point one a point). False when empty.
bool clip_segment(const Points2& convex, const Point2& a, const Point2& b, FT* t0, FT* t1);
Polygon2 to_polygon(const Points2& convex_ccw);
// Convex pieces (triangles and larger) of a regularized set, from CGAL's triangulation decomposition.
std::vector<Points2> convex_pieces(const PolygonSet2& set);
double area(const PolygonSet2& set);

// The union of many regions by pairwise overlays in a balanced tree. Never CGAL's aggregated
// Polygon_set_2::join(begin, end): CGAL 5.5 sweeps all inputs at once, and where edges of three or more
// inputs overlap on one line (parts clipped to one face edge, pieces cut along one line) its overlap step
// for curves with common ancestors (Surface_sweep_2_impl.h, the assertion at l.630 in a debug build) can
// build a corrupt arrangement. Which runs hit it depends on the order of subcurve addresses: the result is
// then non-simple and a later operation on it may crash. A pairwise overlay meets at most two overlapping
// edges at a time (docs/verifier-speed.md, "Unions of many regions").
PolygonSet2 union_of(std::vector<PolygonSet2> sets);
PolygonSet2 union_of(const std::vector<Polygon2>& polygons);
PolygonSet2 union_of(const std::vector<PolygonWithHoles2>& polygons);

// What one face holds.
struct FaceSet {
  PolygonSet2 region;
  std::vector<Segment2> segments;  // not covered by the region
  std::vector<Point2> points;      // not covered by the region or a segment
  bool empty() const { return region.is_empty() && segments.empty() && points.empty(); }
};

}  // namespace cmt::fp

namespace cmt {

struct ReachedSet::Impl {
  const CSpace* cspace = nullptr;
  std::vector<fp::FaceChart> charts;             // per face index
  std::vector<fp::Points2> face_polygon;         // per face index, counter-clockwise in the chart
  std::vector<fp::FaceSet> faces;                // per face index
  std::vector<std::vector<EdgeInterval>> edges;  // per edge index, sorted, disjoint
  std::vector<char> vertices;                    // per vertex index

  explicit Impl(const CSpace& c);
  // Each returns true when the set grew. Inputs are in the face's chart.
  bool add_region(int face_index, const fp::PolygonSet2& part, fp::PolygonSet2* added);
  bool add_segment(int face_index, const fp::Point2& a, const fp::Point2& b);
  bool add_point(int face_index, const fp::Point2& p);
  // Returns the length (in t) of what was new, and the new sub-intervals.
  double add_interval(int edge_index, double t0, double t1, std::vector<EdgeInterval>* added);
  bool add_vertex(int vertex_index);
  bool covered(int face_index, const fp::Point2& p) const;
};

// Parameter slack of edge intervals: endpoints are rounded outward by this much (t is a fraction of the
// edge), and sub-intervals shorter than 4x this are not treated as growth by the forward projection.
inline constexpr double kEdgeParamSlack = 1e-12;

}  // namespace cmt

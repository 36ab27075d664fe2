// Private to verifier/ .cc files (CGAL stays out of public headers): exact 2-D charts of faces, convex
// polygon clipping, and the representation behind ReachedSet. Namespace cmt::face_geometry holds the
// verifier's internals built on them (regions, flights, slides, sweeps); its kernel is the exact kernel of
// models/internal/exact_kernel.h (the same CGAL Epeck types).
#pragma once

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_with_holes_2.h>

#include <polyclipping/clipper.hpp>
#include <vector>

#include "models/cspace.h"
#include "verifier/reached_set.h"

namespace cmt::face_geometry {

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
using Points2 = std::vector<Point2>;

// A region whose new part is no wider than this many cells is rounding, not reach (docs/verifier.md,
// "Region kernel").
inline constexpr double kRegionGrowthCells = 4;

// A closed region of a face chart (Buckley's reached and termination sets on a face): polygons with holes
// on a grid of cell `cell` (region_cell of the scene scale, verifier/reached_set.h), overlaid by Clipper
// (integer coordinates, exact predicates). A polygon enters rounded outward (the hull of the grid cells
// around its vertices' interval bounds: it contains the exact polygon); an overlay rounds the crossings it
// creates to the nearest grid point (at most 0.71 cell). A set subtracted from a reached set is therefore
// up to 1.5 cells larger than computed: every such set is first shrunk by a margin of at least 1e-9 of the
// scene scale (kDecisionMargin, kUmbraRelativeMargin, kSensingBoxRelativeSlack, the inscribed sticking disks'
// pull-in), which is over 20 cells of 2^-35 scale. Operands of one operation share the grid
// (std::logic_error otherwise); an empty region takes the grid of what joins it.
class ChartRegion {
 public:
  ChartRegion() = default;
  ChartRegion(const Polygon2& polygon, double cell);  // rounded outward
  ChartRegion(const PolygonWithHoles2& polygon, double cell);
  double cell() const { return cell_; }
  void join(const ChartRegion& other);
  void join(const Polygon2& polygon, double cell) { join(ChartRegion(polygon, cell)); }
  void difference(const ChartRegion& other);
  void difference(const Polygon2& polygon);  // the polygon rounded outward, as everywhere
  void intersection(const ChartRegion& other);
  void intersection(const Polygon2& polygon);  // the polygon rounded outward
  bool is_empty() const { return paths_.empty(); }
  // Closed membership (ON_NEGATIVE_SIDE: outside) of the grid point nearest to p.
  CGAL::Oriented_side oriented_side(const Point2& p) const;
  // Outer boundaries counter-clockwise, holes clockwise; vertices are grid points.
  std::vector<PolygonWithHoles2> polygons_with_holes() const;
  template <class Out>
  void polygons_with_holes(Out out) const {
    for (PolygonWithHoles2& p : polygons_with_holes()) *out++ = std::move(p);
  }
  double area() const;
  // True when some part is wider than `cells` grid cells (what is left after eroding it by cells / 2).
  bool wider_than(double cells) const;
  // Contains the Minkowski sum with the hull of the origin and `pattern` (chart vectors): the hull is
  // rounded outward to the grid first.
  ChartRegion minkowski_sum(const std::vector<std::pair<double, double>>& pattern) const;
  // Every input at once (Clipper's union is robust for any number of inputs).
  static ChartRegion union_of(const std::vector<const ChartRegion*>& parts);

 private:
  void overlay(ClipperLib::ClipType type, const ChartRegion& other);
  double cell_ = 0;          // 0 while empty and never given a grid
  ClipperLib::Paths paths_;  // outer boundaries positive (Clipper's Orientation), holes negative
};

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
  double cell = 0;  // the region grid's cell (region_cell of the scene scale)
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
std::vector<Points2> convex_pieces(const ChartRegion& set);
double area(const ChartRegion& set);

// The union of many regions in one Clipper overlay.
ChartRegion union_of(std::vector<ChartRegion> sets);
ChartRegion union_of(const std::vector<Polygon2>& polygons, double cell);
ChartRegion union_of(const std::vector<PolygonWithHoles2>& polygons, double cell);

// What one face holds.
struct FaceSet {
  ChartRegion region;
  std::vector<Segment2> segments;  // not covered by the region
  std::vector<Point2> points;      // not covered by the region or a segment
  bool empty() const { return region.is_empty() && segments.empty() && points.empty(); }
};

}  // namespace cmt::face_geometry

namespace cmt {

struct ReachedSet::Impl {
  const CSpace* cspace = nullptr;
  std::vector<face_geometry::FaceChart> charts;      // per face index
  std::vector<face_geometry::Points2> face_polygon;  // per face index, counter-clockwise in the chart
  std::vector<face_geometry::FaceSet> faces;         // per face index
  std::vector<std::vector<EdgeInterval>> edges;      // per edge index, sorted, disjoint
  std::vector<char> vertices;                        // per vertex index

  explicit Impl(const CSpace& c);
  // Each returns true when the set grew (add_region: by a part wider than kRegionGrowthCells, which it
  // returns in `added`; narrower growth is stored all the same). Inputs are in the face's chart.
  bool add_region(int face_index, const face_geometry::ChartRegion& part, face_geometry::ChartRegion* added);
  bool add_segment(int face_index, const face_geometry::Point2& a, const face_geometry::Point2& b);
  bool add_point(int face_index, const face_geometry::Point2& p);
  // Returns the length (in t) of what was new, and the new sub-intervals.
  double add_interval(int edge_index, double t0, double t1, std::vector<EdgeInterval>* added);
  bool add_vertex(int vertex_index);
  bool covered(int face_index, const face_geometry::Point2& p) const;
};

// Parameter slack of edge intervals: endpoints are rounded outward by this much (t is a fraction of the
// edge), and sub-intervals shorter than 4x this are not treated as growth by the forward projection.
inline constexpr double kEdgeParamSlack = 1e-12;

}  // namespace cmt

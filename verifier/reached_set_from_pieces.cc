// ReachedSet::from_pieces: a set stored as pieces (ReachedSet::pieces(), the JSON of cmt verify) read back.
#include <algorithm>

#include "verifier/internal/face_regions.h"
#include "verifier/reached_set.h"

namespace cmt {

namespace {

using face_geometry::ChartRegion;
using face_geometry::Point2;
using face_geometry::Points2;
using face_geometry::Polygon2;

// A ring of 3-D points in a face's chart, counter-clockwise; empty when it has no area or, after the
// rounding to doubles, is not simple.
Polygon2 chart_ring(const face_geometry::FaceChart& chart, const std::vector<Vec3>& ring) {
  Points2 pts;
  for (const Vec3& p : ring) pts.push_back(chart.project(p));
  Polygon2 poly(pts.begin(), pts.end());
  if (poly.size() < 3 || !poly.is_simple() || poly.area() == 0) return Polygon2();
  if (poly.orientation() != CGAL::COUNTERCLOCKWISE) poly.reverse_orientation();
  return poly;
}

// The face region of a piece of 3+ points: its outer boundary minus its holes (pairwise overlays, so a hole
// that touches the boundary after rounding is still a valid operand). Where rounding broke a ring, the
// result stays a superset: an outer boundary becomes its convex hull, a hole is not subtracted.
ChartRegion face_region(const face_geometry::FaceChart& chart, const ReachedPiece& piece) {
  Polygon2 outer = chart_ring(chart, piece.polygon);
  if (outer.is_empty()) {
    Points2 pts;
    for (const Vec3& p : piece.polygon) pts.push_back(chart.project(p));
    const Points2 hull = face_geometry::convex_hull(pts);
    if (hull.size() < 3) return ChartRegion();
    outer = face_geometry::to_polygon(hull);
  }
  ChartRegion region(outer, chart.cell);
  for (const std::vector<Vec3>& hole : piece.holes) {
    const Polygon2 h = chart_ring(chart, hole);
    if (!h.is_empty()) region.difference(h);
  }
  return region;
}

double edge_parameter(const Edge& e, const Vec3& p) {
  const Vec3 d = e.b - e.a;
  return std::clamp((p - e.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
}

}  // namespace

ReachedSet ReachedSet::from_pieces(const CSpace& cspace, const std::vector<ReachedPiece>& pieces) {
  ReachedSet rs(cspace);
  Impl& im = rs.impl();
  for (const ReachedPiece& piece : pieces) {
    if (piece.polygon.empty()) continue;
    const int index = cspace.atom_index(piece.atom);
    switch (cspace.atom_kind(piece.atom)) {
      case AtomKind::kFace: {
        const face_geometry::FaceChart& chart = im.charts[index];
        if (piece.polygon.size() >= 3)
          im.add_region(index, face_region(chart, piece), nullptr);
        else if (piece.polygon.size() == 2)
          im.add_segment(index, chart.project(piece.polygon[0]), chart.project(piece.polygon[1]));
        else
          im.add_point(index, chart.project(piece.polygon[0]));
        break;
      }
      case AtomKind::kEdge: {
        const Edge& e = cspace.edges()[index];
        const double t0 = edge_parameter(e, piece.polygon.front());
        const double t1 = edge_parameter(e, piece.polygon.back());
        im.add_interval(index, std::min(t0, t1), std::max(t0, t1), nullptr);
        break;
      }
      case AtomKind::kVertex:
        im.add_vertex(index);
        break;
    }
  }
  return rs;
}

}  // namespace cmt

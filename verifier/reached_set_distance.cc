// ReachedSet::distance (verifier/reached_set.h): how far a point is from a reached set, for comparing
// observed rollout ends with the verifier's termination sets (experiments/validation/validation.h).
//
// Doubles, not exact arithmetic: the answer is compared with a contact tolerance of 1e-4 of the scene scale
// (validation.h kContactRelativeTolerance), twelve orders of magnitude above the rounding of these formulas.
// Only the in/out test of the orthogonal projection against a face region is exact (CGAL oriented_side on
// the double point), so a point exactly on a region reports 0.
#include <algorithm>
#include <cmath>
#include <limits>

#include "models/polygon_distance.h"
#include "verifier/internal/face_regions.h"
#include "verifier/reached_set.h"

namespace cmt {
namespace {

// Distance from q (in the face's plane) to the boundary loops of a region: the nearest point of a closed
// region to an outside point lies on its boundary, including the boundary of a hole that q is in.
double distance_to_loops(const Vec3& q, const face_geometry::ChartRegion& region,
                         const face_geometry::FaceChart& chart) {
  std::vector<face_geometry::PolygonWithHoles2> pwhs;
  region.polygons_with_holes(std::back_inserter(pwhs));
  double best = std::numeric_limits<double>::infinity();
  auto scan = [&](const face_geometry::Polygon2& loop) {
    for (auto e = loop.edges_begin(); e != loop.edges_end(); ++e)
      best = std::min(best,
                      distance_to_segment(q, chart.lift_double(e->source()), chart.lift_double(e->target())));
  };
  for (const face_geometry::PolygonWithHoles2& pwh : pwhs) {
    scan(pwh.outer_boundary());
    for (auto h = pwh.holes_begin(); h != pwh.holes_end(); ++h) scan(*h);
  }
  return best;
}

}  // namespace

double ReachedSet::distance(const Vec3& p) const {
  const Impl& im = *impl_;
  const CSpace& c = cspace();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t fi = 0; fi < im.faces.size(); ++fi) {
    const face_geometry::FaceSet& fs = im.faces[fi];
    if (fs.empty()) continue;
    const Face& face = c.faces()[fi];
    // Everything on the face lies in its plane: the distance is sqrt(offset^2 + in-plane distance^2) from
    // the orthogonal projection q (the chart itself is an axis projection, not distance-preserving, so
    // in-plane distances are measured in 3-D on lifted points).
    const double offset = face.normal.dot(p) - face.offset;
    if (std::abs(offset) >= best) continue;
    const Vec3 q = p - offset * face.normal;
    const face_geometry::FaceChart& chart = im.charts[fi];
    double in_plane = std::numeric_limits<double>::infinity();
    if (!fs.region.is_empty()) {
      in_plane = fs.region.oriented_side(chart.project(q)) != CGAL::ON_NEGATIVE_SIDE
                     ? 0.0
                     : distance_to_loops(q, fs.region, chart);
    }
    for (const face_geometry::Segment2& s : fs.segments)
      in_plane = std::min(
          in_plane, distance_to_segment(q, chart.lift_double(s.source()), chart.lift_double(s.target())));
    for (const face_geometry::Point2& pt : fs.points)
      in_plane = std::min(in_plane, (q - chart.lift_double(pt)).norm());
    best = std::min(best, std::hypot(offset, in_plane));
  }
  for (std::size_t ei = 0; ei < im.edges.size(); ++ei) {
    const Edge& e = c.edges()[ei];
    const Vec3 d = e.b - e.a;
    for (const EdgeInterval& iv : im.edges[ei])
      best = std::min(best, distance_to_segment(p, e.a + iv.t0 * d, e.a + iv.t1 * d));
  }
  for (std::size_t vi = 0; vi < im.vertices.size(); ++vi)
    if (im.vertices[vi]) best = std::min(best, (p - c.vertices()[vi].point).norm());
  return best;
}

}  // namespace cmt

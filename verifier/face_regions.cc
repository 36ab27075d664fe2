// Exact 2-D geometry in face charts (verifier/internal/face_regions.h).
#include "verifier/internal/face_regions.h"

#include <CGAL/Polygon_triangulation_decomposition_2.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>

namespace cmt::face_geometry {
namespace {

FT plane_coef(const Plane3& p, int i) { return i == 0 ? p.a() : (i == 1 ? p.b() : p.c()); }

HalfPlane2 left_of(const Point2& p, const Point2& q) {
  // cross(q - p, x - p) >= 0
  const FT dx = q.x() - p.x(), dy = q.y() - p.y();
  return {-dy, dx, dy * p.x() - dx * p.y()};
}

}  // namespace

Point3 FaceChart::lift(const Point2& q) const {
  FT c[3];
  c[u] = q.x();
  c[v] = q.y();
  c[drop] =
      -(plane_coef(plane, u) * q.x() + plane_coef(plane, v) * q.y() + plane.d()) / plane_coef(plane, drop);
  return Point3(c[0], c[1], c[2]);
}

FaceChart make_chart(const Face& face) {
  FaceChart chart;
  const Vec3& n = face.normal;
  const Vec3 a = n.cwiseAbs();
  chart.drop = (a.x() >= a.y() && a.x() >= a.z()) ? 0 : (a.y() >= a.z() ? 1 : 2);
  chart.u = (chart.drop + 1) % 3;
  chart.v = (chart.drop + 2) % 3;
  // The exact plane through the corner triple of largest double area.
  const auto& poly = face.polygon;
  std::size_t bi = 1, bj = 2;
  double best = -1;
  for (std::size_t i = 1; i < poly.size(); ++i)
    for (std::size_t j = i + 1; j < poly.size(); ++j) {
      const double area2 = (poly[i] - poly[0]).cross(poly[j] - poly[0]).norm();
      if (area2 > best) {
        best = area2;
        bi = i;
        bj = j;
      }
    }
  // A face whose polygon is degenerate (fewer than three points, or collinear ones: a sliver left by planes
  // that coincide up to rounding) has no plane through its corners. Its own plane n . x = offset then serves,
  // so that lifting into the chart (a division by the dropped axis's coefficient) stays defined.
  if (poly.size() >= 3) chart.plane = Plane3(exact(poly[0]), exact(poly[bi]), exact(poly[bj]));
  if (poly.size() < 3 || plane_coef(chart.plane, chart.drop) == 0)
    chart.plane = Plane3(FT(n.x()), FT(n.y()), FT(n.z()), FT(-face.offset));
  const Vector3 o = chart.plane.orthogonal_vector();
  if (CGAL::to_double(o.x()) * n.x() + CGAL::to_double(o.y()) * n.y() + CGAL::to_double(o.z()) * n.z() < 0)
    chart.plane = chart.plane.opposite();
  chart.flips = plane_coef(chart.plane, chart.drop) < 0;
  return chart;
}

HalfPlane2 restrict_to_chart(const Plane3& p, const FaceChart& chart) {
  const FT cd = plane_coef(chart.plane, chart.drop);
  const FT pd = plane_coef(p, chart.drop);
  return {plane_coef(p, chart.u) - pd * plane_coef(chart.plane, chart.u) / cd,
          plane_coef(p, chart.v) - pd * plane_coef(chart.plane, chart.v) / cd,
          p.d() - pd * chart.plane.d() / cd};
}

Points2 convex_hull(const Points2& points) {
  Points2 hull;
  CGAL::convex_hull_2(points.begin(), points.end(), std::back_inserter(hull));
  return hull;
}

Points2 clip(const Points2& convex, const HalfPlane2& h) {
  if (convex.empty()) return {};
  if (h.trivial()) return h.c >= 0 ? convex : Points2{};
  if (convex.size() == 1) return h.contains(convex[0]) ? convex : Points2{};
  Points2 out;
  const std::size_t n = convex.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Point2& p = convex[i];
    const Point2& q = convex[(i + 1) % n];
    const FT fp = h.a * p.x() + h.b * p.y() + h.c;
    const FT fq = h.a * q.x() + h.b * q.y() + h.c;
    if (fp >= 0) out.push_back(p);
    if ((fp > 0 && fq < 0) || (fp < 0 && fq > 0)) out.push_back(p + (q - p) * (fp / (fp - fq)));
  }
  return convex_hull(out);
}

// Two convex polygons meet in the hull of the vertices of each inside the other and the crossings of their
// edges. Each of those points is the input or one construction from it, whereas clipping by one edge line
// after another builds every round's crossings from the last round's, so that the lazy-exact expressions
// (and the exact evaluations the predicates on them fall back to) deepen with every round.
Points2 clip(const Points2& convex, const Points2& convex_clip) {
  if (convex.empty() || convex_clip.empty()) return {};
  if (convex.size() < 3 || convex_clip.size() < 3) {
    Points2 out = convex;
    const std::size_t n = convex_clip.size();
    for (std::size_t i = 0; i < n && !out.empty(); ++i)
      out = clip(out, left_of(convex_clip[i], convex_clip[(i + 1) % n]));
    return out;
  }
  Points2 candidates;
  for (const Point2& p : convex)
    if (inside_closed(convex_clip, p)) candidates.push_back(p);
  for (const Point2& p : convex_clip)
    if (inside_closed(convex, p)) candidates.push_back(p);
  const std::size_t n = convex.size(), m = convex_clip.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Segment2 a(convex[i], convex[(i + 1) % n]);
    for (std::size_t j = 0; j < m; ++j) {
      const Segment2 b(convex_clip[j], convex_clip[(j + 1) % m]);
      if (!CGAL::do_intersect(a, b)) continue;
      const auto x = CGAL::intersection(a, b);
      if (!x) continue;
      if (const Point2* p = boost::get<Point2>(&*x)) {
        candidates.push_back(*p);
      } else if (const Segment2* s = boost::get<Segment2>(&*x)) {
        candidates.push_back(s->source());
        candidates.push_back(s->target());
      }
    }
  }
  return convex_hull(candidates);
}

bool inside_closed(const Points2& convex, const Point2& p) {
  if (convex.empty()) return false;
  if (convex.size() == 1) return convex[0] == p;
  if (convex.size() == 2)
    return CGAL::collinear(convex[0], convex[1], p) &&
           CGAL::collinear_are_ordered_along_line(convex[0], p, convex[1]);
  for (std::size_t i = 0; i < convex.size(); ++i)
    if (CGAL::orientation(convex[i], convex[(i + 1) % convex.size()], p) == CGAL::RIGHT_TURN) return false;
  return true;
}

bool clip_segment(const Points2& convex, const Point2& a, const Point2& b, FT* t0, FT* t1) {
  if (convex.empty()) return false;
  const Vector2 ab = b - a;
  const FT len2 = ab.squared_length();
  if (len2 == 0) {
    if (!inside_closed(convex, a)) return false;
    *t0 = 0;
    *t1 = 1;
    return true;
  }
  auto param = [&](const Point2& p) { return ((p - a) * ab) / len2; };
  if (convex.size() == 1) {
    if (!CGAL::collinear(a, b, convex[0])) return false;
    const FT t = param(convex[0]);
    if (t < 0 || t > 1) return false;
    *t0 = *t1 = t;
    return true;
  }
  if (convex.size() == 2) {
    const Point2 &p = convex[0], &q = convex[1];
    if (CGAL::collinear(a, b, p) && CGAL::collinear(a, b, q)) {
      FT lo = CGAL::min(param(p), param(q)), hi = CGAL::max(param(p), param(q));
      lo = CGAL::max(lo, FT(0));
      hi = CGAL::min(hi, FT(1));
      if (lo > hi) return false;
      *t0 = lo;
      *t1 = hi;
      return true;
    }
    const auto x = CGAL::intersection(Segment2(a, b), Segment2(p, q));
    if (!x) return false;
    const Point2* pt = boost::get<Point2>(&*x);
    if (!pt) return false;
    *t0 = *t1 = param(*pt);
    return true;
  }
  FT lo = 0, hi = 1;
  const std::size_t n = convex.size();
  for (std::size_t i = 0; i < n; ++i) {
    const HalfPlane2 h = left_of(convex[i], convex[(i + 1) % n]);
    const FT fa = h.a * a.x() + h.b * a.y() + h.c;
    const FT fb = h.a * b.x() + h.b * b.y() + h.c;
    if (fa < 0 && fb < 0) return false;
    if (fa < 0) lo = CGAL::max(lo, fa / (fa - fb));
    if (fb < 0) hi = CGAL::min(hi, fa / (fa - fb));
    if (lo > hi) return false;
  }
  *t0 = lo;
  *t1 = hi;
  return true;
}

Polygon2 to_polygon(const Points2& convex_ccw) { return Polygon2(convex_ccw.begin(), convex_ccw.end()); }

std::vector<Points2> convex_pieces(const ChartRegion& set) {
  std::vector<PolygonWithHoles2> pwhs;
  set.polygons_with_holes(std::back_inserter(pwhs));
  std::vector<Points2> out;
  for (const PolygonWithHoles2& pwh : pwhs) {
    if (!pwh.has_holes() && pwh.outer_boundary().is_convex()) {
      out.push_back(
          convex_hull(Points2(pwh.outer_boundary().vertices_begin(), pwh.outer_boundary().vertices_end())));
      continue;
    }
    std::vector<Polygon2> triangles;
    CGAL::Polygon_triangulation_decomposition_2<Kernel>()(pwh, std::back_inserter(triangles));
    for (const Polygon2& t : triangles)
      out.push_back(convex_hull(Points2(t.vertices_begin(), t.vertices_end())));
  }
  return out;
}

ChartRegion union_of(std::vector<ChartRegion> sets) {
  std::vector<const ChartRegion*> parts;
  parts.reserve(sets.size());
  for (const ChartRegion& r : sets) parts.push_back(&r);
  return ChartRegion::union_of(parts);
}

ChartRegion union_of(const std::vector<Polygon2>& polygons, double cell) {
  std::vector<ChartRegion> sets;
  sets.reserve(polygons.size());
  for (const Polygon2& p : polygons) sets.emplace_back(p, cell);
  return union_of(std::move(sets));
}

ChartRegion union_of(const std::vector<PolygonWithHoles2>& polygons, double cell) {
  std::vector<ChartRegion> sets;
  sets.reserve(polygons.size());
  for (const PolygonWithHoles2& p : polygons) sets.emplace_back(p, cell);
  return union_of(std::move(sets));
}

double area(const ChartRegion& set) { return set.area(); }

}  // namespace cmt::face_geometry

#include "verifier/edr/distinguish.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/polygon_distance.h"
#include "verifier/atom_cone.h"
#include "verifier/sensing.h"

namespace cmt {
namespace {

// A piece as a convex set: 1 point, a segment (2), or a convex planar polygon (3+, counter-clockwise about
// `normal`).
struct ConvexPiece {
  std::vector<Vec3> points;
  Vec3 normal = Vec3::UnitZ();
};

// The convex hull of planar points (Andrew's monotone chain in the plane's own basis).
ConvexPiece planar_hull(const std::vector<Vec3>& pts) {
  ConvexPiece out;
  Vec3 n = polygon_normal(pts);
  if (!(n.norm() > 0.5)) {  // collinear: the two points farthest apart
    std::size_t bi = 0, bj = 0;
    double best = -1;
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (std::size_t j = i + 1; j < pts.size(); ++j)
        if ((pts[i] - pts[j]).squaredNorm() > best) best = (pts[i] - pts[j]).squaredNorm(), bi = i, bj = j;
    out.points = {pts[bi], pts[bj]};
    return out;
  }
  n.normalize();
  const Vec3 u = n.unitOrthogonal(), w = n.cross(u);
  std::vector<std::size_t> order(pts.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto uv = [&](std::size_t i) { return std::pair<double, double>(pts[i].dot(u), pts[i].dot(w)); };
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return uv(a) < uv(b); });
  auto cross = [&](std::size_t o, std::size_t a, std::size_t b) {
    const auto [ox, oy] = uv(o);
    const auto [ax, ay] = uv(a);
    const auto [bx, by] = uv(b);
    return (ax - ox) * (by - oy) - (ay - oy) * (bx - ox);
  };
  std::vector<std::size_t> hull(2 * order.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], order[i]) <= 0) --k;
    hull[k++] = order[i];
  }
  for (std::size_t i = order.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], order[i]) <= 0) --k;
    hull[k++] = order[i];
  }
  hull.resize(k > 1 ? k - 1 : k);
  for (std::size_t i : hull) out.points.push_back(pts[i]);
  out.normal = n;  // counter-clockwise about n in the basis (u, w = n x u)
  if (out.points.size() < 3) out.points.resize(std::min<std::size_t>(out.points.size(), 2));
  return out;
}

ConvexPiece convex_piece(const ReachedPiece& p) {
  if (p.polygon.size() >= 3) return planar_hull(p.polygon);
  return ConvexPiece{p.polygon, Vec3::UnitZ()};
}

double point_to_piece(const Vec3& p, const ConvexPiece& s) {
  if (s.points.size() == 1) return (p - s.points[0]).norm();
  if (s.points.size() == 2) return distance_to_segment(p, s.points[0], s.points[1]);
  return distance_to_convex_polygon(p, s.points, s.normal);
}

// 0 when segment [p, q] crosses the polygon's plane at a point of the polygon, else +infinity.
double segment_crossing(const Vec3& p, const Vec3& q, const ConvexPiece& poly) {
  const double sp = poly.normal.dot(p - poly.points[0]), sq = poly.normal.dot(q - poly.points[0]);
  if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0) || sp == sq) return std::numeric_limits<double>::infinity();
  const Vec3 x = p + (sp / (sp - sq)) * (q - p);
  return distance_to_convex_polygon(x, poly.points, poly.normal);
}

std::vector<std::pair<Vec3, Vec3>> edges_of(const ConvexPiece& s) {
  std::vector<std::pair<Vec3, Vec3>> out;
  if (s.points.size() == 2) out.emplace_back(s.points[0], s.points[1]);
  if (s.points.size() >= 3)
    for (std::size_t i = 0; i < s.points.size(); ++i)
      out.emplace_back(s.points[i], s.points[(i + 1) % s.points.size()]);
  return out;
}

}  // namespace

double piece_distance_lower_bound(const ReachedPiece& pa, const ReachedPiece& pb) {
  const ConvexPiece a = convex_piece(pa), b = convex_piece(pb);
  if (a.points.empty() || b.points.empty()) return std::numeric_limits<double>::infinity();
  // Between compact convex sets of dimension <= 2 the distance is attained at a vertex of one, at a pair of
  // boundary edges, or (when they meet) where an edge of one crosses the other.
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& p : a.points) best = std::min(best, point_to_piece(p, b));
  for (const Vec3& p : b.points) best = std::min(best, point_to_piece(p, a));
  const auto ea = edges_of(a), eb = edges_of(b);
  for (const auto& [p, q] : ea)
    for (const auto& [r, s] : eb) best = std::min(best, distance_between_segments(p, q, r, s));
  if (b.points.size() >= 3)
    for (const auto& [p, q] : ea) best = std::min(best, segment_crossing(p, q, b));
  if (a.points.size() >= 3)
    for (const auto& [p, q] : eb) best = std::min(best, segment_crossing(p, q, a));
  return best;
}

bool confusable(const ReachedPiece& a, const FrictionCone& ca, const ReachedPiece& b, const FrictionCone& cb,
                double eps_s, double theta_f, double margin, Confusion* out) {
  out->distance = piece_distance_lower_bound(a, b);
  if (out->distance > 2 * eps_s + margin) return false;
  out->force_angle = force_angle_lower_bound(ca, cb);
  return out->force_angle <= 2 * theta_f;
}

std::vector<Confusion> confusable_pairs(const std::vector<SlicePiece>& first,
                                        const std::vector<SlicePiece>& second, double eps_s, double theta_f,
                                        double margin) {
  std::vector<Confusion> out;
  std::vector<FrictionCone> cones_a, cones_b;
  for (const SlicePiece& p : first) cones_a.push_back(atom_friction_cone(*p.cspace, p.piece.atom));
  for (const SlicePiece& p : second) cones_b.push_back(atom_friction_cone(*p.cspace, p.piece.atom));
  for (std::size_t i = 0; i < first.size(); ++i)
    for (std::size_t j = 0; j < second.size(); ++j) {
      Confusion c{static_cast<int>(i), static_cast<int>(j)};
      if (confusable(first[i].piece, cones_a[i], second[j].piece, cones_b[j], eps_s, theta_f, margin, &c))
        out.push_back(c);
    }
  return out;
}

}  // namespace cmt

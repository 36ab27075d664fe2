#include "models/polygon_distance.h"

#include <algorithm>
#include <limits>
#include <utility>
#include <vector>

namespace cmt {

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double distance_to_convex_polygon(const Vec3& p, const std::vector<Vec3>& polygon, const Vec3& normal) {
  const std::size_t n = polygon.size();
  bool inside = n >= 3;
  for (std::size_t i = 0; i < n && inside; ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % n];
    inside = normal.dot((b - a).cross(p - a)) >= 0;
  }
  if (inside) return std::abs(normal.dot(p - polygon[0]));
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < n; ++i)
    best = std::min(best, distance_to_segment(p, polygon[i], polygon[(i + 1) % n]));
  return best;
}

Vec3 polygon_normal(const std::vector<Vec3>& polygon) {
  // Newell's method: the normal about which the polygon's own vertex order is counter-clockwise.
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    n += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
              (a.x() - b.x()) * (a.y() + b.y()));
  }
  return n.normalized();
}

double distance_between_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) return r.norm();
  if (a <= 0) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  return ((p0 + s * d1) - (q0 + t * d2)).norm();
}

namespace {

double point_to_convex_set(const Vec3& p, const std::vector<Vec3>& s, const Vec3& n) {
  if (s.size() == 1) return (p - s[0]).norm();
  if (s.size() == 2) return distance_to_segment(p, s[0], s[1]);
  return distance_to_convex_polygon(p, s, n);
}

std::vector<std::pair<Vec3, Vec3>> boundary_edges(const std::vector<Vec3>& s) {
  std::vector<std::pair<Vec3, Vec3>> out;
  if (s.size() == 2) out.emplace_back(s[0], s[1]);
  if (s.size() >= 3)
    for (std::size_t i = 0; i < s.size(); ++i) out.emplace_back(s[i], s[(i + 1) % s.size()]);
  return out;
}

// The distance from the polygon to where segment [p, q] crosses its plane, +infinity when it does not.
double segment_crossing(const Vec3& p, const Vec3& q, const std::vector<Vec3>& poly, const Vec3& n) {
  const double sp = n.dot(p - poly[0]), sq = n.dot(q - poly[0]);
  if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0) || sp == sq) return std::numeric_limits<double>::infinity();
  return distance_to_convex_polygon(p + (sp / (sp - sq)) * (q - p), poly, n);
}

}  // namespace

double distance_between_convex_sets(const std::vector<Vec3>& a, const Vec3& na, const std::vector<Vec3>& b,
                                    const Vec3& nb) {
  if (a.empty() || b.empty()) return std::numeric_limits<double>::infinity();
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& p : a) best = std::min(best, point_to_convex_set(p, b, nb));
  for (const Vec3& p : b) best = std::min(best, point_to_convex_set(p, a, na));
  const auto ea = boundary_edges(a), eb = boundary_edges(b);
  for (const auto& [p, q] : ea)
    for (const auto& [r, s] : eb) best = std::min(best, distance_between_segments(p, q, r, s));
  if (b.size() >= 3)
    for (const auto& [p, q] : ea) best = std::min(best, segment_crossing(p, q, b, nb));
  if (a.size() >= 3)
    for (const auto& [p, q] : eb) best = std::min(best, segment_crossing(p, q, a, na));
  return best;
}

}  // namespace cmt

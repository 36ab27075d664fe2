#include "verifier/convex_polygon.h"

namespace cmt {

std::vector<Vec3> clip_convex_polygon(const std::vector<Vec3>& subject, const std::vector<Vec3>& clip,
                                      const Vec3& n) {
  // Sutherland-Hodgman against each clip edge (keep the left side, counter-clockwise about n).
  std::vector<Vec3> out = subject;
  const std::size_t k = clip.size();
  for (std::size_t i = 0; i < k && !out.empty(); ++i) {
    const Vec3& a = clip[i];
    const Vec3 edge = clip[(i + 1) % k] - a;
    auto side = [&](const Vec3& p) { return n.dot(edge.cross(p - a)); };
    std::vector<Vec3> next;
    for (std::size_t j = 0; j < out.size(); ++j) {
      const Vec3& p = out[j];
      const Vec3& q = out[(j + 1) % out.size()];
      const double sp = side(p), sq = side(q);
      if (sp >= 0) next.push_back(p);
      if ((sp >= 0) != (sq >= 0)) next.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    out = std::move(next);
  }
  if (out.size() < 3) out.clear();
  return out;
}

double polygon_area(const std::vector<Vec3>& polygon, const Vec3& n) {
  Vec3 s = Vec3::Zero();
  for (std::size_t i = 0; i < polygon.size(); ++i) s += polygon[i].cross(polygon[(i + 1) % polygon.size()]);
  return 0.5 * n.dot(s);
}

std::vector<Vec3> clip_to_halfspace(const std::vector<Vec3>& points, const Vec3& d, double level) {
  std::vector<Vec3> out;
  if (points.size() <= 2) {
    for (const Vec3& p : points)
      if (d.dot(p) <= level) out.push_back(p);
    if (points.size() == 2) {
      const double fa = d.dot(points[0]) - level, fb = d.dot(points[1]) - level;
      if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0))
        out.push_back(points[0] + (points[1] - points[0]) * (fa / (fa - fb)));
    }
    return out;
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& a = points[i];
    const Vec3& b = points[(i + 1) % points.size()];
    const double fa = d.dot(a) - level, fb = d.dot(b) - level;
    if (fa <= 0) out.push_back(a);
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) out.push_back(a + (b - a) * (fa / (fa - fb)));
  }
  return out;
}

}  // namespace cmt

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

}  // namespace cmt

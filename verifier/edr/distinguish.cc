#include "verifier/edr/distinguish.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/polygon_distance.h"
#include "verifier/atom_cone.h"
#include "verifier/sensing.h"

namespace cmt {
namespace {}  // namespace

Vec3 plane_normal(const std::vector<Vec3>& pts) {
  if (pts.size() < 3) return Vec3::Zero();
  std::size_t far = 0;
  for (std::size_t i = 1; i < pts.size(); ++i)
    if ((pts[i] - pts[0]).squaredNorm() > (pts[far] - pts[0]).squaredNorm()) far = i;
  const Vec3 d = pts[far] - pts[0];
  if (d.norm() == 0) return Vec3::Zero();
  Vec3 best = Vec3::Zero();
  for (const Vec3& p : pts) {
    const Vec3 c = d.cross(p - pts[0]);
    if (c.norm() > best.norm()) best = c;
  }
  return best.norm() > 1e-12 * d.squaredNorm() ? Vec3(best.normalized()) : Vec3(Vec3::Zero());
}

namespace {

// The convex hull of planar points (Andrew's monotone chain in the plane's own basis).
ConvexPiece planar_hull(const std::vector<Vec3>& pts) {
  ConvexPiece out;
  Vec3 n = plane_normal(pts);
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

}  // namespace

ConvexPiece convex_piece(const ReachedPiece& p) {
  if (p.polygon.size() >= 3) return planar_hull(p.polygon);
  return ConvexPiece{p.polygon, Vec3::UnitZ()};
}

double point_to_piece(const Vec3& p, const ConvexPiece& s) {
  return distance_between_convex_sets({p}, Vec3::UnitZ(), s.points, s.normal);
}

double piece_distance_lower_bound(const ReachedPiece& pa, const ReachedPiece& pb) {
  const ConvexPiece a = convex_piece(pa), b = convex_piece(pb);
  return distance_between_convex_sets(a.points, a.normal, b.points, b.normal);
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

// The reach bound of a velocity-form spring motion (verifier/spring_projection.h velocity_reach_bound) and
// its section by a face (verifier/internal/spring_velocity.h).
#include <algorithm>
#include <cmath>
#include <vector>

#include "verifier/internal/spring_velocity.h"
#include "verifier/internal/spring_velocity_support.h"

namespace cmt::face_geometry {

Points2 velocity_reach_section(const ReachedSet::Impl& g, int fi, const VelocitySpring& m) {
  return support_section(g, fi, {ball_support(m.p, m.reach)}, false, &m.bounds);
}

}  // namespace cmt::face_geometry

namespace cmt {

double velocity_reach_bound(const CSpace& c, const ReachedSet& start, const Vec3& p, const Uncertainty& u) {
  const double eps = u.eps_s, T = std::tan(u.theta_v), cos_v = std::cos(u.theta_v);
  double v = 0;  // >= |x − p*| for every point of the motion so far
  for (const ReachedPiece& piece : start.pieces())
    for (const Vec3& q : piece.polygon) v = std::max(v, (q - p).norm() + eps);
  // A zone can raise the bound only on an atom the robot can reach at all, i.e. one with a point within v of
  // p*; iterate until no zone raises it (each round takes in at least one more atom, or stops).
  const std::size_t nf = c.faces().size(), ne = c.edges().size();
  std::vector<char> used(nf + ne, 0);
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t i = 0; i < nf; ++i) {
      if (used[i]) continue;
      const Face& f = c.faces()[i];
      const double depth = f.offset - f.normal.dot(p);
      const Vec3 center = p + depth * f.normal;
      const double inplane = face_geometry::distance_in_plane(f.polygon, f.normal, center);
      const double h = std::abs(depth) + eps;
      if (std::hypot(depth, inplane) > v + eps) continue;  // not reachable within the bound
      if (inplane > h * T + eps) continue;                 // the zone about p*' misses the face
      used[i] = 1;
      if (h / cos_v > v) {
        v = h / cos_v;
        grew = true;
      }
    }
    for (std::size_t i = 0; i < ne; ++i) {
      if (used[nf + i]) continue;
      const Edge& e = c.edges()[i];
      const Vec3 d = e.b - e.a;
      const double len = d.norm();
      const double t = (p - e.a).dot(d) / (len * len);
      const double perp = (p - (e.a + t * d)).norm();
      const double gap = std::max({0.0, -t * len, (t - 1) * len});  // from the projection to the segment
      if (std::hypot(perp, gap) > v + eps) continue;
      if (gap > (perp + eps) * T + eps) continue;
      used[nf + i] = 1;
      if ((perp + eps) / cos_v > v) {
        v = (perp + eps) / cos_v;
        grew = true;
      }
    }
  }
  return (v + eps) * (1 + face_geometry::kVelocitySlack) + face_geometry::kVelocitySlack * c.scale();
}

}  // namespace cmt

#include "verifier/sensing.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/polygon_distance.h"
#include "verifier/atom_cone.h"

namespace cmt {

Polyhedron sensed_positions(const CSpace& cspace, int atom_id, double eps_s) {
  const std::vector<Vec3> pts = atom_points(cspace, atom_id);
  std::vector<Vec3> dirs;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) dirs.push_back(Vec3(x, y, z).normalized());
  for (int f : atom_faces(cspace, atom_id)) {
    const Face& face = cspace.faces()[f];
    dirs.push_back(face.normal);
    dirs.push_back(-face.normal);
  }
  if (pts.size() >= 2)
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Vec3 e = pts[(i + 1) % pts.size()] - pts[i];
      for (int f : atom_faces(cspace, atom_id)) {
        const Vec3 m = e.cross(cspace.faces()[f].normal);
        if (m.norm() > 0) {
          dirs.push_back(m.normalized());
          dirs.push_back(-m.normalized());
        }
      }
    }
  Polyhedron out;
  out.kind = Polyhedron::Kind::kConvex;
  for (const Vec3& u : dirs) {
    double h = -std::numeric_limits<double>::infinity();
    for (const Vec3& p : pts) h = std::max(h, u.dot(p));
    out.halfspaces.push_back({u, h + eps_s});
  }
  return out;
}

FrictionCone sensed_forces(const CSpace& cspace, int atom_id, double theta_f) {
  return atom_friction_cone(cspace, atom_id).widened(theta_f);
}

double atom_distance(const CSpace& cspace, int a, int b) {
  auto normal = [&](int id) {
    return cspace.atom_kind(id) == AtomKind::kFace ? cspace.faces()[id].normal : Vec3(Vec3::UnitZ());
  };
  return distance_between_convex_sets(atom_points(cspace, a), normal(a), atom_points(cspace, b), normal(b));
}

double force_angle_lower_bound(const CSpace& cspace, int a, int b) {
  return force_angle_lower_bound(atom_friction_cone(cspace, a), atom_friction_cone(cspace, b));
}

double force_angle_lower_bound(const FrictionCone& ca, const FrictionCone& cb) {
  // Smallest angle between two convex cones, if disjoint, is attained at an extreme ray of one of them
  // (spherical convex polygons); the outer cones' rays bound it from below.
  if (ca.is_full(/*outer=*/true) || cb.is_full(/*outer=*/true)) return 0;
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3& r : ca.rays(/*outer=*/true)) best = std::min(best, cb.angle_lower_bound(r));
  for (const Vec3& r : cb.rays(/*outer=*/true)) best = std::min(best, ca.angle_lower_bound(r));
  return best;
}

bool disambiguable(const CSpace& cspace, int a, int b, double eps_s, double theta_f,
                   const std::function<const FrictionCone&(int atom)>& cone) {
  if (a == b) return false;
  if (atom_distance(cspace, a, b) > 2 * eps_s) return true;
  const std::vector<int> fa = atom_faces(cspace, a), fb = atom_faces(cspace, b);
  for (int f : fa)
    if (std::find(fb.begin(), fb.end(), f) != fb.end()) return false;  // §6.4.1: shared face
  return force_angle_lower_bound(cone(a), cone(b)) > 2 * theta_f;
}

bool disambiguable(const CSpace& cspace, int a, int b, double eps_s, double theta_f) {
  FrictionCone ca, cb;
  return disambiguable(cspace, a, b, eps_s, theta_f, [&](int atom) -> const FrictionCone& {
    FrictionCone& c = atom == a ? ca : cb;
    c = atom_friction_cone(cspace, atom);
    return c;
  });
}

}  // namespace cmt

#include "verifier/spring.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "models/friction_cone.h"
#include "verifier/atom_cone.h"
#include "verifier/convex_polygon.h"
#include "verifier/internal/frame.h"
#include "verifier/unique_stick.h"

namespace cmt {
namespace {

constexpr double kHalfPi = std::numbers::pi / 2;
// Sides of the polygons that approximate sticking disks on a face.
constexpr int kDiskPolygonSides = 64;

std::vector<Vec3> negated(const std::vector<Vec3>& v) {
  std::vector<Vec3> out;
  for (const Vec3& x : v) out.push_back(-x);
  return out;
}

// Regular polygon about `center` in the face plane: circumscribed about the circle of radius r when outer,
// else inscribed.
std::vector<Vec3> disk_polygon(const Vec3& center, const Vec3& n, double r, bool outer) {
  Vec3 u, w;
  plane_frame(n, &u, &w);
  const double R = outer ? r / std::cos(std::numbers::pi / kDiskPolygonSides) * (1 + 1e-12) : r;
  std::vector<Vec3> out;
  for (int k = 0; k < kDiskPolygonSides; ++k) {
    const double a = 2 * std::numbers::pi * k / kDiskPolygonSides;
    out.push_back(center + R * (std::cos(a) * u + std::sin(a) * w));
  }
  return out;
}

Polyhedron face_weak_concave(const Face& face, double psi, double eps_s) {
  // Positions that may stick: all but those p with p − x inside cone(n, pi − psi) for every x in F (then
  // every admissible force points away from the face). That set is ∩_{vertices x} (x + C), C convex, taken
  // with an inner polyhedral C so the complement stays an over-approximation; eroded by eps_s (sensing).
  const FrictionCone inner = FrictionCone::face(face.normal, std::tan(std::numbers::pi - psi));
  Polyhedron keep_out;
  keep_out.kind = Polyhedron::Kind::kConvex;
  for (const Vec3& x : face.polygon) {
    const Polyhedron c = hull_plus_cone({x}, inner.extreme_rays(/*outer=*/false));
    keep_out.halfspaces.insert(keep_out.halfspaces.end(), c.halfspaces.begin(), c.halfspaces.end());
  }
  keep_out = keep_out.offset(-eps_s);
  keep_out.kind = Polyhedron::Kind::kComplement;
  return keep_out;
}

// x + (C ⊖ ball(eps_s)) for C = cone(a, alpha): the apex moved eps_s / sin(alpha) along a, and the cone
// taken from inside (kDiskPolygonSides generators on its rim; the chords lie inside the circle).
void add_eroded_cone(const Vec3& x, const CircularCone& cone, double eps_s, Polyhedron* out) {
  const Vec3 a = cone.axis.normalized();
  const Vec3 apex = x + a * (eps_s / std::sin(cone.half_angle));
  if (cone.half_angle >= kHalfPi) {  // a half-space: a . (p − apex) >= 0
    out->halfspaces.push_back({-a, -a.dot(apex)});
    return;
  }
  Vec3 e1, e2;
  plane_frame(a, &e1, &e2);
  auto rim = [&](int k) {
    const double t = 2 * std::numbers::pi * k / kDiskPolygonSides;
    return Vec3(std::cos(cone.half_angle) * a +
                std::sin(cone.half_angle) * (std::cos(t) * e1 + std::sin(t) * e2));
  };
  for (int k = 0; k < kDiskPolygonSides; ++k) {
    Vec3 m = rim(k).cross(rim(k + 1)).normalized();
    if (m.dot(a) > 0) m = -m;  // outward
    out->halfspaces.push_back({m, m.dot(apex)});
  }
}

// Strong region of an edge or vertex: commanded positions p such that, wherever on the atom the robot is (x
// ranges over the atom's end points; the sets are convex, so the whole segment follows) and whatever the
// sensing error (p* in ball(p, eps_s)) and velocity error (theta_v), the force direction p* − x keeps
// sticking the only Coulomb solution: a union over UniqueStick::must_cones alternatives of the intersection,
// over x and the alternative's cones C, of x + (C ⊖ ball(eps_s)). Buckley's summed cone of narrowed face
// cones is not used: inside it, sliding off onto a face can also be a Coulomb solution (a convex block
// corner with the pull along the diagonal into the block: tangential / normal = sqrt 2 > mu on the top face).
std::vector<Polyhedron> edge_vertex_strong(const CSpace& cspace, int atom_id, const std::vector<Vec3>& points,
                                           const Uncertainty& u) {
  std::vector<Polyhedron> out;
  for (const std::vector<CircularCone>& cones :
       UniqueStick::for_atom(cspace, atom_id).must_cones(u.theta_v)) {
    Polyhedron set;
    set.kind = Polyhedron::Kind::kConvex;
    for (const Vec3& x : points)
      for (const CircularCone& c : cones) add_eroded_cone(x, c, u.eps_s, &set);
    // Against rounding in the constructed normals: pull every plane in by a hair (kept sound).
    out.push_back(set.offset(-1e-12 * cspace.scale()));
  }
  return out;
}

}  // namespace

double eps_t(const Uncertainty& u) {
  if (u.theta_v == 0) return u.eps_p;
  const double t_t = u.theta_v / std::tan(u.theta_v);
  return u.eps_p + u.step * std::exp(-t_t) * std::sin(u.theta_v);
}

double eps_o(const Uncertainty& u) {
  if (u.theta_v == 0) return u.eps_p + u.step + 2 * u.eps_p;
  const double t_o = (u.theta_v + kHalfPi) / std::tan(u.theta_v);
  return u.eps_p + (u.step + 2 * u.eps_p) * (1 + std::exp(-t_o) * std::sin(u.theta_v));
}

Polyhedron spring_weak_region(const CSpace& cspace, int atom_id, const Uncertainty& u) {
  const FrictionCone cone = atom_friction_cone(cspace, atom_id);
  const FrictionCone wide = cone.widened(u.theta_v);
  if (cspace.atom_kind(atom_id) == AtomKind::kFace &&
      cone.generators()[0].half_angle + u.theta_v >= kHalfPi) {
    const double psi = cone.generators()[0].half_angle + u.theta_v;
    return psi >= std::numbers::pi ? Polyhedron::everything()
                                   : face_weak_concave(cspace.faces()[atom_id], psi, u.eps_s);
  }
  if (wide.is_full(/*outer=*/true)) return Polyhedron::everything();  // sound: a non-convex summed cone
  return hull_plus_cone(atom_points(cspace, atom_id), negated(wide.extreme_rays(/*outer=*/true)))
      .offset(u.eps_s);
}

SpringStickingRegions spring_sticking_regions(const CSpace& cspace, int atom_id, const Uncertainty& u) {
  SpringStickingRegions out;
  out.weak = spring_weak_region(cspace, atom_id, u);
  out.strong = spring_strong_regions(cspace, atom_id, u);
  return out;
}

std::vector<Polyhedron> spring_strong_regions(const CSpace& cspace, int atom_id, const Uncertainty& u) {
  std::vector<Polyhedron> out;
  const FrictionCone cone = atom_friction_cone(cspace, atom_id);
  const AtomKind kind = cspace.atom_kind(atom_id);
  const double margin = eps_t(u);
  if (kind == AtomKind::kFace) {
    const Face& f = cspace.faces()[atom_id];
    const double phi = cone.generators()[0].half_angle;
    if (phi > u.theta_v) {
      const double depth = u.eps_s + (margin + u.eps_s) / std::tan(phi - u.theta_v);
      Polyhedron strong;
      strong.kind = Polyhedron::Kind::kConvex;
      strong.halfspaces.push_back({f.normal, f.offset - depth});
      const std::size_t k = f.polygon.size();
      for (std::size_t i = 0; i < k; ++i) {
        const Vec3 edge = f.polygon[(i + 1) % k] - f.polygon[i];
        const Vec3 outward = edge.cross(f.normal).normalized();  // CCW about n: edge x n points out of F
        strong.halfspaces.push_back({outward, outward.dot(f.polygon[i]) - margin});
      }
      out.push_back(std::move(strong));
    }
  } else {
    out = edge_vertex_strong(cspace, atom_id, atom_points(cspace, atom_id), u);
  }
  return out;
}

bool SpringStickingRegions::strongly_contains(const Vec3& p) const {
  for (const Polyhedron& s : strong)
    if (s.contains(p)) return true;
  return false;
}

StickClass classify_spring(const SpringStickingRegions& regions, const Vec3& commanded) {
  if (regions.strongly_contains(commanded)) return StickClass::kMust;
  if (regions.weak.contains(commanded)) return StickClass::kMay;
  return StickClass::kNever;
}

FaceStickingRadii face_sticking_radii(const Face& face, const Vec3& p, const Uncertainty& u) {
  FaceStickingRadii out;
  const double phi = std::atan(face.friction);
  const double h = face.offset - face.normal.dot(p);  // depth of p below the face plane (negative: above)
  out.center = p + h * face.normal;
  // Weak: x with angle(p − x̂, −n) <= phi + theta_v for some |x̂ − x| <= eps_s, i.e. x within eps_s of the cone
  // p + cone(n, psi). On the plane that is a disk about p' whose radius solves dist(x, cone) = eps_s.
  const double psi = phi + u.theta_v;
  if (psi >= kHalfPi) {
    out.weak = std::numeric_limits<double>::infinity();  // concave case: the whole face may stick (sound)
  } else {
    auto dist_to_cone = [&](double rho) {  // x at radius rho from p' on the plane
      const double along = h, across = rho;
      const double angle = std::atan2(across, along);  // from the cone axis +n
      const double len = std::hypot(across, along);
      if (angle <= psi) return 0.0;
      if (angle >= psi + kHalfPi) return len;
      return len * std::sin(angle - psi);
    };
    if (dist_to_cone(0) <= u.eps_s) {
      double lo = 0, hi = 1;
      // eps_s and h are finite (models/task_ranges.h), so the doubling ends; a non-finite bound would not,
      // and then the whole face may stick (the sound answer).
      while (dist_to_cone(hi) <= u.eps_s && std::isfinite(hi)) hi *= 2;
      for (int i = 0; i < 100; ++i) {
        const double mid = 0.5 * (lo + hi);
        (dist_to_cone(mid) <= u.eps_s ? lo : hi) = mid;
      }
      out.weak = hi;  // the upper end of the bracket: outer
    }
  }
  // Strong: B(x, eps_s) inside p + cone(n, phi − theta_v), i.e. x in p + (eps_s / sin(phi − theta_v)) n +
  // that cone: a disk of radius (h − eps_s / sin(phi − theta_v)) tan(phi − theta_v).
  const double alpha = phi - u.theta_v;
  if (alpha > 0) out.strong = (h - u.eps_s / std::sin(alpha)) * std::tan(alpha);
  return out;
}

FaceStickingConfigurations face_sticking_configurations(const Face& face, const Vec3& p,
                                                        const Uncertainty& u) {
  FaceStickingConfigurations out;
  const FaceStickingRadii r = face_sticking_radii(face, p, u);
  if (std::isinf(r.weak))
    out.weak = face.polygon;
  else if (r.weak >= 0)
    out.weak =
        clip_convex_polygon(face.polygon, disk_polygon(r.center, face.normal, r.weak, true), face.normal);
  if (r.strong > 0)
    out.strong =
        clip_convex_polygon(face.polygon, disk_polygon(r.center, face.normal, r.strong, false), face.normal);
  return out;
}

}  // namespace cmt

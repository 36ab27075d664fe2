#include "verifier/damper.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "verifier/atom_cone.h"

namespace cmt {
namespace {

constexpr double kPi = std::numbers::pi;

double angle_between(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

}  // namespace

// Slack on the unique-stick margin: directions this close to the boundary are "may".
constexpr double kUniqueStickSlack = 1e-9;

StickClass classify_damper(const FrictionCone& cone, const UniqueStick& unique, const Vec3& v, double theta_v,
                           double stop_angle) {
  // v_a ∈ −FC  ⟺  −v_a ∈ FC: test the cone(−v, theta_v + stop_angle) against the friction cone for "never".
  const CircularCone velocities{-v.normalized(), std::min(theta_v + stop_angle, kPi / 2)};
  if (!cone.may_intersect_cone(velocities)) return StickClass::kNever;
  if (unique.margin(v) >= theta_v + kUniqueStickSlack) return StickClass::kMust;
  return StickClass::kMay;
}

StickClass classify_damper(const AtomCones& cones, int atom_id, const Vec3& v, double theta_v,
                           double stop_angle) {
  return classify_damper(cones[atom_id], cones.unique(atom_id), v, theta_v, stop_angle);
}

StickClass classify_damper(const CSpace& cspace, int atom_id, const Vec3& v, double theta_v) {
  return classify_damper(atom_friction_cone(cspace, atom_id), UniqueStick::for_atom(cspace, atom_id), v,
                         theta_v);
}

bool SlidingCone::contains(const Vec3& d, const Vec3& normal) const {
  if (!possible) return false;
  if (all) return true;
  const Vec3 t = d - d.dot(normal) * normal;
  if (t.norm() == 0) return false;
  return angle_between(t, axis) <= half_angle;
}

SlidingCone sliding_cone(const Vec3& normal, double mu, const Vec3& v_in, double theta_v) {
  SlidingCone out;
  const Vec3 n = normal.normalized();
  const Vec3 v = v_in.normalized();
  const double phi = std::atan(mu);
  const Vec3 pole = -n;
  const double beta = angle_between(v, pole);  // polar angle of v from −n
  const Vec3 vt = v - v.dot(n) * n;
  if (vt.norm() > 1e-15) out.axis = vt.normalized();
  // Meridian at azimuth offset a from v's azimuth: points at polar angle rho have
  // cos(angle to v) = cos(beta) cos(rho) + sin(beta) cos(a) sin(rho) = A cos(rho − psi).
  auto meridian_meets_region = [&](double a) {
    const double A = std::hypot(std::cos(beta), std::sin(beta) * std::cos(a));
    if (A < std::cos(theta_v)) return false;
    const double psi = std::atan2(std::sin(beta) * std::cos(a), std::cos(beta));
    const double w = std::acos(std::clamp(std::cos(theta_v) / A, -1.0, 1.0));
    const double lo = std::max(0.0, psi - w), hi = std::min(kPi, psi + w);
    if (lo > hi) return false;
    return hi > phi && lo < kPi / 2;  // reaches past the friction cone, starts before leaving the face
  };
  // Friction cone strictly inside the velocity cone: every direction slides (Alg 4.3, first case).
  if (beta + phi < theta_v) {
    out.possible = out.all = true;
    return out;
  }
  if (!meridian_meets_region(0)) {
    // No meridian in v's half-plane meets the region; by symmetry and monotonicity none does.
    // v exactly at the pole is symmetric in every azimuth: the test above at a = 0 decides it too.
    return out;
  }
  out.possible = true;
  if (vt.norm() <= 1e-15 || meridian_meets_region(kPi)) {
    out.all = true;
    return out;
  }
  double lo = 0, hi = kPi;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (meridian_meets_region(mid) ? lo : hi) = mid;
  }
  out.half_angle = std::min(kPi, hi + kSlidingConeSlack);
  if (out.half_angle >= kPi) out.all = true;
  return out;
}

EdgeSliding edge_sliding(const CSpace& cspace, int edge_atom_id, const Vec3& v, double theta_v) {
  EdgeSliding out;
  if (classify_damper(cspace, edge_atom_id, v, theta_v) == StickClass::kMust) return out;
  const Edge& e = cspace.edges()[cspace.atom_index(edge_atom_id)];
  // A velocity leaving one face leaves the edge: at a convex edge it points into free space (the union of the
  // faces' fronts), at a concave edge whose faces are at least square (n_f . n_g >= 0) it slides off along
  // the other face; in a sharper crease the reaction from one face can press the robot into the other.
  const bool leaves_with_a_face =
      e.faces.size() == 2 &&
      (e.shape == EdgeShape::kConvex ||
       (e.shape == EdgeShape::kConcave &&
        cspace.faces()[e.faces[0]].normal.dot(cspace.faces()[e.faces[1]].normal) >= 0));
  if (leaves_with_a_face)
    for (int f : e.faces)
      if (v.normalized().dot(cspace.faces()[f].normal) > std::sin(theta_v + kSlidingConeSlack)) return out;
  const Vec3 dir = (e.b - e.a).normalized();
  // Some v_a within theta_v of v has a positive component along dir iff angle(v, dir) < pi/2 + theta_v.
  const double to_b = angle_between(v, dir);
  out.toward_b = to_b < kPi / 2 + theta_v;
  out.toward_a = kPi - to_b < kPi / 2 + theta_v;
  return out;
}

}  // namespace cmt

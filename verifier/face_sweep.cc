// Step A's in-plane sweep (verifier/internal/face_sweep.h).
#include "verifier/internal/face_sweep.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "verifier/damper.h"
#include "verifier/internal/damper_flight.h"

namespace cmt::face_geometry {
namespace {
constexpr double kPi = std::numbers::pi;
}  // namespace

Sweep face_sweep(const Face& f, const Vec3& v, double theta_v, double scale) {
  Sweep out;
  const SlidingCone s = sliding_cone(f.normal, f.friction, v, theta_v);
  const Vec3 vt = v - v.dot(f.normal) * f.normal;
  const double vt_norm = vt.norm();
  double alpha = -1;
  Vec3 axis = s.axis;
  if (s.possible) {
    if (s.all) alpha = kPi;
    alpha = std::max(alpha, s.half_angle);
  }
  if (vt_norm >= std::cos(theta_v + kFlightAngleSlack) && vt_norm > 0) {
    alpha = std::max(alpha, std::acos(std::min(1.0, std::cos(theta_v + kFlightAngleSlack) / vt_norm)));
    axis = vt / vt_norm;
  }
  if (alpha < 0) return out;
  out.none = false;
  alpha += kFlightAngleSlack;
  // Half-angle >= pi/2: the directions positively span the plane and the velocity may switch: whole face.
  if (alpha >= kPi / 2 || std::cos(alpha) < 1e-9 || axis.norm() == 0) {
    out.whole = true;
    return out;
  }
  const Vec3 side = f.normal.cross(axis);
  out.b_plus = std::cos(alpha) * axis + std::sin(alpha) * side;
  out.b_minus = std::cos(alpha) * axis - std::sin(alpha) * side;
  // Any in-face displacement (length <= scale) in W is a combination of b_plus, b_minus with coefficients
  // summing to <= scale / cos(alpha).
  out.far = 2 * scale / std::cos(alpha);
  return out;
}

}  // namespace cmt::face_geometry

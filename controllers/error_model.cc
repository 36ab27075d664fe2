#include "controllers/error_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cmt {

const char* sample_mode_name(SampleMode mode) { return mode == SampleMode::kUniform ? "uniform" : "extreme"; }

std::optional<SampleMode> parse_sample_mode(const std::string& text) {
  if (text == "uniform") return SampleMode::kUniform;
  if (text == "extreme") return SampleMode::kExtreme;
  return std::nullopt;
}

Vec3 DirectionError::apply(const Vec3& v) const {
  const double length = v.norm();
  if (angle == 0 || length == 0) return v;
  const Vec3 u = v / length;
  Vec3 n = axis - axis.dot(u) * u;
  if (n.squaredNorm() < 1e-24) {
    // The reference axis is parallel to v: any perpendicular will do; take the one from the coordinate axis
    // least aligned with v, so the choice is deterministic.
    Eigen::Index k;
    u.cwiseAbs().minCoeff(&k);
    n = u.cross(Vec3::Unit(k));
  }
  n.normalize();
  return length * (std::cos(angle) * u + std::sin(angle) * n.cross(u));
}

ErrorSampler::ErrorSampler(const Uncertainty& bounds, SampleMode mode, bool planar)
    : bounds_(bounds), mode_(mode), planar_(planar) {}

DirectionError ErrorSampler::direction(Rng& rng, double bound) const {
  DirectionError e;
  // Draw order is fixed (axis, then boundary choice, then angle) so that streams are reproducible.
  e.axis = planar_ ? Vec3::UnitY() : uniform_on_sphere(rng);
  const bool boundary = mode_ == SampleMode::kExtreme && uniform01(rng) < kExtremeBoundaryFraction;
  if (planar_) {
    // In the plane the deviation is a signed angle about y: uniform in [-bound, bound], or +-bound.
    const double sign = uniform01(rng) < 0.5 ? -1.0 : 1.0;
    e.angle = boundary ? sign * bound : uniform(rng, -bound, bound);
  } else if (boundary) {
    e.angle = bound;
  } else {
    // Uniform over the cone's solid angle: cos(angle) uniform in [cos(bound), 1]. The axis being uniform on
    // the sphere makes the azimuth about the command uniform.
    e.angle = std::acos(uniform(rng, std::cos(bound), 1.0));
  }
  e.angle = std::clamp(e.angle, -bound, bound);  // acos rounding must not leave the bound
  return e;
}

Vec3 ErrorSampler::offset(Rng& rng, double radius) const {
  const bool boundary = mode_ == SampleMode::kExtreme && uniform01(rng) < kExtremeBoundaryFraction;
  Vec3 v = boundary ? Vec3(radius * uniform_on_sphere(rng, planar_)) : uniform_in_ball(rng, radius, planar_);
  // Rounding of radius x unit vector can exceed the radius by an ulp (and so can the rescaled vector):
  // shrink until the bound holds exactly.
  const double n = v.norm();
  if (n > radius) v *= radius / n;
  while (v.norm() > radius) v *= std::nextafter(1.0, 0.0);
  return v;
}

MotionErrors::MotionErrors(const ErrorSampler& sampler, Rng& rng, double switch_interval)
    : sampler_(&sampler), switch_interval_(switch_interval) {
  velocity_ = sampler.velocity_error(rng);
  force_ = sampler.force_error(rng);
  sensing_offset_ = sampler.sensing_offset(rng);
  switching_ = switch_interval > 0 && uniform01(rng) < 0.5;
  next_switch_ =
      switching_ ? -switch_interval * std::log(1 - uniform01(rng)) : std::numeric_limits<double>::infinity();
}

void MotionErrors::advance(double t, Rng& rng) {
  while (t >= next_switch_) {
    velocity_ = sampler_->velocity_error(rng);
    next_switch_ += -switch_interval_ * std::log(1 - uniform01(rng));
    ++switches_;
  }
}

}  // namespace cmt

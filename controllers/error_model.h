// Bounded errors of Buckley's models (§2.1, L640-652), sampled so that no bound is ever exceeded:
//   theta_v: the actual velocity direction (the force the robot imparts in contact, §3.3.3) is within
//            theta_v of the commanded one, and may switch during a motion (§3.2.1);
//   eps_s:   the sensed position is within eps_s of the true one;
//   theta_f: the sensed reaction-force direction is within theta_f of the true one;
//   eps_p:   a commanded position is reached within eps_p (position-controller form, via points).
// Two modes: uniform (directions uniform over the error cone, offsets uniform in the ball) and extreme (most
// draws on the boundary: the cone rim, the sphere), because termination regions are shaped by the extreme
// trajectories (Buckley App. B, Fig 3.12). Planar tasks keep every error in the x-z plane.
#pragma once

#include <optional>
#include <string>

#include "controllers/random.h"
#include "models/task.h"

namespace cmt {

enum class SampleMode { kUniform, kExtreme };
const char* sample_mode_name(SampleMode mode);
std::optional<SampleMode> parse_sample_mode(const std::string& text);

// Extreme mode: this fraction of draws lies exactly on the boundary of its bound; the rest is drawn as in
// uniform mode so that the interior is still visited.
inline constexpr double kExtremeBoundaryFraction = 0.9;

// A direction error of exactly `angle` radians. apply(v) turns v by `angle` about the unit vector n
// perpendicular to v that is closest to `axis` (a fixed reference axis), keeping |v|: a command direction
// that changes during a motion (the spring's x_c - x) is turned consistently, which is how Buckley's extreme
// spiral trajectories arise (App. B: the velocity always deviates by theta_v to the same side).
struct DirectionError {
  Vec3 axis = Vec3::UnitY();
  double angle = 0;
  Vec3 apply(const Vec3& v) const;
};

class ErrorSampler {
 public:
  ErrorSampler(const Uncertainty& bounds, SampleMode mode, bool planar);

  DirectionError velocity_error(Rng& rng) const { return direction(rng, bounds_.theta_v); }
  DirectionError force_error(Rng& rng) const { return direction(rng, bounds_.theta_f); }
  Vec3 sensing_offset(Rng& rng) const { return offset(rng, bounds_.eps_s); }
  Vec3 positioning_error(Rng& rng) const { return offset(rng, bounds_.eps_p); }

  const Uncertainty& bounds() const { return bounds_; }
  SampleMode mode() const { return mode_; }
  bool planar() const { return planar_; }

 private:
  DirectionError direction(Rng& rng, double bound) const;
  Vec3 offset(Rng& rng, double radius) const;
  Uncertainty bounds_;
  SampleMode mode_;
  bool planar_;
};

// The errors in force during one motion. The sensing offset and the force-direction error are drawn once
// per motion (a calibration-like bias: with a constant offset the sensed velocity is the true velocity). The
// velocity error may switch (§3.2.1): with probability 1/2 it is constant for the whole motion (the extreme
// spiral of App. B needs a constant error), otherwise it is redrawn at the times of a Poisson process with
// mean interval `switch_interval` seconds.
class MotionErrors {
 public:
  MotionErrors(const ErrorSampler& sampler, Rng& rng, double switch_interval);
  // Redraws the velocity error if a switch time has passed; call once per control step with the sim time
  // since the motion started.
  void advance(double t, Rng& rng);

  const DirectionError& velocity() const { return velocity_; }
  const DirectionError& force() const { return force_; }
  const Vec3& sensing_offset() const { return sensing_offset_; }
  int switches() const { return switches_; }

 private:
  const ErrorSampler* sampler_;
  double switch_interval_;
  bool switching_ = false;
  double next_switch_ = 0;
  int switches_ = 0;
  DirectionError velocity_, force_;
  Vec3 sensing_offset_ = Vec3::Zero();
};

}  // namespace cmt

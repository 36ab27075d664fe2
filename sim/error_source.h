// Where a rollout's bounded errors come from (Buckley §2.1; controllers/error_model.h). A rollout asks its
// ErrorSource, in a fixed order, for its start point, then per motion for the motion's errors (velocity
// direction error, which may switch over time; force-direction error; sensing offset; via-point errors), then
// for the sensor reading of a conditional test. Two sources:
//   SampledErrors: random draws from one seeded stream (the Monte Carlo rollouts; docs/rollouts.md);
//   ScriptedErrors (sim/error_vector.h): a fixed vector of numbers in [0, 1] decoded into errors within the
//   task's bounds, so that a search can choose them and a vector replays its rollout exactly
//   (docs/falsify.md).
#pragma once

#include <optional>

#include "controllers/error_model.h"
#include "controllers/random.h"
#include "models/task.h"

namespace cmt {

// The errors of one reading of the sensors at rest, for a conditional test (Buckley §4.2).
struct ReadingErrors {
  Vec3 sensing_offset = Vec3::Zero();  // within eps_s
  DirectionError force;                // within theta_f
};

class ErrorSource {
 public:
  virtual ~ErrorSource() = default;
  // The true start point, in the start region.
  virtual Vec3 start(const Region& start_region) = 0;
  // A motion of strategy node `node` begins: its errors are fixed or drawn now.
  virtual void begin_motion(int node) = 0;
  // Call once per control step with the sim time since the motion began: the velocity error may switch.
  virtual void advance(double t) = 0;
  virtual const DirectionError& velocity() const = 0;
  virtual const DirectionError& force() const = 0;
  virtual const Vec3& sensing_offset() const = 0;
  virtual int switches() const = 0;
  // The error with which the position servo reaches the next via point (position form; within eps_p).
  virtual Vec3 positioning_error() = 0;
  // The errors of the sensor reading after the motion of `node` (its conditional test).
  virtual ReadingErrors reading(int node) = 0;
};

// Samples a start point in a region: uniform over it; in extreme mode mostly its vertices and boundary
// (kExtremeBoundaryFraction: half of those at a vertex, half uniform on the boundary edges).
Vec3 sample_region(const Region& region, SampleMode mode, Rng& rng);

// The Monte Carlo source: every number from one stream, in the order a rollout asks (start point; per motion
// the MotionErrors draws, then switch and via-point draws as time passes; a reading's sensing offset, then
// its force error).
class SampledErrors final : public ErrorSource {
 public:
  SampledErrors(const ErrorSampler& sampler, Rng& rng, double switch_interval)
      : sampler_(&sampler), rng_(&rng), switch_interval_(switch_interval) {}

  Vec3 start(const Region& start_region) override {
    return sample_region(start_region, sampler_->mode(), *rng_);
  }
  void begin_motion(int /*node*/) override { motion_.emplace(*sampler_, *rng_, switch_interval_); }
  void advance(double t) override { motion_->advance(t, *rng_); }
  const DirectionError& velocity() const override { return motion_->velocity(); }
  const DirectionError& force() const override { return motion_->force(); }
  const Vec3& sensing_offset() const override { return motion_->sensing_offset(); }
  int switches() const override { return motion_->switches(); }
  Vec3 positioning_error() override { return sampler_->positioning_error(*rng_); }
  ReadingErrors reading(int /*node*/) override {
    ReadingErrors r;
    r.sensing_offset = sampler_->sensing_offset(*rng_);
    r.force = sampler_->force_error(*rng_);
    return r;
  }

 private:
  const ErrorSampler* sampler_;
  Rng* rng_;
  double switch_interval_;
  std::optional<MotionErrors> motion_;
};

}  // namespace cmt

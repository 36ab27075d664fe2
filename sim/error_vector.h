// A rollout's errors as a finite vector of numbers in [0, 1] (docs/falsify.md "Error vectors"), so that a
// search can choose them (experiments/falsify/) and any vector replays one deterministic rollout. Every
// decoded error lies within the task's bounds, whatever the vector (tests/sim/error_vector_test.cc):
//   start point        2 numbers: a segment's parameter, or a convex polygon's point as an angle about its
//                      centroid and a fraction of the way to the boundary (0 numbers for a point start);
//   per strategy node  the motion's errors: force error (3: axis polar, axis azimuth, angle / theta_f),
//                      sensing offset (3: a point of the cube [-1, 1]^3 pulled onto the unit ball, times
//                      eps_s), K + 1 velocity errors (3 each, as the force error with theta_v) with K switch
//                      times (1 each: u -> horizon u / (1 - u) seconds, so u = 1/2 is the horizon and u = 1
//                      never switches, which makes Buckley's constant extreme error a face of the box; the
//                      times are sorted), and P via-point errors (3 each, as the sensing offset with eps_p;
//                      used in turn, cyclically);
//   per node with a conditional test: the reading's sensing offset (3) and force error (3).
// Planar tasks keep every error in the x-z plane: a direction error turns about y by a signed angle
// (angle number 0 -> -bound, 1 -> +bound; the axis numbers are unused) and offsets drop their y number.
#pragma once

#include <string>
#include <vector>

#include "models/task.h"
#include "sim/error_source.h"

namespace cmt {

struct ErrorVectorShape {
  int switches = 3;    // K: velocity-error switch times per motion (Buckley §3.2.1)
  int via_points = 0;  // P: via-point errors per motion (position form only)
  // The median switch time of a uniform number (seconds after a motion begins).
  double horizon = 5;
};

// The shape searches use: K = 3 switches, P = 2 via-point errors in the position form (none otherwise: the
// other forms have no via points), and a horizon of one scene length at the damper's commanded speed
// (1 / damper_speed_per_scale seconds, 5 s by default: the time scale of a motion across the scene).
ErrorVectorShape default_error_shape(bool position_form, double damper_speed_per_scale);

// Where each group of numbers sits in the vector, for one task and strategy.
class ErrorVectorLayout {
 public:
  ErrorVectorLayout(const Task& task, const Strategy& strategy, const ErrorVectorShape& shape);

  int size() const { return size_; }
  int nodes() const { return static_cast<int>(motion_offsets_.size()); }
  const ErrorVectorShape& shape() const { return shape_; }
  int start_offset() const { return 0; }
  int start_size() const { return start_size_; }
  // Offset of node n's motion block, and of its reading block (-1 when n has no conditional test).
  int motion_offset(int node) const { return motion_offsets_.at(static_cast<std::size_t>(node)); }
  int motion_size() const { return motion_size_; }
  int reading_offset(int node) const { return reading_offsets_.at(static_cast<std::size_t>(node)); }
  // Offsets within a motion block.
  static constexpr int kForce = 0, kSensing = 3, kVelocity = 6;
  int switch_times_offset() const { return kVelocity + 3 * (shape_.switches + 1); }
  int via_offset() const { return switch_times_offset() + shape_.switches; }

 private:
  ErrorVectorShape shape_;
  int start_size_ = 0, motion_size_ = 0, size_ = 0;
  std::vector<int> motion_offsets_, reading_offsets_;
};

// The shape of a vector of `size` entries for this task and strategy: default_error_shape's via points and
// horizon, and the K that gives that size (a vector replays from itself and the controller form alone).
// Throws std::invalid_argument when no K >= 0 does.
ErrorVectorShape shape_of_vector(const Task& task, const Strategy& strategy, int size, bool position_form,
                                 double damper_speed_per_scale);

// Decoding single groups (exposed for tests): a direction error within `bound` from 3 numbers, an offset
// within `radius` from 3 numbers (y ignored when planar), a point of the start region from start_size
// numbers.
DirectionError decode_direction(const double* u, double bound, bool planar);
Vec3 decode_offset(const double* u, double radius, bool planar);
Vec3 decode_start(const Region& region, const double* u);

// The error source of one vector. Throws std::invalid_argument when the vector's length is not the layout's
// size or a number is outside [0, 1] or not finite.
class ScriptedErrors final : public ErrorSource {
 public:
  ScriptedErrors(const Task& task, const ErrorVectorLayout& layout, std::vector<double> vector);

  Vec3 start(const Region& start_region) override;
  void begin_motion(int node) override;
  void advance(double t) override;
  const DirectionError& velocity() const override { return velocity_[static_cast<std::size_t>(segment_)]; }
  const DirectionError& force() const override { return force_; }
  const Vec3& sensing_offset() const override { return sensing_offset_; }
  int switches() const override { return segment_; }
  Vec3 positioning_error() override;
  ReadingErrors reading(int node) override;

 private:
  const double* at(int offset) const { return vector_.data() + offset; }
  const Task* task_;
  const ErrorVectorLayout* layout_;
  std::vector<double> vector_;
  bool planar_;
  int block_ = 0;    // the current motion block's offset
  int segment_ = 0;  // the velocity error in force: 0 .. K (switches so far)
  int via_ = 0;      // via points used so far in this motion
  std::vector<double> switch_times_;
  std::vector<DirectionError> velocity_;
  DirectionError force_;
  Vec3 sensing_offset_ = Vec3::Zero();
};

// A vector as text (comma-separated, 17 significant digits: it parses back to the same doubles) and back.
// parse_error_vector throws std::invalid_argument naming the bad entry.
std::string format_error_vector(const std::vector<double>& vector);
std::vector<double> parse_error_vector(const std::string& text);

}  // namespace cmt

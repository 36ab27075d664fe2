// Termination monitors (Buckley §3.1.2 L726-752, §6 motion types L1662). Every rule works on sensed values
// only (sensed position, velocity and force), as on a real robot:
//   type 1, sticking: the robot has stopped. Rule: over a window of kStopWindow seconds, the sensed
//           displacement divided by the window stays below kStopRelativeSpeed x the motion's reference
//           (initial commanded) speed. (The position form also stops on the AML force rule, controller.h.)
//   type 2: in contact (a sensed force above the controller's guard force within the last kContactHold
//           seconds, since a sliding body is in contact on only part of the steps, docs/mujoco-scene.md)
//           and the sensed position in a set P_s;
//   type 3: the sensed force direction in a set F_s (and the sensed position in P_s when given);
//   time-out: none of the above within the motion's time limit: "none", recorded as a failure.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "controllers/controller.h"
#include "models/friction_cone.h"
#include "models/task.h"

namespace cmt {

enum class Termination { kSticking, kPosition, kForce, kNone, kUnstable };
// "sticking", "position", "force", "none" (time-out: no termination), "unstable" (the simulation broke).
const char* termination_name(Termination t);

// Sticking rule (type 1). The window is 5 servo time constants (50 ms with the default scene), long enough
// that the contact hops of a sliding body (a few steps, ~1e-6 m) average out and that a robot starting from
// rest has reached its commanded speed; 1% of the reference speed means that a spring stopping this way is
// within 1% of its initial distance of where it would stick (its sliding speed decays as e^(-lambda t)), and
// that a damper sliding slower than 1% of its commanded speed (a command within ~0.6 degrees of the friction
// cone) counts as stuck.
inline constexpr double kStopWindow = 0.05;
inline constexpr double kStopRelativeSpeed = 0.01;
inline constexpr double kContactHold = 0.02;

// A union of convex polytopes {x : n_i . x <= d_i}; axis boxes are added as 6 half-spaces.
class PositionSet {
 public:
  void add_box(const AxisBox& box);
  void add_polytope(std::vector<Vec3> normals, std::vector<double> offsets);
  bool contains(const Vec3& p) const;
  bool empty() const { return polytopes_.empty(); }

 private:
  struct Polytope {
    std::vector<Vec3> normals;
    std::vector<double> offsets;
  };
  std::vector<Polytope> polytopes_;
};

// A union of circular cones of force directions.
class ForceDirectionSet {
 public:
  void add_cone(const Vec3& axis, double half_angle);
  bool contains(const Vec3& force) const;  // false for a zero force
  bool empty() const { return cones_.empty(); }

 private:
  std::vector<CircularCone> cones_;
};

// Termination parameters of one motion. Sticking (type 1) is always on; P_s and F_s are optional.
struct TerminationSpec {
  std::optional<PositionSet> sensed_position;     // type 2 (with contact), or the position part of type 3
  std::optional<ForceDirectionSet> sensed_force;  // type 3
};

// The monitor's sets for a task motion's termination parameters (models/task.h MotionTermination): boxes
// become P_s, cones F_s; a list that is not given stays unset.
TerminationSpec termination_spec(const MotionTermination& terminate);

class TerminationMonitor {
 public:
  TerminationMonitor(TerminationSpec spec, double reference_speed, double guard_force, double control_step);
  // Called once per control step with the sensed state; returns the termination once a rule fires.
  // `stop_rule` off suspends the sticking rule (the position form while via points are still being issued:
  // AML SMOVE ends a plan only by its force rule or by completing it).
  std::optional<Termination> update(const Sensed& sensed, bool stop_rule = true);
  bool in_contact() const { return in_contact_; }

 private:
  TerminationSpec spec_;
  double stop_speed_, guard_force_, dt_;
  std::size_t window_steps_;
  std::vector<Vec3> window_;  // ring buffer: sensed positions over the last kStopWindow seconds
  std::size_t count_ = 0;
  double last_contact_time_ = -1e300;
  bool in_contact_ = false;
};

}  // namespace cmt

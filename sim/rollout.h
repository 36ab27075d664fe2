// Monte Carlo rollouts of compliant motion strategies in MuJoCo (docs/rollouts.md). A RolloutScene is the
// immutable part (loaded task, compiled mjModel, controller constants, tolerances) shared by all threads; a
// RolloutRunner owns one mjData and runs rollouts one after another; run_rollouts spreads N rollouts over T
// threads. Rollout i draws every random number from rollout_stream(seed, i) and starts from a reset mjData,
// so its outcome is the same bit for bit whatever the thread count.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "controllers/controller.h"
#include "controllers/error_model.h"
#include "controllers/termination.h"
#include "models/loaded_task.h"
#include "sim/error_source.h"
#include "sim/mjcf_export.h"

namespace cmt {

class MujocoModel;  // sim/mujoco_guard.h (MuJoCo stays out of this header)
class MujocoData;

// A rollout's end point is attributed to the lowest-dimensional atom within this fraction of the scene scale
// (CSpace::nearest_atom), else to free space. A robot at rest sits <= ~1e-6 m inside a face (within the
// rollouts' 1 um soft layer: <= 1.04e-6 m under the calibration's loads) and one sliding at 1 cm/s hops by up
// to ~1.5e-6 m (docs/mujoco-scene.md); 1e-4 of the scene (hole: 1.8e-3 in = 4.6e-5 m) is 30x that, and
// small against every feature of the built-in tasks. The same tolerance decides success (distance to a goal
// region).
inline constexpr double kAtomRelativeTolerance = 1e-4;
// A rollout is unstable when the penetration into the C-obstacles exceeds this fraction of the scene scale
// (hole: 0.018 in = 4.6e-4 m, ~20x the deepest impact measured in the hole rollouts), when a state becomes
// NaN or infinite, when MuJoCo raises a warning or an error, or when the robot leaves the bounds by more
// than that.
inline constexpr double kUnstablePenetrationRelative = 1e-3;

// The rollouts' MuJoCo scene, the Coulomb-calibrated one (`cmt calibrate-friction` passes in it,
// docs/rollouts.md "Calibration"): the soft-surface-layer scene (sim/mjcf_export.h soft_layer_scene(): a
// 0.25 ms step and a 1 um soft layer over the stiff contact, so that both contacts of a robot sliding along a
// concave edge stay active and the edge follows Coulomb) with the seam contact filter (sim/seam_filter.h) at
// tau = the unstable penetration (below): every contact of a stable rollout is shallower than that, and every
// feature of the built-in tasks is far wider. Robot mass 1 kg and servo gain b_s = 100 N s/m (joint damping)
// as exported.
inline MjcfOptions calibrated_scene() {
  MjcfOptions o = soft_layer_scene();
  o.seam_filter_relative = kUnstablePenetrationRelative;
  return o;
}

// The stiff scene, for comparisons with the rollouts' scene (`cmt calibrate-friction --scene stiff`,
// `cmt check-sticking --scene stiff`): the exporter's stiff contact (d = 0.99 at every depth) at a 0.5 ms
// step, with the seam filter. It meets every calibration criterion on a face (sliding within 1.4 % of
// Coulomb, penetration at 1 in/s <= 6.3e-6 m) but not in a concave edge: sliding there runs up to 73 % off
// Coulomb (each face's contact hops off and the other face's friction wedges the robot into the edge,
// docs/rollouts.md "Concave edges").
inline MjcfOptions stiff_scene() {
  MjcfOptions o;
  o.timestep = 0.0005;
  o.seam_filter_relative = kUnstablePenetrationRelative;
  return o;
}

struct SimOptions {
  ControllerForm form = ControllerForm::kAdmittance;
  SampleMode mode = SampleMode::kUniform;
  // The MuJoCo scene: calibrated_scene() (above). It takes 2x the steps of stiff_scene() (0.25 vs 0.5 ms)
  // and more solver work per step: 2.1-3.1x the CPU time per rollout of the stiff scene (docs/rollouts.md
  // "Concave edges: the soft-surface-layer scene").
  MjcfOptions scene = calibrated_scene();
  // Spring rate lambda (1/s): time constant 0.25 s = 25 servo time constants, so the robot is first order on
  // the motion's time scale (Buckley §3.1), and the lag that remains is compensated (controller.h).
  double spring_rate = 4;
  // Damper speed as a fraction of the scene scale per second (Buckley's unit commanded velocity, scaled so a
  // motion across the scene takes ~5 s).
  double damper_speed_per_scale = 0.2;
  // Top speed of the velocity servo for springs, the same fraction of the scene scale per second (hole:
  // 3.6 in/s = 0.09 m/s): keeps impacts slow enough that contact penetration stays ~1e-5 of the scene.
  double max_speed_per_scale = 0.2;
  // Position form: servo gain g (1/s; 5 servo time constants) and time per via point (3 / g: the servo has
  // settled to 5%).
  double position_gain = 20;
  double via_time_constants = 3;
  // Mean time between switches of the velocity error (§3.2.1), s.
  double switch_interval = 0.1;
  // Time limits per motion. Spring: the flight at top speed, |x_c - x0| / v_max, plus N time constants of
  // its slowest sliding. Sliding decays at rate lambda c, where c = v_max / (lambda |x_c - x|) <= 1 is the
  // factor by which the top speed scales the drive down (a target deep below a surface presses hard and
  // slides slowly), so the time constant is max(1 / lambda, (|x_c - x0| + scale) / v_max). N = 10: the
  // sticking rule fires after ln(1 / kStopRelativeSpeed) = 4.6 of them, so a spring that is still moving
  // after 10 never stops. Damper: 3 scene lengths at kStopRelativeSpeed x the commanded speed, the slowest
  // speed the sticking rule does not count as stopped (a damper slides at any speed down to that near the
  // friction cone's rim, and still reaches the end of its face in Buckley's model). Position form: 3x its
  // via-point plan plus N / g.
  double spring_timeout_time_constants = 10;
  double damper_timeout_scales = 3;
  // Optional termination sets per motion name (types 2 and 3); sticking and the time-out always apply.
  std::map<std::string, TerminationSpec> terminations;
  // Trajectory recording for figures: every `trajectory_stride` steps.
  bool record_trajectory = false;
  int trajectory_stride = 10;
};

struct TrajectoryPoint {
  double time = 0;  // s since the rollout started
  int motion = 0;
  Vec3 position = Vec3::Zero();  // true C-space point, task units
  Vec3 sensed = Vec3::Zero();
  bool contact = false;  // MuJoCo reports a contact this step
};

struct MotionOutcome {
  std::string motion;
  int node = -1;    // the strategy node it ran (models/task.h StrategyNode; = its index in a sequence)
  int branch = -1;  // the branch its conditional test chose, -1 when it has no test or no test passed
  Vec3 end = Vec3::Zero();  // true C-space point at termination, task units
  int atom = -1;            // nearest atom within the atom tolerance, -1 = free space
  Termination termination = Termination::kNone;
  Vec3 contact_force = Vec3::Zero();  // total contact force on the robot at termination, N (world frame)
  double sim_time = 0;                // s
  long steps = 0;
  double max_penetration = 0;  // deepest penetration during the motion, task units
  int velocity_switches = 0;
  int replans = 0;  // position form
};

struct RolloutOutcome {
  int index = 0;
  Vec3 start = Vec3::Zero();
  Vec3 end = Vec3::Zero();
  int atom = -1;
  Termination termination = Termination::kNone;  // of the last motion run
  bool success =
      false;  // every motion terminated, every conditional test chose a branch, the end is in the goal
  bool no_branch = false;  // a conditional test (Buckley §4.2) passed no branch and there was no `else`
  bool unstable = false;
  std::string unstable_reason;
  std::vector<MotionOutcome> motions;
  std::vector<TrajectoryPoint> trajectory;
};

// The state after one simulation step, for observers (calibration, tests).
struct StepState {
  double time = 0;
  Vec3 position = Vec3::Zero();  // task units
  Vec3 velocity = Vec3::Zero();  // task units / s
  Vec3 force = Vec3::Zero();     // total contact force on the robot, N
  int contacts = 0;
  double penetration = 0;  // task units
};

class RolloutScene {
 public:
  // Exports the task's MJCF scene with options.scene and compiles it.
  static std::shared_ptr<const RolloutScene> build(std::shared_ptr<const LoadedTask> task,
                                                   const SimOptions& options = {});
  // With an already compiled model of that scene (e.g. one whose options a test changed).
  static std::shared_ptr<const RolloutScene> build(std::shared_ptr<const LoadedTask> task,
                                                   std::shared_ptr<const MujocoModel> model,
                                                   const SimOptions& options);

  const LoadedTask& task() const { return *task_; }
  const std::shared_ptr<const MujocoModel>& model() const { return model_; }
  const SceneInfo& info() const { return info_; }
  const SimOptions& options() const { return options_; }
  const ControllerParams& controller_params() const { return params_; }
  double meters_per_unit() const { return info_.meters_per_unit; }
  double timestep() const;
  double atom_tolerance() const { return kAtomRelativeTolerance * task_->cspace.scale(); }
  double unstable_penetration() const { return kUnstablePenetrationRelative * task_->cspace.scale(); }
  // Time limit of a motion from `from` (task units), s.
  double timeout(const Motion& motion, const Vec3& from) const;
  // Distance from p to the nearest goal region (task units); success is distance <= atom_tolerance().
  double goal_distance(const Vec3& p) const;

 private:
  friend class RolloutRunner;
  RolloutScene() = default;
  void init();
  std::shared_ptr<const LoadedTask> task_;
  std::shared_ptr<const MujocoModel> model_;
  SceneInfo info_;
  SimOptions options_;
  ControllerParams params_;
  int qpos_[3] = {0, 1, 2}, dof_[3] = {0, 1, 2};
  std::vector<char> geom_is_box_;  // per geom: box (box-box contacts report half the overlap)
  double servo_damping_si_ = 0;    // N s / m
};

double distance_to_region(const Vec3& p, const Region& region);

class RolloutRunner {
 public:
  explicit RolloutRunner(std::shared_ptr<const RolloutScene> scene);
  ~RolloutRunner();
  RolloutRunner(const RolloutRunner&) = delete;
  RolloutRunner& operator=(const RolloutRunner&) = delete;

  // Rollout `index` of `strategy` under `seed`. Never throws for simulation failures: an unstable rollout is
  // returned with unstable = true. Conditional strategies: after a motion with a test, the sensors are read
  // once (a fresh sensing offset within eps_s, a fresh force-direction error within theta_f, both from the
  // rollout's stream) and the first branch whose test passes runs (choose_branch); decision-free strategies
  // draw nothing extra.
  RolloutOutcome run(const Strategy& strategy, std::uint64_t seed, int index);
  // The same rollout with its errors from `errors` (SampledErrors over rollout_stream(seed, index) is what
  // the call above uses; ScriptedErrors replays an error vector). `index` only labels the outcome.
  RolloutOutcome run(const Strategy& strategy, ErrorSource& errors, int index);

  // Calibration and tests: puts the robot at rest at `position` (task units) and runs `motion` without
  // errors for `duration` seconds (no termination rules), calling `observer` after every step.
  void drive(const Vec3& position, const Motion& motion, double duration,
             const std::function<void(const StepState&)>& observer);

  long total_steps() const { return total_steps_; }
  // Benchmarks and tests: the generalized force applied at every step (qfrc_applied, N) is appended to
  // `sink`; nullptr turns recording off. Replaying these forces through mj_step reproduces the trajectory.
  void record_applied_forces(std::vector<Vec3>* sink);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  long total_steps_ = 0;
};

// Buckley §4.2: the first branch of `node` whose test passes the sensed position and sensed force (an
// `else` passes always), -1 when none does.
int choose_branch(const StrategyNode& node, const Vec3& sensed_position, const Vec3& sensed_force);

// Runs rollouts 0 .. n-1 over `threads` threads (one RolloutRunner, i.e. one mjData, per thread); results are
// in index order. `progress`, if set, is called from the calling thread with the number done so far.
std::vector<RolloutOutcome> run_rollouts(std::shared_ptr<const RolloutScene> scene, const Strategy& strategy,
                                         int n, std::uint64_t seed, int threads,
                                         const std::function<void(int)>& progress = {});

}  // namespace cmt

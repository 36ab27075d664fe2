// Verification of a strategy (Buckley §4.2): chain the motions' simulations (the termination set of one
// motion is the start of the next) and check that every final termination set lies in the goal. At a
// conditional test after a motion with termination set R (Fig 4.2), branch i is simulated from the points of
// R where some sensor reading may pass test i and no earlier test surely passes (Def 4.1/4.2 under eps_s and
// theta_f; Buckley's R ∩ I_i); without an `else` branch every point of R must surely pass some test
// (Buckley's R ⊆ I_1 ∪ I_2). A branch whose list is empty ends the strategy, so its start set must lie in the
// goal. Generalized-damper and generalized-spring motions are simulated.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/reached_set.h"
#include "verifier/spring_projection.h"

namespace cmt {

// A motion the verifier cannot simulate (none at present; kept for the CLI's exit-2 path).
class UnsupportedMotion : public std::runtime_error {
 public:
  UnsupportedMotion(const std::string& motion, const std::string& what)
      : std::runtime_error(what), motion_(motion) {}
  const std::string& motion() const { return motion_; }

 private:
  std::string motion_;
};

// The conditional test after a step (Buckley §4.2): per branch of the strategy node, the set it starts from.
struct VerifyBranch {
  std::shared_ptr<const ReachedSet> start;  // empty: the branch cannot be taken
  int step = -1;                            // the step simulated first on it, -1 if none (empty or a stop)
};

struct VerifyStep {
  std::string motion;
  ReachedSet termination;
  int node = -1;    // the strategy node (models/task.h StrategyNode) this step simulates
  int parent = -1;  // index of the step before it in `steps`, -1 for the first
  int branch = -1;  // which branch of the parent's test leads here, -1 when it follows unconditionally
  bool may_not_terminate = false;  // no reached atom can stick
  // Reached faces and edges where the motion may slide forever (verifier/slide_forever.h).
  std::vector<int> slide_forever = {};
  bool fallback = false;  // the fixpoint fell back to "everything reached"
  int fixpoint_steps = 0;
  int widened_atoms = 0;    // spring: atoms widened (kSpringWideningRounds: hull, then whole)
  double reached_area = 0;  // area of the reached face regions (diagnostics)
  // Spring motions: the robot may come to rest in free space within free_radius of free_center (the
  // commanded position). Never inside a goal (goals are contact regions): the strategy fails there.
  bool free_termination = false;
  Vec3 free_center = Vec3::Zero();
  double free_radius = 0;
  // Every contact point the motion may pass through (diagnostics, reports; the start included).
  std::shared_ptr<const ReachedSet> reached = nullptr;
  // Motions with termination sets (Buckley §4.5): the reached points where sensing may stop the motion
  // (verifier/sensing_termination.h), already united into `termination`; nullptr without termination sets.
  std::shared_ptr<const ReachedSet> sensing = nullptr;
  // The conditional test after this step (empty without one), and the termination points that may pass no
  // test when there is no `else` branch (nullptr otherwise).
  std::vector<VerifyBranch> branches = {};
  std::shared_ptr<const ReachedSet> unmatched = nullptr;
};

// Steps are in simulation order (depth first, branches in file order); for a decision-free strategy step i
// is motion i. After a failure on one path its sibling branches are still simulated (so every reachable
// node has its prediction); the first failure is the one reported.
struct VerifyResult {
  bool reliable = false;
  SpringModel spring_model = SpringModel::kViaPoint;  // the model the spring motions were simulated with
  double stop_relative_speed = 0;                     // VerifyOptions::stop_relative_speed used
  double contact_lift = 0;                            // VerifyOptions::contact_lift used
  double servo_coast = 0;                             // VerifyOptions::servo_coast used
  std::vector<VerifyStep> steps;
  int failed_step = -1;  // index into steps, or -1
  std::string failure;   // why, when unreliable
  // Offending pieces of the failed step: outside the goal, or passing no test.
  std::vector<ReachedPiece> outside_goal;
  // Index into steps of each strategy node's simulation, -1 where a node was not simulated.
  std::vector<int> node_step;
  const VerifyStep* step_of_node(int node) const {
    return node >= 0 && node < static_cast<int>(node_step.size()) && node_step[node] >= 0
               ? &steps[static_cast<std::size_t>(node_step[node])]
               : nullptr;
  }
};

// Containment tolerance for 1-D and 0-D termination pieces (segments and points on faces, edge intervals,
// vertices), as a fraction of the scene scale: the same 1e-6 as LoadedTask::surface_tolerance(). Face
// regions are compared exactly.
inline constexpr double kGoalRelativeTolerance = 1e-6;

// How the motions are modelled. The spring model must match the controller form whose rollouts the prediction
// is compared with (experiments/validation/verifier_model.h): kVelocity for the impedance and admittance
// forms, kViaPoint (Buckley's App. B) for the position form.
struct VerifyOptions {
  SpringModel spring_model = SpringModel::kViaPoint;
  // kappa of a stop rule that also ends a motion where the robot slides slower than kappa times the motion's
  // reference speed (the rollouts' rule: controllers/termination.h kStopRelativeSpeed, passed in by
  // experiments/validation/verifier_model.h since the verifier does not depend on controllers/). Widens the
  // termination sets of dampers and of velocity-model springs (docs/verifier.md "Slow slides count as
  // stops"). 0: termination by Coulomb sticking only, as in the thesis.
  double stop_relative_speed = 0;
  // How far (task units) a robot sliding on a face may rise off it (docs/verifier.md "Contact lift"). The
  // rollouts' MuJoCo contact gives slip a separating velocity of up to mu x the slip speed, which the servo
  // brings back within its time constant, so a slide into a concave edge may meet the other face up to that
  // high and stick there (experiments/validation/verifier_model.h derives the bound from the controller's
  // gains). Damper projections seed that band beside every reached concave edge. 0: Buckley's first-order
  // contact.
  double contact_lift = 0;
  // tau V (task units): how far the servo's lag may carry a motion on: a damper at an impact along the face
  // it lands on and past a convex rim it slides over (docs/verifier.md "Servo coast"), a velocity-model
  // spring in every flight (the lead point's bounds, "Servo coast of springs"). The rollouts' servo
  // m xddot = b (v_c - xdot) relaxes the velocity with time constant tau = m / b, so a velocity change the
  // first-order model makes at once takes tau there; experiments/validation/verifier_model.h derives tau V
  // from the scene. 0: Buckley's first-order model.
  double servo_coast = 0;
  // lambda tau (dimensionless): a spring's speed is at most lambda |x_c − x̂| (lambda its rate, the rollouts'
  // drive before its top speed), so its coast is at most lambda tau (|p − x| + eps_s) as well as servo_coast
  // (docs/verifier.md "Servo coast of springs"). 0: servo_coast alone bounds it.
  double spring_lag = 0;
  // Also bound velocity-model spring flights for the servo coast (servo_coast, spring_lag; docs/verifier.md
  // "Servo coast of springs"). false: the first-order flights of springs (dampers still coast).
  bool spring_coast = true;
};

// The pieces of `final_set` outside the task's goal (within kGoalRelativeTolerance for 1-D and 0-D pieces):
// the goal containment every final termination set must pass.
std::vector<ReachedPiece> pieces_outside_goal(const LoadedTask& task, const ReachedSet& final_set);

// A decision-free sequence (Strategy::sequence); an unknown motion name is a TaskError.
VerifyResult verify_motions(const LoadedTask& task, const std::vector<std::string>& motions,
                            const VerifyOptions& options = {});
// The start set verify_strategy runs from: the task's start located on its atoms (ReachedSet::from_region);
// with a contact lift, a point start also holds the nearest point of every edge and vertex within
// contact_lift of it (docs/verifier.md "Starts near a rim"): the rollouts' contact, which lets the robot
// sink and rise by about that much, cannot tell a robot that close to a rim or crease from one on it.
ReachedSet start_set(const LoadedTask& task, const VerifyOptions& options);
VerifyResult verify_strategy(const LoadedTask& task, const Strategy& strategy,
                             const VerifyOptions& options = {});
// The same from another start set (a part of the task's start, or any contact set): the teaching system's
// pre-image test (verifier/teaching).
VerifyResult verify_strategy_from(const LoadedTask& task, const Strategy& strategy, const ReachedSet& start,
                                  const VerifyOptions& options = {});

}  // namespace cmt

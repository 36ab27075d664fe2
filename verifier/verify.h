// Verification of a decision-free strategy (Buckley §4.2): chain the motions' simulations (the termination
// set of one motion is the start of the next) and check that the final termination set lies in the goal.
// Generalized-damper and generalized-spring motions are simulated.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/reached_set.h"

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

struct VerifyStep {
  std::string motion;
  ReachedSet termination;
  bool may_not_terminate = false;  // no reached atom can stick
  bool fallback = false;           // the fixpoint fell back to "everything reached"
  int fixpoint_steps = 0;
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
};

struct VerifyResult {
  bool reliable = false;
  std::vector<VerifyStep> steps;
  int failed_step = -1;                    // index into steps, or -1
  std::string failure;                     // why, when unreliable
  std::vector<ReachedPiece> outside_goal;  // offending termination pieces of the failed step
};

// Containment tolerance for 1-D and 0-D termination pieces (segments and points on faces, edge intervals,
// vertices), as a fraction of the scene scale: the same 1e-6 as LoadedTask::surface_tolerance(). Face
// regions are compared exactly.
inline constexpr double kGoalRelativeTolerance = 1e-6;

VerifyResult verify_motions(const LoadedTask& task, const std::vector<std::string>& motions);
VerifyResult verify_strategy(const LoadedTask& task, const Strategy& strategy);

}  // namespace cmt

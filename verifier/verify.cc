// Decision-free strategy verification (Buckley §4.2, Alg 4.1 per motion).
#include "verifier/verify.h"

#include "models/task_error.h"
#include "verifier/atom_cone.h"
#include "verifier/forward_projection.h"
#include "verifier/sensing_termination.h"
#include "verifier/spring_projection.h"

namespace cmt {

VerifyResult verify_motions(const LoadedTask& lt, const std::vector<std::string>& names) {
  std::vector<const Motion*> motions;
  for (const std::string& name : names) {
    const Motion* m = lt.task.find_motion(name);
    if (!m) throw TaskError(lt.task.source_file, "motions", "no motion named '" + name + "'");
    motions.push_back(m);
  }
  VerifyResult out;
  const AtomCones cones(lt.cspace);
  ReachedSet current = ReachedSet::from_region(lt, lt.task.start);
  for (std::size_t i = 0; i < motions.size(); ++i) {
    VerifyStep step{motions[i]->name, ReachedSet(lt.cspace)};
    if (motions[i]->kind == Motion::Kind::kSpring) {
      SpringProjection p = forward_project_spring(lt, current, motions[i]->target);
      step.termination = std::move(p.termination);
      step.may_not_terminate = p.may_not_terminate;
      step.fallback = p.fallback;
      step.fixpoint_steps = p.steps;
      step.reached_area = p.reached.area();
      step.free_termination = p.free_termination;
      step.free_center = p.free_center;
      step.free_radius = p.free_radius;
      step.reached = std::make_shared<const ReachedSet>(std::move(p.reached));
    } else {
      DamperProjection p = forward_project_damper(lt, cones, current, motions[i]->target);
      step.termination = std::move(p.termination);
      step.may_not_terminate = p.may_not_terminate;
      step.fallback = p.fallback;
      step.fixpoint_steps = p.steps;
      step.reached_area = p.reached.area();
      step.reached = std::make_shared<const ReachedSet>(std::move(p.reached));
    }
    if (motions[i]->terminate.any()) {
      // §4.5: the weakly consistent reached points join the weak sticking points (Alg 4.1 step 4). A motion
      // that can stop by sensing somewhere may terminate even where nothing sticks.
      auto sensed =
          std::make_shared<const ReachedSet>(sensing_termination(lt, cones, *motions[i], *step.reached));
      step.termination.unite(*sensed);
      step.may_not_terminate = step.may_not_terminate && sensed->empty();
      step.sensing = std::move(sensed);
    }
    out.steps.push_back(step);
    if (step.may_not_terminate) {
      out.failed_step = static_cast<int>(i);
      out.failure =
          "motion '" + motions[i]->name + "' may never terminate: no reached atom can stick" +
          (motions[i]->terminate.any() ? " and no reached point is consistent with its termination sets"
                                       : "");
      return out;
    }
    if (step.free_termination) {
      // Goals are contact regions, and a motion from a free-space rest is not simulated: a failure either
      // way.
      out.failed_step = static_cast<int>(i);
      out.failure =
          "motion '" + motions[i]->name + "' may come to rest in free space near its commanded position";
      return out;
    }
    current = out.steps.back().termination;
  }
  if (out.steps.empty()) {
    out.failure = "empty strategy";
    return out;
  }
  const ReachedSet goal = ReachedSet::from_regions(lt, lt.task.goal);
  out.outside_goal = current.pieces_outside(goal, kGoalRelativeTolerance * lt.cspace.scale());
  out.reliable = out.outside_goal.empty();
  if (!out.reliable) {
    out.failed_step = static_cast<int>(out.steps.size()) - 1;
    out.failure = "termination of motion '" + out.steps.back().motion + "' is not inside the goal";
  }
  return out;
}

VerifyResult verify_strategy(const LoadedTask& lt, const Strategy& strategy) {
  return verify_motions(lt, strategy.motions);
}

}  // namespace cmt

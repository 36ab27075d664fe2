// Decision-free strategy verification (Buckley §4.2, Alg 4.1 per motion).
#include "verifier/verify.h"

#include "models/task_error.h"
#include "verifier/atom_cone.h"
#include "verifier/forward_projection.h"

namespace cmt {

VerifyResult verify_motions(const LoadedTask& lt, const std::vector<std::string>& names) {
  std::vector<const Motion*> motions;
  for (const std::string& name : names) {
    const Motion* m = lt.task.find_motion(name);
    if (!m) throw TaskError(lt.task.source_file, "motions", "no motion named '" + name + "'");
    if (m->kind == Motion::Kind::kSpring)
      throw UnsupportedMotion(
          name, "unsupported: spring forward projection not implemented yet (motion '" + name + "')");
    motions.push_back(m);
  }
  VerifyResult out;
  const AtomCones cones(lt.cspace);
  ReachedSet current = ReachedSet::from_region(lt, lt.task.start);
  for (std::size_t i = 0; i < motions.size(); ++i) {
    DamperProjection p = forward_project_damper(lt, cones, current, motions[i]->target);
    VerifyStep step{motions[i]->name, p.termination, p.may_not_terminate,
                    p.fallback,       p.steps,       p.reached.area()};
    out.steps.push_back(std::move(step));
    if (p.may_not_terminate) {
      out.failed_step = static_cast<int>(i);
      out.failure = "motion '" + motions[i]->name + "' may never terminate: no reached atom can stick";
      return out;
    }
    current = std::move(p.termination);
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

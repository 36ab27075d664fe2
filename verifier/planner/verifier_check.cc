// The verifier's check of one planned motion (verifier_check.h).
#include "verifier/planner/verifier_check.h"

namespace cmt::planner {

std::optional<std::vector<int>> verifier_targets(const LoadedTask& task, const std::vector<int>& state,
                                                 const Vec3& commanded, const VerifyOptions& options) {
  LoadedTask with = task;
  Motion m;
  m.name = "planner_check";
  for (int k = 2; with.task.find_motion(m.name); ++k) m.name = "planner_check_" + std::to_string(k);
  m.kind = Motion::Kind::kSpring;
  m.target = commanded;
  with.task.motions.push_back(m);
  ReachedSet start(with.cspace);
  for (int atom : state) start.add_whole_atom(atom);
  start.add_boundary_closure();
  const VerifyResult v = verify_strategy_from(with, Strategy::sequence(m.name, {m.name}), start, options);
  if (v.steps.empty()) return std::nullopt;
  const VerifyStep& step = v.steps.front();
  if (step.may_not_terminate || !step.slide_forever.empty() || step.fallback || step.free_termination)
    return std::nullopt;
  return step.termination.atoms();
}

}  // namespace cmt::planner

// The verifier's check of a planned chain of motions (verifier_check.h).
#include "verifier/planner/verifier_check.h"

namespace cmt::planner {

namespace {

// The task with spring motions to `commanded` added under free names, and those names.
std::pair<LoadedTask, std::vector<std::string>> with_motions(const LoadedTask& task,
                                                             const std::vector<Vec3>& commanded) {
  std::pair<LoadedTask, std::vector<std::string>> out{task, {}};
  int k = 1;
  for (const Vec3& p : commanded) {
    Motion m;
    do m.name = "planner_check_" + std::to_string(k++);
    while (out.first.task.find_motion(m.name));
    m.kind = Motion::Kind::kSpring;
    m.target = p;
    out.first.task.motions.push_back(m);
    out.second.push_back(m.name);
  }
  return out;
}

std::optional<std::vector<int>> step_ends(const VerifyStep& step) {
  if (step.may_not_terminate || !step.slide_forever.empty() || step.fallback || step.free_termination)
    return std::nullopt;
  return step.termination.atoms();
}

}  // namespace

ChainVerdict verifier_chain(const LoadedTask& task, const std::vector<Vec3>& commanded,
                            const VerifyOptions& options) {
  const auto [with, names] = with_motions(task, commanded);
  const VerifyResult v = verify_strategy(with, Strategy::sequence("planner_check", names), options);
  ChainVerdict out;
  out.reliable = v.reliable;
  for (const VerifyStep& step : v.steps) {
    out.ends.push_back(step_ends(step));
    if (!out.ends.back()) break;
  }
  return out;
}

}  // namespace cmt::planner

// The verifier's check of a planned chain of motions (verifier_check.h).
#include "verifier/planner/verifier_check.h"

#include <algorithm>

#include "verifier/planner/goal_stops.h"
#include "verifier/planner/task_atoms.h"

namespace cmt::planner {

namespace {

// The task with spring motions to `commanded` added under free names, and those names.
std::pair<LoadedTask, std::vector<std::string>> with_motions(const LoadedTask& task,
                                                             const std::vector<Vec3>& commanded,
                                                             const MotionTermination& terminate) {
  std::pair<LoadedTask, std::vector<std::string>> out{task, {}};
  int k = 1;
  for (const Vec3& p : commanded) {
    Motion m;
    do m.name = "planner_check_" + std::to_string(k++);
    while (out.first.task.find_motion(m.name));
    m.kind = Motion::Kind::kSpring;
    m.target = p;
    m.terminate = terminate;
    out.first.task.motions.push_back(m);
    out.second.push_back(m.name);
  }
  return out;
}

// The atoms of the step's termination set, those that are not goal atoms but whose part lies in the goal as
// the goal-stop atom.
std::optional<std::vector<int>> step_ends(const LoadedTask& task, const std::vector<bool>& goal_atom,
                                          const VerifyStep& step) {
  if (step.may_not_terminate || !step.slide_forever.empty() || step.fallback || step.free_termination)
    return std::nullopt;
  // One containment test for the whole set: a non-goal atom with no piece outside lies in the goal.
  std::vector<bool> outside(goal_atom.size(), false);
  for (const ReachedPiece& piece : pieces_outside_goal(task, step.termination))
    outside[static_cast<std::size_t>(piece.atom)] = true;
  std::vector<int> ends;
  for (int a : step.termination.atoms()) {
    const bool stays_atom = goal_atom[static_cast<std::size_t>(a)] || outside[static_cast<std::size_t>(a)];
    ends.push_back(stays_atom ? a : goal_stop_atom(task.cspace));
  }
  std::sort(ends.begin(), ends.end());
  ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
  return ends;
}

}  // namespace

ChainVerdict verifier_chain(const LoadedTask& task, const std::vector<Vec3>& commanded,
                            const VerifyOptions& options, const MotionTermination& terminate) {
  const auto [with, names] = with_motions(task, commanded, terminate);
  const std::vector<bool> goal_atom = goal_atoms(task);
  const VerifyResult v = verify_strategy(with, Strategy::sequence("planner_check", names), options);
  ChainVerdict out;
  out.reliable = v.reliable;
  for (const VerifyStep& step : v.steps) {
    out.ends.push_back(step_ends(task, goal_atom, step));
    if (!out.ends.back()) break;
  }
  return out;
}

}  // namespace cmt::planner

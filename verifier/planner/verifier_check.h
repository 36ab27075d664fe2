// The planner's independent check of a motion (PlanRequest::confirm) by the verifier (verifier/verify.h).
#pragma once

#include <optional>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/planner/search.h"
#include "verifier/verify.h"

namespace cmt::planner {

// The atoms where the spring motion to `commanded`, started anywhere on the closures of the state's atoms,
// may stop (verify_strategy_from's termination, ascending), or nothing when it may fail otherwise: rest in
// free space, slide forever, or not terminate, or the verifier fell back to "everything reached".
std::optional<std::vector<int>> verifier_targets(const LoadedTask& task, const std::vector<int>& state,
                                                 const Vec3& commanded, const VerifyOptions& options = {});

// A decision-free chain of spring motions verified from the task's start (verify_strategy): per motion, in
// order, the atoms where it may stop, or nothing where it may fail otherwise (as verifier_targets); the
// list ends at the first motion that may fail. Each motion starts from the previous one's actual
// termination set, not from whole atoms, so a chain can verify where its arcs from whole atoms cannot.
ChainVerdict verifier_chain(const LoadedTask& task, const std::vector<Vec3>& commanded,
                            const VerifyOptions& options = {});

}  // namespace cmt::planner

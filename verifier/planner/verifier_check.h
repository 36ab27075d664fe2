// The planner's independent check of a motion (PlanRequest::confirm) by the verifier (verifier/verify.h).
#pragma once

#include <optional>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/verify.h"

namespace cmt::planner {

// The atoms where the spring motion to `commanded`, started anywhere on the closures of the state's atoms,
// may stop (verify_strategy_from's termination, ascending), or nothing when it may fail otherwise: rest in
// free space, slide forever, or not terminate, or the verifier fell back to "everything reached".
std::optional<std::vector<int>> verifier_targets(const LoadedTask& task, const std::vector<int>& state,
                                                 const Vec3& commanded, const VerifyOptions& options = {});

}  // namespace cmt::planner

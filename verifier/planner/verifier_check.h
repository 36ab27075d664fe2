// The planner's independent checks by the verifier (verifier/verify.h): a candidate chain from the task's
// start (PlanRequest::confirm_chain), and one motion from the start region (PlanRequest::start_targets).
#pragma once

#include <optional>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/planner/search.h"
#include "verifier/verify.h"

namespace cmt::planner {

// A decision-free chain of spring motions verified from the task's start (verify_strategy): per motion, in
// order, the atoms where it may stop, or nothing where it may fail otherwise (rest in free space, slide
// forever, not terminate, or the verifier fell back to "everything reached"); the list ends at the first
// motion that may fail. Each motion starts from the previous one's actual termination set, not from whole
// atoms, so a chain can verify where its arcs from whole atoms cannot. Every motion carries `terminate`
// (empty: sticking only). A stop on an atom that is not a goal atom but lies wholly in the goal (a partial
// goal face, goal_stops.h) is reported as the goal-stop atom, cspace.atom_count() + 1.
ChainVerdict verifier_chain(const LoadedTask& task, const std::vector<Vec3>& commanded,
                            const VerifyOptions& options = {}, const MotionTermination& terminate = {});

}  // namespace cmt::planner

// The physics check of an EDR strategy (docs/edr.md "Physics check"): MuJoCo rollouts in worlds whose model
// parameters are drawn uniformly over their whole intervals (not only at the verifier's slices; a discrete
// parameter uniformly among its values), each world's
// scene built from the task read at those values, the strategy run under the usual sampled bounded errors,
// and every rollout's end classified by the EDR termination predicate against what happened:
//  - success: the predicate signals success and the robot is in the world's goal;
//  - failure_signalled: it signals failure and the robot is not in the goal;
//  - false_success (forbidden): success signalled, not in the goal;
//  - false_failure (forbidden): failure signalled in a world where the verifier guarantees success (run in
//    that world, it says every termination lies in the goal);
//  - missed_success: failure signalled although the robot is in the goal of a world without that guarantee
//    (allowed by Donald's axioms only where success is not recognizable; a slicing gap when the verifier's
//    slices say every termination in the goal is recognized);
//  - timeout: a motion did not terminate; unstable: the simulation broke (not classified).
// The predicate (the robot's own test after the last motion): a fresh sensing draw (position offset within
// eps_s, force direction turned by up to theta_f; on the bounds in extreme mode) is consistent with a
// termination in the goal of some slice of the verifier's result, or of the sweep between two adjacent slices
// (verifier/edr/edr.h EdrResult::swept_success): within eps_s of one of its pieces (a face region as the hull
// of its outline) with the sensed force within theta_f of that atom's friction cone.
#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "controllers/error_model.h"
#include "models/loaded_task.h"
#include "verifier/edr/edr.h"

namespace cmt {

struct EdrCheckOptions {
  int rollouts = 1000;          // in all, spread over ceil(rollouts / rollouts_per_world) worlds
  int rollouts_per_world = 10;  // the last world takes the remainder
  std::uint64_t seed = 1;       // world w draws its rollouts from seed + w (replay: cmt rollout --world)
  int threads = 1;
  SampleMode mode = SampleMode::kExtreme;
};

struct EdrCheckOutcome {
  std::vector<double> values;  // the world's model parameters
  int world = -1, index = -1;  // rollout `index` of world `world` (seed EdrCheckOptions::seed + world)
  std::string outcome;
  Vec3 end = Vec3::Zero();
  std::string replay;  // `cmt rollout ... --world NAME=VALUE ...` that runs it as its last rollout
};

struct EdrCheck {
  int rollouts = 0, success = 0, failure_signalled = 0, false_success = 0, false_failure = 0,
      missed_success = 0, timeout = 0, unstable = 0;
  std::vector<EdrCheckOutcome> forbidden;  // false successes and false failures (at most 50)
  std::vector<EdrCheckOutcome> missed;     // missed successes (at most 50)
  // The verifier in each world against its rollouts (docs/validation.md): motion ends outside the world's
  // predicted termination sets, of `ends`; soundness = (ends - outside) / ends; coverage the mean over the
  // worlds of their coverage (validation.h score_coverage). `outside_ends` lists them (the first 20, each
  // world's farthest first) with replays.
  int ends = 0, outside = 0;
  double soundness = 1, coverage = 0;
  std::vector<EdrCheckOutcome> outside_ends;
  // Per world: its values, whether its verification is reliable, its outcome counts (the report's plot),
  // outside ends and coverage, and the `cmt rollout` command that runs its rollouts again.
  nlohmann::json worlds = nlohmann::json::array();
};

// `strategy` names a decision-free strategy of the task (its motions run in every world).
EdrCheck check_edr(const Task& task, const std::string& strategy, const EdrResult& verdict,
                   const EdrCheckOptions& options);
nlohmann::json edr_check_json(const Task& task, const EdrCheck& check);

}  // namespace cmt

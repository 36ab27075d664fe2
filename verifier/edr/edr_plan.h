// LIMITED's generate-and-test EDR planner (Donald 1987 §6.3, l.3663-3732; Algorithm Multi, §10.4) over
// generalized-damper commands, one and two motions:
//  1. One step: commanded directions first toward centroid(goal) - centroid(start), then turned outward on
//     both sides in steps of `angle_step` (about the horizontal axis across that direction, or y when it is
//     vertical); the first whose EDR verdict (edr.h) holds on the coarse slices and again on the fine ones.
//  2. Two steps (Algorithm Multi): a first motion that terminates in every coarse slice (its termination sets
//     are its sticking push-forward push(G u H), the next motion's start), then a second searched the same
//     way toward centroid(goal) - centroid(push-forward), the pair's verdict on the coarse and the fine
//     slices.
// The multi-resolution loop (M1-M2): plan on the coarse slices, re-verify on the fine ones; a candidate that
// fails there is dropped and the search goes on (M3's "nearby directions" are the next candidates).
// With `guaranteed`, a plan must also be guaranteed wherever the goal exists (every slice with a goal is
// `reliable`: success from the whole start, Donald's R' = R there), not only EDR-reliable, which allows a
// failure signal in such a slice where success is not guaranteed.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "verifier/edr/edr.h"

namespace cmt {

// The task with damper motions of these commanded directions added, named edr_plan_motion_name(0, 1, ...),
// the last one carrying the EDR termination predicate; it must read at other model values too (task_at), so
// the caller edits the task's text (experiments/edr/edr_plan_task.h).
using TaskWithDampers = std::function<Task(const std::vector<Vec3>& directions)>;

std::string edr_plan_motion_name(int index);

struct EdrPlanOptions {
  int coarse_resolution = 2, fine_resolution = 5;  // model_error.h slice_values
  double angle_step = 0.2618;                      // 15 degrees
  int angle_steps = 6;                             // up to 90 degrees on each side
  int max_motions = 2;                             // 1: one-step plans only
  int min_motions = 1;                             // 2: two-step plans only
  int max_verdicts = 400;                          // coarse verdicts before giving up
  bool guaranteed = false;                         // require success wherever the goal exists
  EdrOptions edr;                                  // the verifier's model per slice
};

struct EdrPlan {
  bool found = false;
  std::vector<Vec3> directions;  // the plan's commanded velocities, in order
  EdrResult verdict;             // on the fine slices (when found)
  int verdicts = 0;              // coarse verdicts computed
  std::string reason;            // why nothing was found
};

// Every slice with a goal is reliable (its terminations all in the goal).
bool guaranteed_where_goal_exists(const EdrResult& verdict);

// The candidate directions about `toward` (unit): toward itself, then turned by +-k angle_step.
std::vector<Vec3> edr_candidate_directions(const Vec3& toward, double angle_step, int angle_steps);

EdrPlan plan_edr(const Task& task, const TaskWithDampers& with_dampers, const EdrPlanOptions& options);

}  // namespace cmt

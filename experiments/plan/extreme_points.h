// Buckley §6.3.4's experiment, in simulation: how much of a planned motion's set of commanded positions is
// reliable, and how conservative the set is. For each motion of a planned decision-free strategy, the
// strategy is run with that motion commanded at each vertex (extreme point) of its cposition polyhedra, the
// other motions as planned: the planner claims every point of the closed set, so every rollout must succeed.
// Then at the vertices of the polyhedra grown by k eps_p (each facet moved out by k eps_p, so each such point
// is at least k eps_p outside): the success rates there say how much the planner gives away. Every point runs
// `cmt validate` (the verifier's verdict at that point and N MuJoCo rollouts). docs/planner.md "§6.3.4".
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/planner/cposition_set.h"

namespace cmt {

// One motion of the planned strategy and the commanded positions the planner claims for it: a cell, or (a
// start or chain projection's motion, which claims no cell) its one commanded position.
struct PlannedMotionCell {
  std::string motion;           // the motion's name in the planned task
  Vec3 commanded;               // as planned
  planner::CPositionSet cells;  // empty: the motion claims `commanded` alone
};

struct ExtremePointOptions {
  int rollouts = 100;                    // per commanded point
  std::vector<double> grow = {1, 2, 4};  // growth of the polyhedra, in eps_p
  std::uint64_t seed = 1;                // point k of the experiment uses master seed splitmix64(seed + k)
  int threads = 1;                       // results are identical for every thread count
};

// The vertices of a motion's cposition polyhedra (its commanded point when it claims no cell), without
// repeats.
std::vector<Vec3> cell_vertices(const PlannedMotionCell& cell);
// The vertices of each polyhedron grown by `distance` (its half-spaces' offsets increased by it; a motion
// that claims one point grows into the cube of half-side `distance` about it), less those strictly inside
// another grown polyhedron of the motion: every point returned is at least `distance` from every polyhedron
// (points on a seam between two grown pieces are kept, though they are not corners of the grown union).
std::vector<Vec3> grown_vertices(const PlannedMotionCell& cell, double distance);

struct PointTrial {
  Vec3 commanded = Vec3::Zero();
  bool reliable = false;  // the verifier's verdict of the strategy with this commanded position
  std::string failure;    // the verifier's reason when not reliable
  int rollouts = 0, successes = 0, outside = 0, unstable = 0;
};

struct GrownTrials {
  double factor = 0;  // in eps_p
  std::vector<PointTrial> points;
};

struct MotionExtremes {
  std::string motion;
  bool claims_cell = false;  // false: a projection's single commanded position
  std::vector<PointTrial> vertices;
  std::vector<GrownTrials> grown;
};

// The whole experiment on `planned` (a task holding `strategy`, decision free, whose motions are `cells`).
std::vector<MotionExtremes> run_extreme_points(std::shared_ptr<const LoadedTask> planned,
                                               const std::string& strategy,
                                               const std::vector<PlannedMotionCell>& cells,
                                               const ExtremePointOptions& options);

// JSON `extremes`: rollouts_per_point, grow, seed, eps_p, vertices_all_succeed, and per motion its vertices'
// and each growth's points (commanded, reliable, failure, rollouts, successes, outside, unstable) with the
// totals (rollouts, successes, rate).
nlohmann::json extreme_points_json(const LoadedTask& task, const std::vector<MotionExtremes>& motions,
                                   const ExtremePointOptions& options);
// Every rollout commanded at a vertex reached the goal, and none ended outside the verifier's prediction.
bool vertices_all_succeed(const std::vector<MotionExtremes>& motions);

}  // namespace cmt

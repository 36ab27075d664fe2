// The data of a 3-D page (docs/viewer.md "Data format"): a task's C-space, start and goal, and optionally a
// strategy's predicted termination sets, observed motion ends and rollout trajectories, as generic layers (a
// named set of polygons, segments, points, polylines and spheres with one style). Other tools (teaching,
// planning) add layers of their own with add_layer.
#pragma once

#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/report/predicted_sets.h"
#include "experiments/report/results_db.h"
#include "models/loaded_task.h"

namespace cmt::report {

// A recorded rollout path (task units), drawn as one polyline per rollout.
struct ViewTrajectory {
  int rollout = 0;
  bool success = false;
  std::vector<Vec3> points;
};

// The stick class ("must", "may" or "never", Buckley §3.3) of an atom under a motion of the task, for the
// shading of predicted pieces; the caller supplies it (the verifier computes it; this library does not link
// the verifier).
using StickClassOf = std::function<std::string(const LoadedTask& task, const std::string& motion, int atom)>;

struct ConfigRow;
// The failing rollout a configuration's validation recorded (metrics.counterexample), replayed with its
// trajectory; empty when there is none. The caller supplies it (this library does not link the simulator).
using CounterexampleReplay =
    std::function<std::vector<ViewTrajectory>(std::shared_ptr<const LoadedTask> task, const ConfigRow& row)>;

struct ViewInput {
  const LoadedTask* task = nullptr;
  std::string title;
  std::vector<std::string> motions;           // the strategy's motion names in order (without a prediction)
  const PredictedSets* prediction = nullptr;  // null: nothing predicted
  const std::vector<RolloutRow>* ends = nullptr;  // null: no rollouts
  std::vector<ViewTrajectory> trajectories;
  std::vector<ViewTrajectory> counterexample;  // the replayed failing rollout, if any
  StickClassOf stick_class;                    // empty: pieces are not shaded by class
};

// One layer: {id, name, group, style: {color, opacity}, visible, polygons, segments, points, polylines,
// spheres}; every item has `info` (shown when clicked).
nlohmann::json make_layer(const std::string& id, const std::string& name, const std::string& group,
                          const std::string& color, double opacity);

// A point as the page reads it, [x, y, z]; a list of points, the non-finite ones (a piece the verifier could
// not place) left out.
nlohmann::json view_point(const Vec3& p);
nlohmann::json view_points(const std::vector<Vec3>& ps);
// Adds a piece of a contact set to `layer` by its vertex count: a point (one), a segment (two) or a polygon
// with holes, each with `info`.
void add_view_piece(nlohmann::json& layer, const std::vector<Vec3>& polygon,
                    const std::vector<std::vector<Vec3>>& holes, const nlohmann::json& info);

// {format: "cmt-view-1", title, units, bounds: {min, max} (the whole C-space), focus: {min, max} (start,
// goal, prediction, ends, trajectories: where the camera looks first), layers: [...]}.
nlohmann::json view_data(const ViewInput& input);

}  // namespace cmt::report

// Strong backprojections checked by physics (docs/teaching.md "Backprojections"): MuJoCo rollouts of a chain
// of motions started at points of its strong backprojection S (the pieces' corners and points drawn
// uniformly in its face regions) must all reach the goal. Each point becomes a task file of its own (the task
// with the chain as a strategy and the point as the start), so every failure replays with `cmt rollout`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/teach/task_file_check.h"
#include "experiments/validation/validation.h"
#include "verifier/reached_set.h"

namespace cmt {

struct BackprojectionCheckOptions {
  int points = 20;  // start points drawn in S (up to half of them the pieces' corners)
  int n = 25;       // rollouts per point
  std::uint64_t seed = 1;
  int threads = 1;
  SampleMode mode = SampleMode::kExtreme;
  ControllerForm form = ControllerForm::kImpedance;  // the rollouts' controller form
  std::filesystem::path dir;                         // where the point task files are written
};

struct PointCheck {
  Vec3 start;
  std::string task_file;
  TaskFileCheck result;
};

struct BackprojectionCheck {
  std::string strategy;  // the chain's name in the point task files
  std::vector<PointCheck> points;
  int rollouts = 0, successes = 0, unstable = 0, failures = 0, outside = 0;
};

// Start points in `strong`: the corners of its face, edge and vertex pieces first (at most half of
// options.points), then points drawn uniformly on its faces (rejection against the face regions, from
// options.seed), in task coordinates.
std::vector<Vec3> backprojection_sample(const LoadedTask& task, const ReachedSet& strong,
                                        const BackprojectionCheckOptions& options);
BackprojectionCheck check_backprojection(const std::string& task_yaml, const LoadedTask& task,
                                         const std::vector<std::string>& chain, const ReachedSet& strong,
                                         const BackprojectionCheckOptions& options);
nlohmann::json backprojection_check_json(const BackprojectionCheck& check, int dimension);

}  // namespace cmt

// The teaching system's pre-images checked by physics (docs/teaching.md "Pre-image check"): for every solved
// cell of a teaching session, MuJoCo rollouts of the chain that solved it, started at points sampled in the
// cell (its vertices and edges included: experiments/validation), must all reach the goal. Each cell becomes
// a task file of its own (the task, the teaching session's inline motions, the chain as a strategy, the cell
// as the start), so every failure replays with `cmt rollout`.
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "experiments/validation/validation.h"
#include "verifier/teaching/teaching_session.h"

namespace cmt {

struct PreimageCheckOptions {
  int n = 100;  // rollouts per solved cell
  std::uint64_t seed = 1;
  int threads = 1;
  SampleMode mode = SampleMode::kUniform;
  std::filesystem::path dir;  // where the cell task files are written
};

struct CellCheck {
  int step = 0;      // 0-based teaching step
  std::string cell;  // the cell's path in the halving tree ("" the whole start)
  std::string task_file, strategy;
  int rollouts = 0, successes = 0, unstable = 0, outside = 0;
  double soundness = 1;
  std::string replay;  // the first failed rollout's replay command, if any
};

struct PreimageCheck {
  std::vector<CellCheck> cells;
  int rollouts = 0, successes = 0, unstable = 0, failures = 0, outside = 0;
};

PreimageCheck check_preimages(const std::string& task_yaml, const teaching::Session& session,
                              const PreimageCheckOptions& options);
nlohmann::json preimage_check_json(const PreimageCheck& check);

}  // namespace cmt

// Command-line options that every rollout-running command shares (`cmt rollout`, `cmt validate`): the number
// of rollouts, the master seed, the thread count and the error-sampling mode, with the same help and checks.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "models/loaded_task.h"

namespace cmt {

void add_rollout_sampling_options(CLI::App* cmd, int& n, std::uint64_t& seed, int& threads,
                                  std::string& mode);
// Throws CLI::ValidationError unless n > 0 and threads >= 0.
void check_rollout_sampling_options(int n, int threads);

// `--world NAME=VALUE` (repeatable): the task read at those model-error values (load_task_slice), the other
// parameters at their nominal values; the task itself when `world` is empty. A name the task's model_error
// lacks, a malformed item or a value outside its interval is a InputError naming --world.
std::shared_ptr<const LoadedTask> task_in_world(std::shared_ptr<const LoadedTask> task,
                                                const std::vector<std::string>& world);

}  // namespace cmt

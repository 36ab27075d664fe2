// Command-line options that every rollout-running command shares (`cmt rollout`, `cmt validate`): the number
// of rollouts, the master seed, the thread count and the error-sampling mode, with the same help and checks.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

namespace cmt {

void add_rollout_sampling_options(CLI::App* cmd, int& n, std::uint64_t& seed, int& threads,
                                  std::string& mode);
// Throws CLI::ValidationError unless n > 0 and threads >= 0.
void check_rollout_sampling_options(int n, int threads);

}  // namespace cmt

#include "experiments/cli/rollout_cli.h"

namespace cmt {

void add_rollout_sampling_options(CLI::App* cmd, int& n, std::uint64_t& seed, int& threads,
                                  std::string& mode) {
  cmd->add_option("-n", n, "number of rollouts (> 0)")->capture_default_str();
  cmd->add_option("--seed", seed, "master seed; rollout i uses a stream derived from (seed, i)")
      ->capture_default_str();
  cmd->add_option("--threads", threads,
                  "worker threads (default: hardware threads); results do not depend on it");
  cmd->add_option("--mode", mode, "error sampling: uniform, or extreme (mostly on the bounds' boundaries)")
      ->check(CLI::IsMember({"uniform", "extreme"}))
      ->capture_default_str();
}

void check_rollout_sampling_options(int n, int threads) {
  if (n <= 0) throw CLI::ValidationError("-n", "must be > 0, got " + std::to_string(n));
  if (threads < 0) throw CLI::ValidationError("--threads", "must be >= 0, got " + std::to_string(threads));
}

}  // namespace cmt

// A physics check of one written task file (the teaching system's pre-image and backprojection checks): the
// file is written, then `cmt validate` runs its strategy without a counterexample search.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "experiments/validation/validation.h"

namespace cmt {

struct TaskFileCheck {
  int rollouts = 0, successes = 0, unstable = 0, outside = 0;
  double soundness = 1;
  std::string replay;  // the first failed rollout's replay command, if any
  int failures() const { return rollouts - unstable - successes; }
};

// Writes `text` to `file` (std::runtime_error naming `dir_option` when it cannot) and validates `strategy`.
TaskFileCheck check_task_file(const std::filesystem::path& file, const std::string& text,
                              const std::string& strategy, ValidateOptions options,
                              const std::string& dir_option);

}  // namespace cmt

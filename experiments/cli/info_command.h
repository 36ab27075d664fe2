// `cmt info TASK [--atoms] --json`: counts of the C-space atoms (docs/contracts.md), and with --atoms their
// geometry.
#pragma once

#include <nlohmann/json.hpp>

#include "models/loaded_task.h"

namespace cmt {

nlohmann::json info_json(const LoadedTask& task, bool with_atoms, double build_seconds);
// A short human-readable summary for the terminal.
std::string info_text(const LoadedTask& task);

}  // namespace cmt

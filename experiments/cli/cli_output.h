// How every cmt command reports: one JSON object on stdout with --json (logs and messages on stderr), and the
// exit statuses of docs/contracts.md: 0 success, 1 the computation found a failure, 2 bad input or usage.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "experiments/common/point_json.h"
#include "models/task_error.h"

namespace cmt {

inline constexpr int kExitSuccess = 0;
inline constexpr int kExitFailureFound = 1;
inline constexpr int kExitBadInput = 2;

// Prints the object (pretty) followed by a newline.
void print_json(const nlohmann::json& object);

// Reports a bad-input error: on stderr always; with --json also as {"error": {message, file, key, reason,
// line, column}} on stdout (each field only when known; line and column for YAML syntax errors). Returns 2.
int report_bad_input(const std::string& message, bool json, const std::string& file = "",
                     const std::string& key = "", const std::string& reason = "", TextLocation where = {});

// A task file's text (kept when a command writes it back, e.g. with planned motions); a
// missing file is bad input naming it (like load_task).
std::string read_task_text(const std::string& path);

}  // namespace cmt

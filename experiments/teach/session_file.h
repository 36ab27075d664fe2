// Teaching session files (docs/contracts.md, docs/task-format.md "Teaching sessions"): `steps:` a list, in
// the order the teacher proposes motions (the strategy's last motion first); each item a motion name of the
// task or an inline motion {spring: [x, y, z]} / {damper: [x, y, z]} with an optional `name`. Coordinates are
// in the task's dimension ([x, z] for planar tasks), checked as the task loader checks motions; every error
// is a InputError naming the file, the key and the reason.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "models/task.h"

namespace cmt {

struct SessionStep {
  std::string motion;                   // a motion of the task (when `inline_motion` is empty)
  std::optional<Motion> inline_motion;  // its name empty unless the file gave one
};

std::vector<SessionStep> parse_session(const std::string& yaml_text, const std::string& label,
                                       const Task& task);
std::vector<SessionStep> load_session(const std::filesystem::path& path, const Task& task);

// One step as the teaching session file spells it (the interactive mode's transcript).
std::string session_step_yaml(const SessionStep& step, int dimension);

}  // namespace cmt

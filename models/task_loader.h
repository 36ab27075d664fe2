// Reads a task YAML file (docs/contracts.md "Task files") into a Task, checking the schema: unknown, missing
// and mistyped keys, value ranges, degenerate parts and regions, strategies naming unknown motions. Checks
// that need the configuration space (regions on the contact surface, empty free space) live in load_task
// (models/loaded_task.h). Every failure throws TaskError naming file, key path and reason.
#pragma once

#include <filesystem>
#include <string>

#include "models/task.h"

namespace cmt {

// Planar tasks (dimension: 2) are extruded along y: environment and C-space parts span y in
// [-kPlanarPartHalfDepth, kPlanarPartHalfDepth], robot parts half of that, and the C-space is clipped to
// |y| <= kPlanarClipHalfDepth, strictly inside every extruded obstacle, so no y-facing atom is real.
inline constexpr double kPlanarPartHalfDepth = 1.0;
inline constexpr double kPlanarRobotHalfDepth = 0.25;
inline constexpr double kPlanarClipHalfDepth = 0.5;

// Parses and checks the schema. `file_label` names the file in messages (defaults to the path).
Task parse_task_file(const std::filesystem::path& path);
// `model_values` (one per model parameter, in file order) reads a slice of a task with model_error; nullptr
// reads it at the nominal values.
Task parse_task_string(const std::string& yaml_text, const std::string& file_label,
                       const std::vector<double>* model_values = nullptr);
// The task read again at other model values (a slice of C x J, models/model_error.h) from its file text
// (Task::model_source): changes made to `task` in memory after loading are not carried over. TaskError when a
// value is outside its interval or the geometry there is not accepted (a part degenerates).
Task task_at(const Task& task, const std::vector<double>& model_values);

}  // namespace cmt

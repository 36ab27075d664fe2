// `cmt export-mjcf TASK -o FILE`: writes the task's MuJoCo 2.2 scene (sim/mjcf_export.h).
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>

#include "models/loaded_task.h"

namespace cmt {

// Writes the scene and returns the JSON summary; throws std::runtime_error on I/O failure.
nlohmann::json export_mjcf_command(const LoadedTask& task, const std::filesystem::path& output);

}  // namespace cmt

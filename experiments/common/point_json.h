// A point of a task in JSON, in the task's own coordinates (docs/contracts.md): [x, y, z], or [x, z] for a
// planar task.
#pragma once

#include <nlohmann/json.hpp>

#include "models/task.h"

namespace cmt {

nlohmann::json point_json(const Vec3& p, int dimension);

}  // namespace cmt

// A task together with its configuration space: what every command works on. Loading checks the schema
// (task_loader.h) and then what needs the C-space: start and goal regions must lie on the contact surface and
// the free space must not be empty. With model error the goal is the part of its regions on the surface in
// each world (it may vanish in some, Donald l.867): at the nominal values some of it must lie there. Nothing
// is half-loaded: either both parts exist or TaskError is thrown.
#pragma once

#include <filesystem>
#include <memory>

#include "models/cspace.h"
#include "models/task.h"

namespace cmt {

// A start/goal region counts as on the contact surface when every sample of it lies within this fraction of
// the scene scale (CSpace::scale, the diagonal of the atoms' bounding box) of a face: 1e-6 absorbs decimal
// rounding of hand-written coordinates and nothing more.
inline constexpr double kRegionOnSurfaceRelativeTolerance = 1e-6;

struct LoadedTask {
  Task task;
  CSpace cspace;
  double surface_tolerance() const { return kRegionOnSurfaceRelativeTolerance * cspace.scale(); }
};

// Loads, builds and checks; shared_ptr<const> because a loaded task never changes and is shared across
// threads.
std::shared_ptr<const LoadedTask> load_task(const std::filesystem::path& path);
std::shared_ptr<const LoadedTask> load_task_from_string(const std::string& yaml_text,
                                                        const std::string& label);

// A slice of a task with model error (models/model_error.h): the task read at `model_values` and built and
// checked as load_task does, except that the goal may leave the contact surface (Donald l.867: the goal may
// vanish in some slices). The start must stay on the surface in every slice (TaskError otherwise).
std::shared_ptr<const LoadedTask> load_task_slice(const Task& task, const std::vector<double>& model_values);
// Points that stand for a region when checking it: its vertices, and for segments and polygons a grid of
// interior points (a segment across a hole has its ends on the surface but not its middle).
std::vector<Vec3> region_samples(const Region& region, int per_side = 16);

}  // namespace cmt

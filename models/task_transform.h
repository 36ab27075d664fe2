// Similarity maps of a whole task (geometry, regions, commands, error bounds): y = scale R x + offset with R
// a rotation by multiples of 90° (a signed permutation, det +1), optionally relabelled in other length units.
// A verdict must not depend on where a task sits in the world, on how it is turned, or on the units it is
// written in: the verifier's invariance tests run every built-in strategy on transformed copies.
#pragma once

#include <memory>
#include <optional>

#include "models/loaded_task.h"
#include "models/task.h"

namespace cmt {

struct TaskTransform {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // a signed permutation with det +1
  double scale = 1;                                        // lengths are multiplied by it
  Vec3 offset = Vec3::Zero();
  std::optional<LengthUnit> units;  // the transformed task's units label (unchanged when empty)

  Vec3 point(const Vec3& x) const { return scale * (rotation * x) + offset; }
  Vec3 direction(const Vec3& d) const { return rotation * d; }

  // The quarter turn about axis 0 (x), 1 (y) or 2 (z), `turns` times.
  static TaskTransform quarter_turns(int axis, int turns);
  // The same physical task written in other units (lengths scaled by the ratio of unit sizes).
  static TaskTransform change_units(LengthUnit from, LengthUnit to);
  // this after `first`.
  TaskTransform after(const TaskTransform& first) const;
};

// Whether r is a rotation by multiples of 90° about the axes: a signed permutation with det +1.
bool is_quarter_turn_rotation(const Eigen::Matrix3d& r);

// The geometry of a task (parts and bounds) in its own axes (Task::axes): every point x becomes
// axes^T x, exactly (a signed permutation moves and negates coordinates, with no rounding); the returned
// task's axes are the world axes. Regions, motions and strategies are left as they are.
Task geometry_in_own_axes(const Task& task);

// Throws std::invalid_argument when the rotation is not a proper signed permutation, or when a planar task
// (dimension 2, extruded along y) would be turned out of its x-z plane. A task with model error becomes its
// nominal slice, without model error.
Task transformed(const Task& task, const TaskTransform& map);

// Builds the configuration space of an in-memory task and checks its regions, as load_task does for a file.
std::shared_ptr<const LoadedTask> load_task_from_task(Task task);

}  // namespace cmt

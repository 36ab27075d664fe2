// Accepted numeric ranges and sizes of a task (docs/task-format.md "Accepted ranges and sizes"). The schema
// alone lets through numbers the geometry cannot work with: a box 1e-320 thick (its face normals underflow),
// bounds of 1e308 (squares overflow), error bounds larger than the scene. These limits keep every accepted
// task inside what double-precision geometry and the exact kernel's conversions handle, and each violation is
// a TaskError naming the key (exit status 2).
#pragma once

#include <cstddef>
#include <numbers>
#include <string>

#include "models/task.h"

namespace cmt {

// Largest magnitude of any coordinate or direction component in a task file, in task units.
inline constexpr double kMaxCoordinate = 1e6;
// Smallest scene size (the diagonal of the scene box, task_scene_size), in task units.
inline constexpr double kMinSceneSize = 1e-6;
// The scene box may lie at most this many scene sizes from the origin (its farthest coordinate over its
// size): beyond, a double's rounding of a coordinate exceeds the contact tolerance of 1e-6 scene sizes.
inline constexpr double kMaxSceneOffset = 1e6;
// Every part is at least this fraction of the scene size thick (ten contact tolerances,
// kRegionOnSurfaceRelativeTolerance): a thinner part is below what the tolerances can resolve.
inline constexpr double kMinPartWidthRelative = 1e-5;
// eps_s, eps_p and step are at most this many scene sizes; step at least kMinStepRelative of the scene.
inline constexpr double kMaxErrorRelative = 1.0;
inline constexpr double kMinStepRelative = 1e-4;
// A spring's commanded position lies within this many scene sizes of the scene box (farther, use a damper).
inline constexpr double kMaxSpringReachRelative = 1e3;
// theta_v stays below this (pi/2): a velocity error of pi/2 or more may stop any motion.
inline constexpr double kMaxThetaV = std::numbers::pi / 2;
// The reason a theta_v out of range is refused (the loader's, and a widened one's in the verifier model).
std::string theta_v_range_reason(double theta_v);
// Coulomb coefficients up to this (a friction cone of 89.4 degrees).
inline constexpr double kMaxFriction = 100;
// A direction (damper, force cone) has at least this length before it is normalized.
inline constexpr double kMinDirectionLength = 1e-100;
// Sizes.
inline constexpr std::size_t kMaxParts = 20000;          // robot + environment + cspace parts
inline constexpr std::size_t kMaxConvexVertices = 1000;  // points of one convex part
inline constexpr std::size_t kMaxRegionPoints = 1000;    // points of one start/goal polygon
inline constexpr std::size_t kMaxGoalRegions = 1000;
inline constexpr std::size_t kMaxMotions = 1000;
inline constexpr std::size_t kMaxStrategyNodes = 1000;  // motions of one strategy
inline constexpr std::size_t kMaxTaskFileBytes = 64u << 20;

// The scene size: the diagonal of the scene box, which is the bounds box when given, else the bounding box
// of the C-space obstacles (cspace parts, or environment parts grown by the robot's extent), in either case
// together with the start and goal regions. For planar tasks only x and z count (y is the fixed extrusion).
double task_scene_size(const Task& task);

// The spring interpolation step when the file gives none (Uncertainty::step == 0): eps_p, or, when eps_p is
// below kMinStepRelative of the scene (perfect positioning included), kDefaultStepRelative of the scene.
inline constexpr double kDefaultStepRelative = 0.01;
void apply_scene_defaults(Task& task);

// Throws TaskError(task.source_file, key, reason) at the first value outside the ranges above that needs
// the whole scene to decide (part widths, error bounds, spring targets). Per-value limits (kMaxCoordinate,
// sizes) are checked while parsing.
void check_task_ranges(const Task& task);

// Width of a convex part: the smallest distance between two parallel planes enclosing it (over the x, z plane
// for planar tasks); 0 for a degenerate part.
double part_width(const ConvexPart& part, int dimension);

}  // namespace cmt

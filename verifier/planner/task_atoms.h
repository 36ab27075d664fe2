// The planner's start and goal in atoms (Buckley §6.3: "the start region is a top edge", "the goal region is
// the interior of the cube bottom").
#pragma once

#include <vector>

#include "models/loaded_task.h"

namespace cmt::planner {

// The atoms the task's start region lies in, less those that only bound another of them (the ends of a start
// edge, the edges of a start face: the thesis's start atoms are open; the verifier's check of a planned
// strategy runs from the closed region).
std::vector<int> start_atoms(const LoadedTask& task);

// The vertex centroid of a region (a point, a segment's middle, a polygon's vertex mean).
Vec3 region_centroid(const Region& region);

// Whether p lies in the closed region (a point, a segment or a convex planar polygon), within tol.
bool in_region(const Region& region, const Vec3& p, double tol);

// Per atom: its closure lies inside one of the goal regions (within the task's surface tolerance).
std::vector<bool> goal_atoms(const LoadedTask& task);

}  // namespace cmt::planner

// Cells of a start region for the teaching system's adaptive refinement (verifier/teaching/README.md): a
// region is split in two halves whose union is the region, so that a part of the start can be solved when
// the whole cannot.
#pragma once

#include <vector>

#include "models/task.h"

namespace cmt::teaching {

// The two halves of a region: a segment at its midpoint; a convex polygon by the plane through its vertex
// centroid across its longest vertex-to-vertex extent. A point (or a degenerate region) has no halves: the
// result is empty. Shared cut points are computed once, so the halves meet exactly (in doubles); their
// union differs from the polygon only by the rounding of the cut points, far inside the outward grid
// rounding a start set gets (ReachedSet::from_region).
std::vector<Region> split_region(const Region& region);

// The region's length (segment), area (polygon) or 0 (point): the measure reported as the solved share.
double region_measure(const Region& region);

}  // namespace cmt::teaching

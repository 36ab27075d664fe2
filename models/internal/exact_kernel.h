// Private to models/: the exact kernel shared by the C-space construction units. Not a public header (CGAL
// stays out of public headers to keep compile times down).
#pragma once

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>

#include <vector>

namespace cmt::exact {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using FT = Kernel::FT;
using Point2 = Kernel::Point_2;
using Point3 = Kernel::Point_3;
using Vector3 = Kernel::Vector_3;
using Plane3 = Kernel::Plane_3;

// An exact convex polygon in the plane, vertices counter-clockwise.
using Polygon2Points = std::vector<Point2>;

// One maximal region on an oriented plane, as produced by the Boolean stage: outer boundary CCW, holes CW.
struct RegionWithHoles {
  Polygon2Points outer;
  std::vector<Polygon2Points> holes;
};

// Boolean stage on one plane (Polygon_set_2, regularized): (union of `below`) minus (union of `above`),
// intersected with `clip` when `clip` is non-empty. Inputs are convex polygons in any orientation.
std::vector<RegionWithHoles> planar_region(const std::vector<Polygon2Points>& below,
                                           const std::vector<Polygon2Points>& above,
                                           const Polygon2Points& clip, bool use_clip);

// Splits a region into convex pieces, only where it is not convex: from each reflex vertex the incident edge
// most aligned with the plane's second axis is extended until it meets the boundary or an earlier cut (for a
// rectangle with a rectangular hole: two opposite hole sides extended to the walls, Buckley §6.3.3 L2634).
// Pieces are counter-clockwise with collinear points removed.
std::vector<Polygon2Points> convex_pieces(const RegionWithHoles& region);

}  // namespace cmt::exact

// Convex planar polygons in 3-D (floating point): clipping and area.
#pragma once

#include <vector>

#include "models/task.h"

namespace cmt {

// Intersection of two convex polygons lying in one plane with unit normal n (both counter-clockwise about n).
std::vector<Vec3> clip_convex_polygon(const std::vector<Vec3>& subject, const std::vector<Vec3>& clip,
                                      const Vec3& n);
double polygon_area(const std::vector<Vec3>& polygon, const Vec3& n);
// The part of a convex polygon (3 or more corners in order), a segment (2 points) or a point with
// d . x <= level (Sutherland-Hodgman on one plane).
std::vector<Vec3> clip_to_halfspace(const std::vector<Vec3>& points, const Vec3& d, double level);

}  // namespace cmt

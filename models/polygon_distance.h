// Euclidean distances to segments and convex planar polygons in 3-D (floating point).
#pragma once

#include "models/task.h"

namespace cmt {

double distance_to_segment(const Vec3& p, const Vec3& a, const Vec3& b);
// The closest distance between segments [p0, p1] and [q0, q1] (clamped closest points; Ericson, Real-Time
// Collision Detection §5.1.9).
double distance_between_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);
// `polygon` is convex and planar, counter-clockwise about the unit `normal`.
double distance_to_convex_polygon(const Vec3& p, const std::vector<Vec3>& polygon, const Vec3& normal);
// The unit normal about which a planar polygon's own vertex order is counter-clockwise (Newell's method).
Vec3 polygon_normal(const std::vector<Vec3>& polygon);

}  // namespace cmt

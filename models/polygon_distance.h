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
// The distance between two convex sets of dimension <= 2, each given by its points: one point, a segment (2),
// or a convex planar polygon (3+, counter-clockwise about its unit normal na or nb; ignored otherwise). It is
// attained at a vertex of one, between a pair of boundary edges, or (when they meet) where an edge of one
// crosses the other. +infinity when either is empty.
double distance_between_convex_sets(const std::vector<Vec3>& a, const Vec3& na, const std::vector<Vec3>& b,
                                    const Vec3& nb);
// The unit normal about which a planar polygon's own vertex order is counter-clockwise (Newell's method).
Vec3 polygon_normal(const std::vector<Vec3>& polygon);

}  // namespace cmt

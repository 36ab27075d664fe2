// Orthonormal frames of planes and about axes, laid out so that they turn with the task (docs/verifier.md
// "Invariance"): polygons and ray fans sampled in them map onto the turned task's.
#pragma once

#include <cmath>

#include "models/task.h"

namespace cmt {

// A right-handed orthonormal frame (u, w) of the plane with unit normal n: u = n x e_i / |n x e_i| for the
// world axis e_i least aligned with n (the lowest index on a tie), w = n x u. A quarter turn R of the world
// axes (a signed permutation with det +1) maps e_i to the axis least aligned with R n, so the frame of R n is
// (R u, R w) up to a common sign, or (for n along an axis, where two axes tie) a quarter turn in the plane:
// a regular polygon of 4k sides laid out at angles 2 pi j / 4k in it maps onto the turned task's polygon.
inline void plane_frame(const Vec3& n, Vec3* u, Vec3* w) {
  const Vec3 m = n.cwiseAbs();
  const int i = m.x() <= m.y() && m.x() <= m.z() ? 0 : m.y() <= m.z() ? 1 : 2;
  *u = n.cross(Vec3::Unit(i)).normalized();
  *w = n.cross(*u);
}

}  // namespace cmt

// Private to verifier/ .cc files: the in-plane displacements of the generalized damper on one face (Buckley
// Alg 4.3 sliding plus tangential flight), shared by the forward projection and the weak backprojection.
#pragma once

#include "models/cspace.h"

namespace cmt::face_geometry {

// Step A's in-plane sweep on one face: none, the whole face, or the wedge W of directions b_minus..b_plus.
struct Sweep {
  bool none = true, whole = false;
  Vec3 b_plus, b_minus;
  double far = 0;
};

// Buckley Alg 4.3 (via sliding_cone, damper.h) plus tangential flight: velocities tangent to the face (|v.n|
// <= sin theta_v) move the robot within the plane; such displacements lie in the wedge of half-angle
// acos(cos theta_v / |v_t|) about v_t, symmetric about the same axis as the sliding cone, so the larger
// half-angle covers both (and any mix: W is a convex cone).
Sweep face_sweep(const Face& f, const Vec3& v, double theta_v, double scale);

}  // namespace cmt::face_geometry

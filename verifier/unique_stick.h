// Robot force directions for which sticking is the ONLY Coulomb solution at an atom (Buckley §2.3 refined).
//
// Buckley's edge and vertex cones are Minkowski sums of the face cones: a force in the sum admits a static
// solution, so outside the (outer) sum sticking is impossible ("never" is sound). But inside the sum,
// rigid-body Coulomb friction can also admit sliding: at a concave edge a force between the kinetic limit |t|
// <= mu1 N1 + mu2 N2 and the sum cone (which adds wedging) may stick or slide (observed in MuJoCo by the
// friction calibration, sim/calibration.h). So "must stick" needs stick to be the unique solution:
//   face: inside the face cone.
//   concave edge, perpendicular faces n1, n2, edge direction e (f = −N1 n1 − N2 n2 + t e): stick is unique
//   iff
//     N1, N2 >= 0 and |t| <= mu1 N1 + mu2 N2 (no sliding along the edge; with both faces pressed neither can
//     separate), or N2 <= 0 (face 2 separates) and f inside face 1's cone, or symmetrically.
//   box corner (three mutually perpendicular faces): pressing into all three (every N_i >= 0).
//   anything else (convex, flat, non-perpendicular or non-manifold edges, other vertices): inside every
//   face's
//     cone, whichever contact the physics picks.
// margin(f) is a lower bound on the angle from f to the set's boundary (<= 0 when f is outside), built from
// the supporting planes and rim circles of the boundary pieces.
#pragma once

#include <vector>

#include "models/cspace.h"
#include "models/friction_cone.h"

namespace cmt {

class UniqueStick {
 public:
  static UniqueStick for_atom(const CSpace& cspace, int atom_id);
  static UniqueStick face(const Vec3& normal, double mu);
  static UniqueStick concave_edge(const Vec3& n1, double mu1, const Vec3& n2, double mu2);
  static UniqueStick corner(const Vec3& n1, const Vec3& n2, const Vec3& n3, std::vector<double> mus = {});
  static UniqueStick intersection(const std::vector<Vec3>& normals, const std::vector<double>& mus);

  double margin(const Vec3& force) const;

  // Convex sets of force directions that keep sticking the only Coulomb solution under a direction error of
  // `angle`: every direction within `angle` of a member lies in the unique-stick set. Returned as a union
  // (outer list) of intersections of circular cones (inner lists); an alternative whose cone would narrow to
  // nothing is left out. Faces, and atoms of the intersection kind: ∩ cone(−n_i, phi_i − angle).
  // Perpendicular concave edges: the kinetic wedge (its four bounding planes, each narrowed to cone(−w, pi/2
  // − angle)), or either face's own narrowed cone (inside a face's cone neither that face nor the edge can
  // slide: the other wall only adds normal force and friction against the sliding direction). Concave box
  // corners: pressing into all three faces by at least `angle`, or any one face's narrowed cone (the same
  // argument).
  std::vector<std::vector<CircularCone>> must_cones(double angle) const;

 private:
  enum class Kind { kIntersection, kConcaveEdge, kCorner };
  Kind kind_ = Kind::kIntersection;
  std::vector<Vec3> normals_;
  std::vector<double> mus_;
  Vec3 e_ = Vec3::Zero();
};

}  // namespace cmt

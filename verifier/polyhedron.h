// Convex polyhedra in half-space form, possibly unbounded, possibly complemented: the shape of sticking
// regions of commanded positions (Buckley §6.7.4) and of sensed-position sets (§4.5).
#pragma once

#include <vector>

#include "models/task.h"

namespace cmt {

struct HalfSpace {
  Vec3 normal;        // unit
  double offset = 0;  // normal . x <= offset
};

struct Polyhedron {
  enum class Kind { kEmpty, kConvex, kComplement, kEverything };
  Kind kind = Kind::kEmpty;
  std::vector<HalfSpace> halfspaces;  // kConvex: their intersection; kComplement: the complement of it

  static Polyhedron everything() { return {Kind::kEverything, {}}; }
  static Polyhedron nothing() { return {Kind::kEmpty, {}}; }
  bool contains(const Vec3& p) const;
  // Every half-space moved outward (delta > 0) or inward (delta < 0) by |delta|: P ⊕ ball(delta) is contained
  // in the grown set (exact up to rounding at P's edges), P ⊖ ball(-delta) equals the shrunk set for convex
  // P.
  Polyhedron offset(double delta) const;
};

// Relative slack in the facet-validity test of hull_plus_cone (see there).
inline constexpr double kPolarSlack = 1e-12;

// conv(points) + cone(rays) in half-space form, exactly (up to floating-point rounding of the normals): the
// candidate facet normals are all cross products of pairs from {rays} ∪ {point differences}, kept when they
// are valid (u . r <= kPolarSlack for every ray r), with offset max over points of u . x. Every facet of the
// set is spanned by two such vectors, so the intersection is the set itself. Throws if the set is all of R^3.
Polyhedron hull_plus_cone(const std::vector<Vec3>& points, const std::vector<Vec3>& rays);

}  // namespace cmt

// The friction cone of an atom (Buckley §2.3, L571-614): a face's circular cone, the sum of its two faces'
// cones for an edge, the sum of all its faces' cones for a vertex.
#pragma once

#include "models/cspace.h"
#include "models/friction_cone.h"
#include "verifier/unique_stick.h"

namespace cmt {

FrictionCone atom_friction_cone(const CSpace& cspace, int atom_id);
// The faces whose cones make up the atom's cone (the face itself for a face).
std::vector<int> atom_faces(const CSpace& cspace, int atom_id);
// The atom's points: face polygon, edge ends, or the vertex.
std::vector<Vec3> atom_points(const CSpace& cspace, int atom_id);

// Every atom's friction cone, built once per C-space and shared read-only (the polyhedral approximations
// inside are built on first use, thread-safely). Immutable like the C-space it describes.
class AtomCones {
 public:
  explicit AtomCones(const CSpace& cspace);
  // The friction cone (Minkowski sum for edges and vertices): sticking is possible only inside it.
  const FrictionCone& operator[](int atom_id) const { return cones_[atom_id]; }
  // Where sticking is the only Coulomb solution (verifier/unique_stick.h): "must" is decided against it.
  const UniqueStick& unique(int atom_id) const { return unique_[atom_id]; }
  int size() const { return static_cast<int>(cones_.size()); }

 private:
  std::vector<FrictionCone> cones_;
  std::vector<UniqueStick> unique_;
};

}  // namespace cmt

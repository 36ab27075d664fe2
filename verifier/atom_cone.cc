#include "verifier/atom_cone.h"

#include <cmath>

namespace cmt {

std::vector<int> atom_faces(const CSpace& c, int atom_id) {
  switch (c.atom_kind(atom_id)) {
    case AtomKind::kFace:
      return {atom_id};
    case AtomKind::kEdge:
      return c.edges()[c.atom_index(atom_id)].faces;
    case AtomKind::kVertex:
      return c.vertices()[c.atom_index(atom_id)].faces;
  }
  return {};
}

std::vector<Vec3> atom_points(const CSpace& c, int atom_id) {
  switch (c.atom_kind(atom_id)) {
    case AtomKind::kFace:
      return c.faces()[c.atom_index(atom_id)].polygon;
    case AtomKind::kEdge: {
      const Edge& e = c.edges()[c.atom_index(atom_id)];
      return {e.a, e.b};
    }
    case AtomKind::kVertex:
      return {c.vertices()[c.atom_index(atom_id)].point};
  }
  return {};
}

FrictionCone atom_friction_cone(const CSpace& c, int atom_id) {
  std::vector<CircularCone> generators;
  for (int f : atom_faces(c, atom_id)) {
    const Face& face = c.faces()[f];
    const CircularCone g{face.normal, std::atan(face.friction)};
    // Coplanar faces (a flat edge, a T-junction) contribute the same cone once.
    bool seen = false;
    for (const CircularCone& h : generators)
      seen = seen || (h.axis == g.axis && h.half_angle == g.half_angle);
    if (!seen) generators.push_back(g);
  }
  return FrictionCone::sum(std::move(generators));
}

AtomCones::AtomCones(const CSpace& cspace) {
  cones_.reserve(cspace.atom_count());
  for (int id = 0; id < cspace.atom_count(); ++id) {
    cones_.push_back(atom_friction_cone(cspace, id));
    unique_.push_back(UniqueStick::for_atom(cspace, id));
  }
}

}  // namespace cmt

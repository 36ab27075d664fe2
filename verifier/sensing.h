// Position and force sensing (Buckley §4.5, Def 5.1, Def 6.1, §6.7.6-6.7.7).
#pragma once

#include <functional>

#include "models/cspace.h"
#include "models/friction_cone.h"
#include "verifier/polyhedron.h"

namespace cmt {

// Sensed positions of an atom: atom ⊕ ball(eps_s), as a convex polyhedral over-approximation (supporting
// planes in the atom's own normal directions and 26 lattice directions, each moved out by eps_s).
Polyhedron sensed_positions(const CSpace& cspace, int atom_id, double eps_s);

// Sensed force directions of an atom: its friction cone widened by theta_f (§6.7.7).
FrictionCone sensed_forces(const CSpace& cspace, int atom_id, double theta_f);

// Euclidean distance between the closures of two atoms.
double atom_distance(const CSpace& cspace, int atom_a, int atom_b);

// A lower bound on the smallest angle between a reaction force of atom a and one of atom b (0 if the cones
// may meet). Uses the outer cones, so "larger than x" is certain.
double force_angle_lower_bound(const CSpace& cspace, int atom_a, int atom_b);
// The same for two cones (of atoms in different C-spaces, e.g. two slices of a task with model error).
double force_angle_lower_bound(const FrictionCone& a, const FrictionCone& b);

// Def 6.1: two atoms are disambiguable when their closest points are more than 2 eps_s apart or their closest
// reaction forces differ by more than 2 theta_f. Atoms sharing a face are never force-disambiguable (§6.4.1).
bool disambiguable(const CSpace& cspace, int atom_a, int atom_b, double eps_s, double theta_f);
// The same with the atoms' friction cones (atom_friction_cone) from `cone`, asked only when the forces
// decide: for callers that test many pairs and keep each atom's cone.
bool disambiguable(const CSpace& cspace, int atom_a, int atom_b, double eps_s, double theta_f,
                   const std::function<const FrictionCone&(int atom)>& cone);
// Def 5.1 for atoms: some pair of points within 2 eps_s whose friction cones are within 2 theta_f.
inline bool confusable(const CSpace& cspace, int atom_a, int atom_b, double eps_s, double theta_f) {
  return !disambiguable(cspace, atom_a, atom_b, eps_s, theta_f);
}

}  // namespace cmt

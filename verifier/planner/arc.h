// Arcs of Buckley's state graph (§6.6.2): a set of commanded motions from an atom (a state) with the atoms
// where they may terminate, and their composition into a reliable set (Theorems 6.1–6.3, Table 6.4).
#pragma once

#include <string>
#include <vector>

#include "verifier/planner/cposition_set.h"

namespace cmt::planner {

// A type 1 arc (termination by sticking, §6.7.1): the commanded positions and the atoms where a motion
// commanded to one of them may stop (targets, ascending atom ids; the free-space atom is the C-space's
// atom_count()).
struct Arc {
  std::vector<int> targets;
  CPositionSet cpositions;
};

// The sorted union of two target lists.
std::vector<int> target_union(const std::vector<int>& a, const std::vector<int>& b);

// Arc composition (§6.6.2, "Type 1 Arcs"): the weak arcs Λ, a complete set, are inserted one by one into a
// list Ψ2 that stays nonoverlapping: α is composed with each β of Ψ2 (Table 6.4: αβ = (C_α ∩ C_β, T_α ∪
// T_β), α⁻ = (C_α − C_β, T_α), β⁻ = (C_β − C_α, T_β)); β is replaced by αβ and β⁻, and α by α⁻. Arcs with
// identical targets are merged first (they may overlap, Theorem 6.2), and again at the end. The result is
// complete and nonoverlapping up to the pieces' shared boundaries (Theorem 6.3), hence reliable (6.1).
// Arcs with no commanded positions are dropped.
std::vector<Arc> compose_type1(const std::vector<Arc>& weak_arcs);

// Arcs with identical targets merged into one (their cpositions united), in the order of first appearance.
std::vector<Arc> merge_identical_targets(const std::vector<Arc>& arcs);

}  // namespace cmt::planner

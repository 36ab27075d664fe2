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

// A type 2 arc (termination by sensed position, §6.6.2, §6.7.6): commanded positions, the set of sensed
// positions the motion terminates on, and the atoms where it may stop. A motion commanded to c with
// termination set S may stop in atom i of a weak arc (C_i, S_i, {i}) when c is in C_i and S meets S_i.
struct Type2Arc {
  std::vector<int> targets;
  CPositionSet cpositions;
  CPositionSet spositions;
};

// Type 2 arc composition (§6.2 Table 6.2, generalised by incremental insertion as compose_type1): the weak
// arcs are inserted one by one; α composed with each β of the list gives (C_α ∩ C_β, S_α ∩ S_β, T_α ∪ T_β),
// β's parts (C_β − C_α, S_β, T_β) and (C_β, S_β − S_α, T_β), and α's remainders (C_α − C_β, S_α, T_α) and
// (C_α, S_α − S_β, T_α), each of which goes on to the next β. Arcs may overlap where their targets agree
// (Theorem 6.2: Table 6.2's second and third arcs do); exact duplicates and arcs with an empty set are
// dropped. Every composed arc (C, S, T) is sound (for each weak atom i outside T, C misses C_i or S misses
// S_i, up to shared boundaries: no motion of the arc may stop there) and the arcs are complete (a commanded
// position c of some C_i with a sensed position s of that S_i lies in an arc together). The number of arcs
// grows exponentially with the weak arcs (§6.8): for small inputs; the planner's search explores cells
// instead (simulation.h).
std::vector<Type2Arc> compose_type2(const std::vector<Type2Arc>& weak_arcs);

}  // namespace cmt::planner

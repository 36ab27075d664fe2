// Buckley's simulation of an atom (§6.7) for type 1 arcs (termination by sticking) under the generalized
// spring: which atoms a motion commanded to p may stop in, from a set of start atoms, and a convex set of
// commanded positions around p that stop nowhere else (an arc's cpositions). docs/planner.md, "Simulation".
//
// The sets, each Buckley's or an over-approximation of it (a larger weak set only makes arcs less confident,
// never wrong); the lift-off rule of connected reaching is the thesis's and does not bound paths that
// overshoot (docs/planner.md), which the search's verifier check covers:
//   - stop in B (§6.7.1): B's weak sticking region (verifier/spring.h);
//   - leave B (§6.7.2): p outside S_B, the strong sticking region of B, and in weak_reach(B, B'). Every atom
//     B' ≠ B is a candidate (Buckley drops unconnected edges and vertices as unlikely; a sound set cannot);
//   - direct reaching (§6.7.5), weak, ignoring obstacles (subtracting the obstacles' strong reaching sets
//     only shrinks the weak set, so leaving it out is sound and looser): see weak_reach below;
//   - free space: the commanded positions within spring_rest_radius of free space (the robot may come to
//     rest there), whose target is the free-space atom.
// For one p these sets make a graph on the atoms (B → B' when p leaves B and may reach B'); the atoms
// reachable from the start where p may stick are the targets. Buckley's recursion computes, for every
// target, the whole set of such p (with waitlists for cycles, L2240–2254); here the arrangement of the same
// sets is explored at chosen commanded positions instead: the cell of p is the convex set where every
// missing edge of the graph stays missing, every reachable atom where p does not stick stays so, and p stays
// out of free space, so every commanded position in it has targets among p's (search.h picks the p).
//
// Goal stops (goal_stops.h): with partial goal faces, sticking on such a face where the goal surely holds the
// sticking points (goal_sticking) is a stop at the goal-stop atom (goal_stop_atom(), after the free-space
// atom), sticking elsewhere on it a stop at the face; with P_s (type 2 arcs, §6.7.6), every reached atom
// that P_s may sense also stops at the goal-stop atom, whatever p. Leaving an atom is modelled from the whole
// atom, as for sticking (a type 2 motion that crosses its goal stops there first; the sets do not use it:
// sound, looser; the verifier's sensing termination makes the same choice).
#pragma once

#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "models/cspace.h"
#include "verifier/planner/arc.h"
#include "verifier/planner/goal_stops.h"

namespace cmt::planner {

// The box of commanded positions the planner considers: the atoms' bounding box grown on every side by
// its diagonal (a spring motion commanded further away behaves like one commanded on the box, only
// faster). Every arc's cpositions lie in it; completeness is relative to motions commanded inside it.
AxisBox planner_domain(const CSpace& cspace);
// The bounding box of the atoms.
AxisBox atoms_box(const CSpace& cspace);

class AtomSimulation {
 public:
  AtomSimulation(const CSpace& cspace, const Uncertainty& u, GoalStops goal_stops = {});

  int free_atom() const { return cspace_.atom_count(); }
  // The target of stops surely inside the goal on atoms that are not goal atoms.
  int goal_stop_atom() const { return planner::goal_stop_atom(cspace_); }
  const GoalStops& goal_stops() const { return goal_stops_; }
  const AxisBox& domain() const { return domain_; }
  // The atoms where a motion commanded to p may stop when it starts in one of `start` (ascending: the
  // free-space atom when it may come to rest in free space, then the goal-stop atom, come last).
  std::vector<int> targets_at(const std::vector<int>& start, const Vec3& p);
  // A convex set of commanded positions around p (p on it; empty when p lies on the boundary of a set that
  // decides) whose every position has targets among targets_at(start, p).
  CPositionSet cell_at(const std::vector<int>& start, const Vec3& p);

  const CPositionSet& weak_sticking(int atom);
  const CPositionSet& strong_sticking(int atom);
  // The part of the weak sticking region of a partial goal face where every sticking point lies in the goal
  // (goal_stops.h); empty for other atoms.
  const CPositionSet& goal_sticking(int atom);
  // Commanded positions from which the robot, anywhere in A, may reach B directly (§6.7.5, weak):
  //   connected (one bounds the other): for a common face F, p at most eps_s in front of F's plane (else
  //   the pull lifts it off F) and on B's side of each separating plane between A and B, moved toward A by
  //   eps_t + eps_o (the via-point paths stay within eps_t of the segment to p + eps_o u, App. B; the
  //   thesis moves the planes by eps_t only);
  //   unconnected: p with seg[x, p + eps_o u] within eps_t of B for some x in A: the closure of
  //   B_t + cone(B_t − A), B_t = B grown by an eps_t cube, grown by eps_o. Where A and B touch without
  //   bounding one another (faces at an edge), A's part within 2 eps_t + eps_o of the shared boundary is
  //   left to the path through the boundary atom (the thesis's atom-level model; the verifier's check of
  //   every planned motion covers the exact starts).
  const CPositionSet& weak_reach(int from, int to);
  const CPositionSet& free_rest();

 private:
  // Breadth first over p's graph from the start atoms: at_atom(b) for each reached atom (false: no way on
  // from b), then at_pair(b, next, edge) for every other atom (edge: p may reach it from b).
  void traverse(const std::vector<int>& start, const Vec3& p, const std::function<bool(int)>& at_atom,
                const std::function<void(int, int, bool)>& at_pair);
  bool senses(int atom) const;  // a type 2 motion may stop on it by sensing (GoalStops::senses)
  CPositionSet connected_reach(int from, int to) const;
  CPositionSet flight_reach(int from, int to) const;

  const CSpace& cspace_;
  Uncertainty u_;
  GoalStops goal_stops_;
  AxisBox domain_;
  double eps_t_ = 0, eps_o_ = 0;
  // Made on first use: per atom, and per (from, to) at from x atom_count + to. Never resized, so the
  // references handed out stay valid.
  std::vector<std::optional<CPositionSet>> weak_stick_, strong_stick_, goal_stick_, reach_;
  std::optional<CPositionSet> free_rest_;
};

// Whether one atom's closure holds the other (a face and its edges and vertices, an edge and its ends):
// Buckley's "connected".
bool atoms_connected(const CSpace& cspace, int a, int b);

}  // namespace cmt::planner

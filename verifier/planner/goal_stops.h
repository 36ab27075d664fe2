// Stops inside a goal that covers part of a face, and the sensed positions of a goal (Buckley §6.7.6, type 2
// arcs). Buckley's goals are whole atoms ("the interior of the cube bottom", §6.3.2); a task's goal is a
// closed polygon, so a goal such as the bottom inset from its edges holds no atom's closure, and the planner
// counts a stop as a goal stop when it surely lies in the goal polygon (docs/planner.md, "Goal stops"):
//   - sticking on a face F partly in the goal: a spring commanded to p sticks on F only where p lies in the
//     negative friction cone widened by theta_v and grown by eps_s (§6.7.4), i.e. within
//     rho = (d + eps_s) tan(phi + theta_v) + eps_s of p's projection on F, d the depth of p behind F. Every
//     side m . x <= c of the goal polygon then holds all such points when
//     m . p + tan(phi + theta_v) d <= c - eps_s (1 + tan(phi + theta_v)): linear in p (goal_sticking);
//   - sensing (type 2): the motion stops when in contact with its sensed position in P_s. P_s is built so
//     that every contact point within eps_s of it lies in the goal: such stops are goal stops, wherever the
//     robot touches P_s grown by eps_s.
#pragma once

#include <vector>

#include "models/loaded_task.h"
#include "verifier/polyhedron.h"

namespace cmt::planner {

// The planner's target for stops surely inside the goal on atoms that are not goal atoms: the id after the
// free-space atom (atom_count()).
inline int goal_stop_atom(const CSpace& cspace) { return cspace.atom_count() + 1; }

// A goal polygon lying on a face that is not a goal atom: the face's atom id and the polygon's sides as
// in-plane half-spaces (m . x <= c, m a unit vector in the face's plane).
struct PartialGoalFace {
  int atom = -1;
  std::vector<HalfSpace> sides;
};

// The task's goal polygons that lie on a face (within the surface tolerance, overlapping it with positive
// area) whose closure is not in the goal.
std::vector<PartialGoalFace> partial_goal_faces(const LoadedTask& task, const std::vector<bool>& goal_atom);

// The margin, times the scene scale, by which P_s keeps clear of the points it must not sense: above the
// verifier's own growth of the boxes (kSensingBoxRelativeSlack) and any rounding.
inline constexpr double kSensedSetRelativeMargin = 1e-6;

// P_s for a type 2 motion that ends in the goal: per goal polygon on an axis-aligned plane, one axis box, the
// largest axis rectangle centred in the polygon (found by bisection on its scale) whose box grown by
// eps_s + margin stays a margin inside every side (an axis-parallel side moves in by eps_s + 2 margin), 2
// eps_s thick across the plane: a robot at a point of the rectangle shrunk by eps_s surely senses a
// position in it. A box is kept only when every contact point (of any atom) within eps_s + margin of it
// lies in the goal (within the surface tolerance): a wall along the goal's edge stays a margin clear. Empty
// when no goal polygon gives one.
std::vector<AxisBox> goal_sensed_positions(const LoadedTask& task);

// Per atom: whether the atom has a point within eps_s + margin of one of the boxes (a type 2 motion may stop
// there by sensing).
std::vector<bool> sensing_atoms(const CSpace& cspace, const std::vector<AxisBox>& boxes, double eps_s);

// The goal stops of a plan: sticking on partial goal faces, and P_s with the atoms it may stop on.
struct GoalStops {
  std::vector<PartialGoalFace> partial_faces;
  std::vector<AxisBox> sensed_positions;  // P_s (type 2); empty for sticking termination
  std::vector<bool> senses;               // per atom, sensing_atoms() of P_s; empty without P_s
};

}  // namespace cmt::planner

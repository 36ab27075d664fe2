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
//     robot touches P_s grown by eps_s;
//   - sensing positions and forces (type 3): the motion stops when its sensed position is in P_s and its
//     sensed force direction in F_s. F_s holds the goal faces' friction cones widened by theta_f, so a stop
//     on the goal face passes the force test; P_s need then keep clear only of the contacts whose widened
//     cones may meet F_s (a wall beside a goal floor cannot sense the floor's force), and may reach the
//     goal's edges where a type 2 P_s must stay eps_s inside them.
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
// With F_s (`forces`, type 3) the contact points whose atom's friction cone widened by theta_f cannot meet
// F_s are not sensed, and each side of a goal polygon is either inset as for type 2 or not (the box then
// reaches within a margin of it: a wall there cannot sense the goal's force): of the boxes of every such
// choice that sense the goal only, the largest.
std::vector<AxisBox> goal_sensed_positions(const LoadedTask& task, const std::vector<ForceCone>& forces = {});

// The margin (radians) by which F_s clears the rim of a goal face's widened friction cone, so that the
// verifier counts every stop on the face as surely sensed: above its kForceContainmentMargin plus the
// rounding of the angle it computes with acos between two unit normals (~1.5e-8 for a dot product one ulp
// below 1).
inline constexpr double kSensedForceMargin = 1e-7;

// F_s for a type 3 motion that ends in the goal: per goal polygon on a face of the C-space, the cone about
// the face's friction-cone axis (the reaction's mean direction) whose half angle is the friction angle plus
// theta_f and kSensedForceMargin; one cone per distinct face direction.
std::vector<ForceCone> goal_sensed_forces(const LoadedTask& task);

// Per atom: whether the atom has a point within eps_s + margin of one of the boxes and, with F_s, a friction
// cone widened by theta_f that may meet one of its cones (a type 2 or 3 motion may stop there by sensing).
std::vector<bool> sensing_atoms(const LoadedTask& task, const std::vector<AxisBox>& boxes,
                                const std::vector<ForceCone>& forces = {});

// The goal stops of a plan: sticking on partial goal faces, and P_s (and F_s) with the atoms they may stop
// on.
struct GoalStops {
  std::vector<PartialGoalFace> partial_faces;
  std::vector<AxisBox> sensed_positions;  // P_s (types 2 and 3); empty for sticking termination
  std::vector<ForceCone> sensed_forces;   // F_s (type 3); empty otherwise
  std::vector<bool> senses;               // per atom, sensing_atoms() of P_s and F_s; empty without P_s
};

}  // namespace cmt::planner

// Sensing termination of a motion (Buckley §3.1.2 termination types 2 and 3, §4.5): the reached contact
// points that are weakly consistent (Def 4.1) with the motion's sets P_s (sensed positions) and F_s (sensed
// force directions), which Alg 4.1 step 4 adds to the weak sticking points. docs/verifier.md, "Sensing
// termination (§4.5)".
#pragma once

#include "models/loaded_task.h"
#include "verifier/atom_cone.h"
#include "verifier/reached_set.h"

namespace cmt {

// Every P_s box is grown by eps_s plus this fraction of the scene scale before clipping: the slack covers the
// double rounding of the grown bounds and of edge parameters, and turns a plane that only touches the box
// into a thin 2-D window (both are growth, so sound).
inline constexpr double kSensingBoxRelativeSlack = 1e-9;

// The points of `reached` where motion `m` may stop by sensing (its weakly consistent set T_w ∩ reached):
//   P_s given: reached ∩ ∪_boxes (box grown by eps_s), a superset of reached ∩ (P_s ⊕ ball(eps_s));
//   F_s given: only atoms whose friction cone widened by theta_f may meet some cone of F_s (the sensed force
//   is the reaction force, inside the atom's cone, turned by at most theta_f);
//   both: both filters; neither: empty (sticking termination only).
// Strongly consistent sets (T_s, which would stop the projection early) are not used: sound, looser.
ReachedSet sensing_termination(const LoadedTask& task, const AtomCones& cones, const Motion& m,
                               const ReachedSet& reached);

// The same for any sensing test of that form (a motion's termination sets, a conditional branch's test,
// §4.2): the points of `set` where some sensor reading within the error bounds passes `test` (Def 4.1,
// weakly consistent). Empty when the test gives neither set.
ReachedSet weakly_consistent(const LoadedTask& task, const AtomCones& cones, const MotionTermination& test,
                             const ReachedSet& set);

// `set` less points where every sensor reading within the error bounds surely passes `test` (Def 4.2,
// strongly consistent), never removing a point where some reading fails it:
//   position: the sensing ball lies in one box, i.e. the point is in the box shrunk by eps_s on every axis
//   (exact for a Euclidean ball in an axis box), shrunk further by kSensingBoxRelativeSlack x scale;
//   force: only face atoms whose friction cone widened by theta_f lies inside one cone of F_s (the reaction
//   force at rest is in the cone; edges and vertices are never removed: their sums are not tested for
//   containment), with kForceContainmentMargin to spare;
//   both: the position removal on those faces only.
ReachedSet without_strongly_consistent(const LoadedTask& task, const AtomCones& cones,
                                       const MotionTermination& test, const ReachedSet& set);

// Angle (radians) by which a widened face cone must clear the rim of an F_s cone to count as inside it: far
// above the rounding of the double angle formulas, far below any angle a task gives.
inline constexpr double kForceContainmentMargin = 1e-9;

}  // namespace cmt

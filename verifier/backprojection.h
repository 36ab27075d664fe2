// Weak and strong backprojections of one generalized-damper motion (Buckley §5.4.2-5.4.3, Alg 5.2): the
// contact points from which the motion might reach a set, and those from which it surely ends in a target.
// The reversal of the forward projection (verifier/damper_projection.h) under the same first-order model:
// velocities anywhere in cone(v, theta_v), switching freely; sliding by Alg 4.3 and tangential flight (the
// face's sweep wedge); straight-line flight with occlusion by single occluders.
#pragma once

#include "models/loaded_task.h"
#include "verifier/atom_cone.h"
#include "verifier/reached_set.h"
#include "verifier/spring_projection.h"

namespace cmt {

// W_m(from), Alg 5.2: every contact point from which the damper motion v might reach `from` (an
// over-approximation). Worklist fixpoint over the ReachedSet: each newly added part is processed once,
//  - backsliding: on a face that is not must-stick, the part swept back by the face's wedge (Alg 4.3 with
//    tangential flight), clipped to the face; along an edge, the rest of the edge behind the part in each
//    direction the robot may slide along it; at a vertex, the whole of each incident edge that may slide
//    toward it;
//  - straight lines: the flight of the part along cone(-v, theta_v) (the cone of Fig 5.14 reversed), kept in
//    front of its face (at an edge, of either face if convex, of both if not), hitting faces from
//    which some admissible velocity lifts off; occluded by single occluders as in the forward flight;
//  - closure: a face part's boundary on the face's edges and vertices (the same points).
// Falls back to every atom (sound) after kMaxBackprojectionSteps work items.
struct WeakBackprojection {
  ReachedSet weak;
  bool fallback = false;
  int steps = 0;
};
inline constexpr int kMaxBackprojectionSteps = 200000;
// A finished fixpoint's result: `weak` as reached, or every atom when `capped` (the step cap was hit).
WeakBackprojection finish_weak_backprojection(ReachedSet weak, bool capped, int steps);
WeakBackprojection weak_backproject_damper(const LoadedTask& task, const AtomCones& cones,
                                           const ReachedSet& from, const Vec3& v);

// Strong backprojection S_m(X) = complement of W_m(B) (§5.4.2), B = the points outside the target X where the
// motion may stop: every point of an atom whose damper class is must or may (with `stop_relative_speed` as in
// forward_project_damper: slow slides count as stops) that is not in X. `strong` is the whole C-space surface
// less W_m(B) grown by kBackprojectionRelativeMargin x the scene scale: the closed set `strong` keeps that
// distance from every point that might reach B, far above the region kernel's rounding (1.5 cells of 2^-36
// scale) and the forward projection's own outward margins (umbras shrunk by 1e-9 of the scale, which a
// corner of an occluder and the divergence of rays magnify), so that the forward projection of `strong`
// stays out of B too.
// Under the first-order damper model a motion from a point of `strong` never stops outside X; that it stops
// at all is the forward projection's business (slide_forever, may_not_terminate), so callers that certify a
// pre-image still verify it forward (verifier/teaching).
inline constexpr double kBackprojectionRelativeMargin = 1e-6;
struct DamperBackprojection {
  ReachedSet base;    // B
  ReachedSet weak;    // W_m(B)
  ReachedSet strong;  // S_m(X)
  bool fallback = false;
  int steps = 0;
};
// `margin` (task units, >= kBackprojectionRelativeMargin x scale; 0 takes that): a caller that runs S in the
// rollouts passes their contact resolution (experiments: the contact lift), since their contact cannot tell a
// robot that close to W from one in it.
DamperBackprojection backproject_damper(const LoadedTask& task, const AtomCones& cones,
                                        const ReachedSet& target, const Vec3& v,
                                        double stop_relative_speed = 0, double margin = 0);

// Weak and strong backprojections of one generalized-spring motion commanded to p (Buckley §5.4.4, Alg 5.2)
// under the via-point model (App. B, SpringModel::kViaPoint: the model of the position form), reversing the
// forward projection's pointwise relations (spring_projection.h). With r = eps_t + eps_o, a path from x
// toward p stays within r of seg[x, p] (the eps_t cylinder about the segment to p + eps_o u):
//  - straight lines (Figs 5.15-5.17): x may reach a part P when seg[x, p] meets P ⊕ cube(r), the set
//    K + cone(K − p) of contact points behind K as seen from p (K = P ⊕ cube(r)); face points only where the
//    robot may leave the face (outside its no-leave disk about p', as forward_project_spring); occlusion is
//    not subtracted (spring paths bend: sound, looser, as the forward flight);
//  - backsliding on a face F (Fig 5.18): points of F whose slide toward p'_F (the projection of p on F's
//    plane) passes within r of P, on faces where the robot may stay; guaranteed sticking on the way is not
//    subtracted (sound, looser);
//  - along an edge: points whose slide toward q (the projection of p on the edge's line, either way within
//    the forward projection's half-width about q) crosses P;
//  - closure: a face part's boundary on the face's edges and vertices.
// Falls back to every atom (sound) after kMaxBackprojectionSteps work items.
WeakBackprojection weak_backproject_spring(const LoadedTask& task, const ReachedSet& from, const Vec3& p);

// S_p(X) = the surface less W_p(B) grown by the margin (as backproject_damper), B = the points outside X
// where the motion may stop: the termination of the via-point forward projection from the whole surface, and
// the whole of each face or edge where it may slide forever. When the robot may come to rest in free space
// (the rest ball about p meets free space), every path may end there (all of them end near p): W is the whole
// surface and S is empty.
struct SpringBackprojection {
  ReachedSet base;         // B
  ReachedSet weak;         // W_p(B)
  ReachedSet strong;       // S_p(X)
  bool free_rest = false;  // B holds the free-space rest ball about p
  bool fallback = false;
  int steps = 0;
};
SpringBackprojection backproject_spring(const LoadedTask& task, const ReachedSet& target, const Vec3& p,
                                        double margin = 0);

// The points of `set` not in `target`: face regions by their difference on the grid, edge intervals cut,
// vertices dropped (segments and points on faces are kept: a superset).
ReachedSet points_outside(const ReachedSet& set, const ReachedSet& target);

// The closed complement of `set` on the C-space surface, kept `margin` (task units) away from it: whole faces
// less the set's face parts and its edge and vertex points grown by margin, whole edges less its intervals
// grown by margin (and less the ends near its vertices), the vertices farther than margin from it.
ReachedSet surface_complement(const ReachedSet& set, double margin);

}  // namespace cmt

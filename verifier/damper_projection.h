// Forward projection and sticking termination of one generalized-damper motion (Buckley ch. 4, Alg 4.1 with
// Alg 4.3 for sliding), following docs/forward-projection-design.md steps A-F. Sound: `termination` contains
// every point where a damper motion with velocity anywhere in cone(v, theta_v), switching freely, can stop
// by sticking; every approximation adds reachable points.
#pragma once

#include <vector>

#include "models/loaded_task.h"
#include "verifier/atom_cone.h"
#include "verifier/reached_set.h"

namespace cmt {

struct DamperProjection {
  ReachedSet reached;      // F_m(S): every contact point reachable from the start (the start included)
  ReachedSet termination;  // T_m(S): the reached points of atoms whose damper class is must or may
  // No reached atom can stick: the motion may never terminate (reported as a failure).
  bool may_not_terminate = false;
  // Reached faces and edges where the motion may slide forever (verifier/slide_forever.h; a failure).
  std::vector<int> slide_forever = {};
  // The fixpoint hit kMaxFixpointSteps and fell back to "every atom is reached" (sound, uninformative).
  bool fallback = false;
  int steps = 0;  // work items processed
};

// Work items (a face's new region, an edge's new intervals, a vertex) processed before the fallback.
inline constexpr int kMaxFixpointSteps = 200000;

// `stop_relative_speed` (kappa, >= 0): termination also holds the atoms where the robot may slide slower than
// kappa times its commanded speed (a stop rule that counts slow slides as sticking, like the rollouts'
// controllers/termination.h). The sliding speed is at least |v_a| sin(angle(−v_a, FC)) (the reaction lies in
// the friction cone, so v_a minus the velocity is in it), hence such atoms are those with a velocity within
// theta_v + asin(kappa) of the friction cone (docs/verifier.md "Slow slides count as stops"). 0: Coulomb
// sticking only.
// `contact_lift` (>= 0, task units, VerifyOptions::contact_lift): a robot at a reached concave edge may touch
// either adjacent face anywhere within that distance of the reached interval (it rose off the other face
// while sliding); that band of each face is reached too. 0: first-order contact.
// `servo_coast` (>= 0, task units, VerifyOptions::servo_coast): tau V, how far the servo's lag may carry the
// robot on at an impact (every landing region grows by it along its face) and past a convex rim it slides
// over (flights start from the rim swept by the sliding directions that far, lifted by contact_lift).
// 0: first-order velocity changes.
DamperProjection forward_project_damper(const LoadedTask& task, const AtomCones& cones,
                                        const ReachedSet& start, const Vec3& v,
                                        double stop_relative_speed = 0, double contact_lift = 0,
                                        double servo_coast = 0);

}  // namespace cmt

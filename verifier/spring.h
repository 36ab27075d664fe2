// The generalized spring (Buckley §3.3, §6.7.4, App. B): free-space error envelopes and sticking regions.
#pragma once

#include <vector>

#include "models/cspace.h"
#include "verifier/polyhedron.h"
#include "verifier/stick_class.h"

namespace cmt {

// App. B with interpolation steps of length `step` (eq. 3.21, 3.22): trajectories stay within eps_t of the
// line toward the commanded position (Fig 3.13) and overshoot by at most eps_o. Only e^{-t_t} reproduces the
// thesis's quoted .218 (buckley-notes §1): t_t = theta_v / tan(theta_v), t_o = (theta_v + pi/2) /
// tan(theta_v).
double eps_t(const Uncertainty& u);
double eps_o(const Uncertainty& u);

// Sticking regions of commanded positions for an atom (Buckley §6.7.4): the weak region holds every commanded
// position that might make the robot stick on the atom (an over-approximation), the strong region only
// commanded positions that are guaranteed to (an under-approximation).
struct SpringStickingRegions {
  Polyhedron weak;
  std::vector<Polyhedron> strong;  // a union of convex sets (none: nothing is guaranteed)
  bool strongly_contains(const Vec3& p) const;
};

// Weak: atom ⊕ K_w ⊕ ball(eps_s), K_w = −(friction cone widened by theta_v), outer polyhedral cones. When a
// face's phi + theta_v > pi/2 (the concave case the thesis skipped), K_w is not convex and the weak region is
// the complement of ∩_{x in F} (x + cone(n, pi − phi − theta_v)) ⊖ ball(eps_s), built from inner cones.
// Strong, face: commanded positions whose projection p' is at least eps_t inside every edge of the face and
// deep enough below it that, once the robot has slid to within eps_t of p', every sensed and velocity error
// still sticks: depth >= eps_s + (eps_t + eps_s) / tan(phi − theta_v) (derived here; Buckley's construction
// states only depth >= eps_s, which does not guarantee sticking when phi − theta_v is small). Empty when phi
// <= theta_v. Strong, edge and vertex: positions from which the pull from every point x of the atom keeps
// sticking the unique Coulomb solution under every sensing and velocity error (UniqueStick::must_cones
// narrowed by theta_v, eroded by eps_s, from inner cones). Buckley's summed cone is not used for "must": at a
// convex corner, sliding off onto a face is also a solution inside it.
SpringStickingRegions spring_sticking_regions(const CSpace& cspace, int atom_id, const Uncertainty& u);
// Its two parts on their own (the weak one builds the widened cone's polyhedral hull: the costly part).
Polyhedron spring_weak_region(const CSpace& cspace, int atom_id, const Uncertainty& u);
std::vector<Polyhedron> spring_strong_regions(const CSpace& cspace, int atom_id, const Uncertainty& u);

// must: p in the strong region; may: p in the weak region only; never: p outside the weak region.
StickClass classify_spring(const SpringStickingRegions& regions, const Vec3& commanded);

// Fig 3.16: for a commanded position, the points of a face where the robot may stick (weak) and where it is
// guaranteed to stick (strong), as convex polygons (outer / inner polygonal approximations of disks clipped
// to the face). Empty polygons when there are none.
struct FaceStickingConfigurations {
  std::vector<Vec3> weak;
  std::vector<Vec3> strong;
};
FaceStickingConfigurations face_sticking_configurations(const Face& face, const Vec3& commanded,
                                                        const Uncertainty& u);

// The disks behind FaceStickingConfigurations, about p' (the projection of the commanded position onto the
// face's plane): weak radius (< 0: none; infinity: the whole plane), strong radius (<= 0: none).
struct FaceStickingRadii {
  Vec3 center;
  double weak = -1, strong = 0;
};
FaceStickingRadii face_sticking_radii(const Face& face, const Vec3& commanded, const Uncertainty& u);

}  // namespace cmt

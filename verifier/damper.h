// The generalized damper in contact (Buckley §3.2, §4.3.5): may the robot stick on an atom, must it, and in
// which directions can it slide.
#pragma once

#include "models/cspace.h"
#include "models/friction_cone.h"
#include "verifier/atom_cone.h"
#include "verifier/stick_class.h"
#include "verifier/unique_stick.h"

namespace cmt {

// The actual velocity v_a lies in cone(v, theta_v) (§3.2.1); a static solution exists iff v_a lies in the
// negative friction cone of the atom (Fig 3.5). never: cone(v, theta_v) ∩ −FC = {0} (outer cone); must: every
// v_a in the cone lies where sticking is the only Coulomb solution (UniqueStick, margin >= theta_v); may
// otherwise. Errors only go toward may.
// `stop_angle` (>= 0) widens the "never" test only: a robot whose velocity is within theta_v + stop_angle of
// the friction cone may slide so slowly that a termination rule counting slow slides as stops fires
// (docs/verifier.md "Slow slides count as stops"); "must" keeps theta_v.
StickClass classify_damper(const FrictionCone& atom_cone, const UniqueStick& unique, const Vec3& v,
                           double theta_v, double stop_angle = 0);
StickClass classify_damper(const AtomCones& cones, int atom_id, const Vec3& v, double theta_v,
                           double stop_angle = 0);
StickClass classify_damper(const CSpace& cspace, int atom_id, const Vec3& v, double theta_v);

// Directions in which the robot may slide on a face (Alg 4.3), as an interval of azimuths about the face
// normal. A robot pushed with v_a (v_a . n < 0) slides iff angle(v_a, −n) > phi, and then along the
// tangential part of v_a (the reaction lies on the friction cone's rim opposite the motion: ẋ_t = v_t − mu
// |v_n| v_t/|v_t|), so the sliding directions are the azimuths of R = cone(v, theta_v) ∩ {phi < polar angle
// from −n < pi/2}. R is symmetric about the azimuth of v, and a meridian meets R iff its cap interval reaches
// past phi and starts before pi/2, which is monotone in the azimuth offset: the half-width is found by
// bisection and widened by kSlidingConeSlack (sound). This replaces eq 4.5-4.7, which are inconsistent as
// printed.
struct SlidingCone {
  bool possible = false;  // some admissible velocity slides
  bool all = false;       // every tangential direction (the friction cone lies inside the velocity cone)
  Vec3 axis;              // unit tangential direction of v (the cone's axis, eq. 4.3), when defined
  double half_angle = 0;  // in the face plane; may exceed pi/2
  // Does the cone contain the tangential direction d?
  bool contains(const Vec3& d, const Vec3& normal) const;
};
inline constexpr double kSlidingConeSlack = 1e-9;  // radians
SlidingCone sliding_cone(const Vec3& normal, double mu, const Vec3& v, double theta_v);

// Sliding along an edge (direction e = b − a): may the robot move toward b, toward a? Over-approximation: a
// direction is possible when some admissible velocity has a component along it and the robot need not stick;
// at a convex edge, and at a concave edge whose faces are at least square (n_f . n_g >= 0), also only when
// some admissible velocity presses into each face (v . n <= sin theta_v): a velocity that leaves a face of a
// convex edge points into free space (the flights from the edge cover it), and one that leaves a face of such
// a concave edge moves the robot onto the other face's plane, which that face's sliding covers (the forward
// projection seeds both faces from every reached edge point).
struct EdgeSliding {
  bool toward_a = false;
  bool toward_b = false;
};
EdgeSliding edge_sliding(const CSpace& cspace, int edge_atom_id, const Vec3& v, double theta_v);

}  // namespace cmt

// Private to verifier/ .cc files: the generalized spring under the velocity-form error model
// (docs/verifier.md, "Velocity-form spring model"): the robot's velocity (in contact: the force it imparts)
// lies within theta_v of p* − x, where p* = p − b is the commanded position moved by the sensing offset b,
// |b| <= eps_s, which is constant during a motion (a bias; controllers/error_model.h draws it once per
// motion). This is the model of the impedance and admittance forms (Buckley eq. 3.13 / 3.24 through a
// velocity controller); Buckley's via-point tubes (eps_t, eps_o; spring_flight.h) model the position form
// (eq. 3.25).
//
// Facts used (proved in the doc): in free flight |x − p*| never grows, the angle psi at p* between x(t) − p*
// and x(0) − p* obeys psi <= tan(theta_v) ln(|x(0) − p*| / |x(t) − p*|), so the path stays within delta
// |x(0) − p*| of seg[x(0), p*] (spring_spiral_deviation), and it stays in the cone x(0) + cone(p* − x(0),
// theta_v). Sliding on a face, the in-plane velocity is within beta(d) = asin(sin(theta_v) sqrt(d^2 + h*^2) /
// d) of the direction to p*' (d: in-plane distance, h*: depth of p* below the face), so the same laws hold in
// the plane with beta(d) while d > h* tan(theta_v) (the zone), and d never exceeds max(d(0), zone).
#pragma once

#include <algorithm>
#include <functional>
#include <vector>

#include "verifier/internal/damper_flight.h"
#include "verifier/internal/spring_velocity_support.h"
#include "verifier/spring_projection.h"

namespace cmt::face_geometry {

// A cone whose half-angle reaches pi/2 − this (rad) is not used as a bound (it would not be pointed).
inline constexpr double kVelocityPointedMargin = 0.05;
// Flight sources are cut (split_source) into pieces of angular radius <= kVelocityMaxSpread about their mean
// direction from p and of radial extent <= eps_s / (4 delta).
// The sizes the cuts aim for scale with eps_s (a piece's bounds blur by about eps_s anyway). With small or
// zero sensing error (perfect sensing) they scale instead with the spring's via-point step, and never go
// below kVelocityMinCutRelative of the scene, so that a source is not cut to the piece budget at every level
// (about 10x the time of eps_s = step on hole `teach`). Cutting less is sound (each piece's bounds hold for
// any piece), only looser.
inline constexpr double kVelocityMinCutRelative = 1e-3;
inline double cutting_eps(const Uncertainty& u, double scene_scale) {
  return std::max({u.eps_s, u.step, kVelocityMinCutRelative * scene_scale});
}

// What one velocity-form spring motion shares across its flights and slides.
struct VelocitySpring {
  Vec3 p;            // commanded position
  Uncertainty u;     // theta_v (possibly widened, experiments/validation/verifier_model.h) and eps_s are used
  double reach = 0;  // every point of the motion lies within this distance of p (velocity_reach_bound)
  std::vector<HalfSpace> bounds;  // every point of the motion lies in these (velocity_invariant_half_spaces)
  // Servo coast c = tau V (VerifyOptions::servo_coast, docs/verifier.md "Servo coast of springs"); 0 is the
  // first-order model (spring_projection.cc flies the coast's prisms).
  double coast = 0;
};

// The part of face fi within m.reach of p (outer polygon; empty if none): what widening may take.
Points2 velocity_reach_section(const ReachedSet::Impl& geometry, int fi, const VelocitySpring& m);

// Free-space reach from the convex source conv(src): for every face g but `source_face`, per piece X of the
// source, g ∩ (conv(X ∪ B(p, eps_s)) ⊕ ball(delta (R + eps_s))) ∩ ball(p, min(R + 2 eps_s, reach)) ∩ (X +
// cone(−a, theta_v + sigma + asin(eps_s / R_min))) ∩ the spiral regions (R: max |x − p| over X; a, sigma: X's
// mean direction from p and angular radius about it). No occlusion (paths bend); no landing on a face the
// flight meets only in the piece's own points. `departure` (servo coast, task units), given each piece's
// points: the displacements tau u of the velocities u the robot may leave that piece with; the piece's
// regions grow by conv(0, departure(piece)). Empty: the first-order flight.
using CoastDeparture = std::function<std::vector<Vec3>(const std::vector<Vec3>& piece)>;
std::vector<FlightHit> velocity_fly(const ReachedSet::Impl& geometry, const std::vector<Point3>& src,
                                    int source_face, const VelocitySpring& m,
                                    const CoastDeparture& departure = {});

// Sliding on face fi from the convex chart piece `part` (1, 2 or more points): the face ∩ (conv(part ∪
// disk(p', eps_s)) ⊕ disk(L)) ∩ disk(p', max(d0, zone) + eps_s) ∩ the in-plane spiral regions ∩ (the forward
// wedge ∪ the disk d <= d_w) ∩ the reach bound, per piece (a part within 2 eps_s of p' is first cut by the
// square of half-side 2 eps_s about p'). Returns the region (area) or, when it has none, fills `lower` with a
// segment or point.
ChartRegion velocity_slide(const ReachedSet::Impl& geometry, int fi, const Points2& part,
                           const VelocitySpring& m, Points2* lower);

}  // namespace cmt::face_geometry

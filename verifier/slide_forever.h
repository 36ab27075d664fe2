// Can a motion slide forever without stopping? Buckley's Alg 4.1 reports the points where the robot may stick
// (step 4), which says where a motion can end, not that it does: with a velocity error that switches (§3.2.1)
// a robot on a face whose friction angle is below theta_v can be pushed back and forth near the foot of its
// command and never stop (a spring pulled into a μ .1 box top with theta_v .27 does so in the rollouts).
// Derived here (docs/verifier.md "Termination: sliding forever"):
//
// A potential that grows on every motion the robot makes, except on "non-progressive" slides, proves
// termination when every non-progressive slide is slower than the stop rule's threshold (kappa times the
// reference speed): damper Phi = x . v (free flight: x' . v >= cos(theta_v) V; a face slide follows the
// tangential part of v_a, within 90 degrees of v's unless angle(v, −n) <= theta_v); spring Phi = −|p* − x|^2
// with p* the fixed sensed-offset target (the velocity model). Bounded C-space and speed >= kappa V_ref while
// moving bound the moving time; then only slow slides or sticking remain, which the stop rule ends.
//
// Speed of a non-progressive slide, per unit |v_a| (the robot's commanded velocity turned by the error):
//   face, beta = angle(w, −n) (w = v for a damper, p* − x for a spring): non-progressive v_a exist iff beta
//     <= theta_v and lie within psi = acos(cos(theta_v) / cos(beta)) <= theta_v of −n; a face slide's speed
//     is sin(alpha − phi) / cos(phi) at alpha = angle(v_a, −n);
//   edge (direction e), gamma = asin(|w . e| / |w|): non-progressive v_a exist iff gamma <= theta_v and have
//     |v_a . e| <= sin(theta_v − gamma); the normal reactions N_i (N_1 n_1 + N_2 n_2 = −v_a's part normal to
//     e) sum to at least that part's length, so the speed is <= sin(theta_v − gamma − phi_min) / cos(phi_min)
//     (phi_min: the least friction angle of the edge's faces); a convex edge's single contact gives the same.
//   a damper on an edge with two faces (u = v fixed) gets the exact bound: sliding along s e, the reactions
//     N_i >= 0 balance v_a's part normal to e (N_1 n_1 + N_2 n_2 = −v_a's part; for a convex edge as for a
//     concave one) and friction mu_1 N_1 + mu_2 N_2 opposes the slide, so the speed is s v_a . e − sum mu_i
//     N_i, linear in v_a: its largest value over the v_a within theta_v of u that keep every N_i >= 0 (none:
//     the robot leaves the edge) is found among the peaks of a linear function on that spherical region.
// Vertices do not slide. A motion may slide forever iff a reached face or edge holds a point where a
// non-progressive slide may be at least the stop threshold fast.
#pragma once

#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/reached_set.h"

namespace cmt {

// Speed bounds of non-progressive slides per unit |v_a|, as above; < 0 when there are none (or all stick).
double face_nonprogressive_speed(double beta, double theta_v, double mu);
double edge_nonprogressive_speed(double gamma, double theta_v, double mu_min);

// The exact damper edge bound above, per unit |v_a|, for an edge with unit direction e and faces (n1, mu1),
// (n2, mu2) (normals orthogonal to e), raised by 1e-9 on the sound side; < 0 when no non-progressive
// slide exists. Nearly parallel normals (a flat edge) fall back to edge_nonprogressive_speed.
double edge_slide_speed(const Vec3& u, double theta_v, const Vec3& n1, double mu1, const Vec3& n2, double mu2,
                        const Vec3& e);
// The same for a C-space edge (edge_nonprogressive_speed unless it has exactly two faces).
double edge_slide_speed(const CSpace& cspace, const Edge& edge, const Vec3& u, double theta_v);

// The least friction coefficient of an edge's faces (0 for an edge without faces).
double edge_min_friction(const CSpace& cspace, int edge_atom);

// The reached faces and edges (atom ids) where the motion may slide forever. Damper: commanded direction v;
// `must_stick[atom]` (the damper's "must" class: every admissible velocity sticks) excludes an atom.
// kappa: the stop rule's relative speed (VerifyOptions::stop_relative_speed; 0: Coulomb sticking only).
std::vector<int> damper_slide_forever_atoms(const CSpace& cspace, const ReachedSet& reached, const Vec3& v,
                                            double theta_v, double kappa,
                                            const std::vector<bool>& must_stick);

// Spring toward p with the target error p* within eps_s of p, fixed during the motion. The zone of a face is
// the disk about p's foot of radius (max(0, h) + eps_s) tan(theta_v) + eps_s (h: p's depth behind the plane),
// which holds every point x with angle(p* − x, −n) <= theta_v; an edge's zone the interval of its line within
// (rho + eps_s) tan(theta_v) + eps_s of p's foot (rho: p's distance to the line). A slide is slow enough when
// its bound times max(1, |p* − x|max / |p* − x0|min) is below kappa (|v_a| = min(V_max, k |p* − x|), V_ref =
// min(V_max, k |p* − x0|) at the start x0). `strong_atom[atom]` (the spring's guaranteed sticking: p in the
// atom's strong region) excludes an edge.
std::vector<int> spring_slide_forever_atoms(const CSpace& cspace, const ReachedSet& reached,
                                            const ReachedSet& start, const Vec3& p, const Uncertainty& u,
                                            double kappa, const std::vector<bool>& strong_atom);

// "f6 e13" for a failure message.
std::string atom_list(const CSpace& cspace, const std::vector<int>& atoms);

}  // namespace cmt

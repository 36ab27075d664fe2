// Forward projection and termination of one generalized-spring motion (Buckley §3.3, §4.4, Alg 4.4, which the
// thesis only proposed), in the framework of damper_projection.h (Alg 4.1: flight, sliding, edges, vertices,
// fixpoint). Sound: `termination` contains every contact point where a spring motion commanded to p and
// obeying the error bounds (theta_v, eps_s, eps_p, step: eps_t, eps_o) can come to rest, and
// `free_termination` is set whenever it may come to rest in free space (near p). docs/verifier.md, "Spring".
#pragma once

#include <vector>

#include "models/loaded_task.h"
#include "verifier/polyhedron.h"
#include "verifier/reached_set.h"

namespace cmt {

// Which trajectory model bounds the spring's paths (docs/verifier.md):
//   kViaPoint: Buckley's App. B via-point model (eps_t cylinders, eps_o overshoot; the sensing and
//              positioning errors may change at every replanning), the model of the position form (eq. 3.25);
//   kVelocity: the velocity forms (impedance eq. 3.13, admittance eq. 3.24): the velocity lies within
//              theta_v of p* − x for a p* within eps_s of p that is fixed during the motion (the sensing
//              offset is a bias); bounded by logarithmic spirals about p* (internal/spring_velocity.h).
enum class SpringModel { kViaPoint, kVelocity };
const char* spring_model_name(SpringModel m);

struct SpringProjection {
  ReachedSet reached;              // every contact point reachable from the start (the start included)
  ReachedSet termination;          // reached points where sticking is possible (weak sticking configurations)
  bool may_not_terminate = false;  // no contact termination and no free-space rest
  // Reached faces and edges where the motion may slide forever (verifier/slide_forever.h; a failure).
  std::vector<int> slide_forever = {};
  bool fallback = false;  // the fixpoint cap was hit: every atom is reached (sound, uninformative)
  int steps = 0;          // work items processed
  int widened = 0;        // atoms widened (hull stage, kSpringWideningRounds)
  // The robot may come to rest in free space: the ball of radius free_radius about free_center (= p) meets
  // free space and the motion may leave contact.
  bool free_termination = false;
  Vec3 free_center = Vec3::Zero();
  double free_radius = 0;
};

// Widening (a sound acceleration of the fixpoint; docs/verifier.md "Widening"): once a face's reached region
// or an edge's reached intervals have grown in this many fixpoint rounds (work items; several additions in
// one round count once), the convex hull of what it holds is taken as reached; after twice as many, the whole
// face or edge (the velocity model: its part inside the reach ball). Any addition is sound (everything added
// is propagated); the hull stage stops creep by slivers that fill in a region without extending it, and keeps
// a far rim out of the set when no landing comes near it. Under Buckley's error model a robot that may leave
// a face can hop up to eps_t from every breakaway point (the cylinder holds the ball about its source), so
// reached sets can creep across a face by ~eps_t per round; the limit of that creep is (nearly) the whole
// face, and the rounds cost time ∝ face size / eps_t.
inline constexpr int kSpringWideningRounds = 24;

// Work items processed before the "every atom is reached" fallback.
inline constexpr int kMaxSpringFixpointSteps = 20000;

// Radius of the free-space rest ball about p: at rest in free space the sensed position equals the commanded
// one (x' = p − x̂ = 0), so the robot is within eps_s of p; eps_p bounds the final positioning error. The
// larger of the two.
double spring_rest_radius(const Uncertainty& u);

// Velocity model with a stop rule that counts slides slower than kappa times the motion's reference speed
// as stops (the rollouts' rule, controllers/termination.h; the reference speed is min(max speed, rate
// |p − x̂0|) at the sensed start x̂0): such a slow point x is where the robot may stick with p* − x moved by
// less than kappa V_ref / rate <= kappa (|p − x0| + eps_s). That radius, maximized over the start, is added
// to eps_s in the weak sticking regions and the free-space rest ball (docs/verifier.md "Slow slides count
// as stops"). 0 when kappa is 0.
double slow_stop_radius(const ReachedSet& start, const Vec3& p, const Uncertainty& u, double kappa);

// Velocity model (docs/verifier.md, "Velocity-form spring model"). delta(theta_v) = max(max_b e^(−b / tan
// theta_v) sin b, e^(−pi / (2 tan theta_v))) = e^(−theta_v / tan theta_v) sin(theta_v): a free path from x
// toward a fixed p* stays within delta |x − p*| of seg[x, p*].
double spring_spiral_deviation(double theta_v);
// A bound on |x − p| over every point x of a velocity-model motion from `start`: |x − p*| never grows in
// flight, nor while sliding outside a face's or an edge's zone; inside a zone (reachable within the bound)
// it is at most the distance from p* to the plane or line over cos(theta_v); + eps_s for p* − p.
double velocity_reach_bound(const CSpace& cspace, const ReachedSet& start, const Vec3& p,
                            const Uncertainty& u);

// Velocity model: half-spaces normal . x <= offset that hold every point of a motion from `start` toward p
// whose points all lie within `reach` of p (velocity_reach_bound), for the 6 axis and 8 diagonal normals w:
// the least level c >= max w . x over the start such that every admissible motion direction on the level (or
// above it) has a non-positive component along w (docs/verifier.md, "Invariant half-spaces"). Directions
// without such a level below the reach ball's extent are left out.
std::vector<HalfSpace> velocity_invariant_half_spaces(const CSpace& cspace, const ReachedSet& start,
                                                      const Vec3& p, const Uncertainty& u, double reach);

// `stop_relative_speed` (kappa): see slow_stop_radius; used by the velocity model only (the via-point model
// bounds the position form, whose stop rule is the AML force rule while via points are issued).
// `contact_lift` (>= 0, task units, VerifyOptions::contact_lift): a robot sliding on one face of a reached
// concave edge toward it may be up to this far off that face when it meets the other one (docs/verifier.md
// "Contact lift"); the other face gets lift strips over the reached edge intervals, as for dampers.
// `servo_coast` (>= 0, task units, VerifyOptions::servo_coast): tau V, how far the servo's lag may carry the
// robot beyond the first-order flight; velocity-model flights are bounded for the lag (docs/verifier.md
// "Servo coast of springs"); `spring_lag` (VerifyOptions::spring_lag) bounds it near p.
SpringProjection forward_project_spring(const LoadedTask& task, const ReachedSet& start, const Vec3& p,
                                        SpringModel model = SpringModel::kViaPoint,
                                        double stop_relative_speed = 0, double contact_lift = 0,
                                        double servo_coast = 0, double spring_lag = 0);

}  // namespace cmt

// Distinguishability of termination sets by the sensors (Donald's LIMITED test, l.1883-1919; Buckley
// Def 5.1): two termination points are confusable when they lie within 2 eps_s of each other and their
// friction cones (the reaction forces the robot may sense there) come within 2 theta_f. The sets may come
// from different slices of a task with model error: the robot's sensors say nothing about the model
// parameters (Donald's physics axioms, l.968-1022), so a success in one slice and a failure in another must
// be told apart too.
#pragma once
#include <vector>

#include "models/cspace.h"
#include "models/friction_cone.h"
#include "verifier/reached_set.h"

namespace cmt {

// How far, as a fraction of the scene scale, a physical robot at rest may lie from the C-space point it
// stands for: the rollouts' contact tolerance (sim/rollout.h kAtomRelativeTolerance, 30x MuJoCo's largest
// resting penetration and slip hop). The EDR predicate accepts a sensed position within eps_s plus this of a
// goal termination (experiments/edr/edr_check.h): a robot that stopped at a goal termination, sunk into the
// face, is still recognized.
inline constexpr double kEdrContactRelativeSlack = 1e-4;
// Added to 2 eps_s as a fraction of the larger scene scale: a pair is position-distinguishable only when its
// distance bound exceeds 2 eps_s by more than this: the predicate's slack above on both sides, and 2e-6 for
// the goal containment tolerance kGoalRelativeTolerance and the region kernel's rounding (docs/edr.md).
inline constexpr double kEdrPositionRelativeMargin = 2 * kEdrContactRelativeSlack + 2e-6;

// A piece as a convex set: 1 point, a segment (2), or a convex planar polygon (3+, counter-clockwise about
// `normal`). A face region is taken as the convex hull of its outer boundary.
struct ConvexPiece {
  std::vector<Vec3> points;
  Vec3 normal = Vec3::UnitZ();
};
ConvexPiece convex_piece(const ReachedPiece& piece);
// A unit normal of the plane through points in any order, zero when they are collinear (or fewer than 3):
// from the point farthest from the first and the point farthest from the line through both.
Vec3 plane_normal(const std::vector<Vec3>& points);
// Distance from p to the convex set (+infinity for an empty one). Floating point.
double point_to_piece(const Vec3& p, const ConvexPiece& piece);

// A lower bound on the distance between two pieces (ReachedSet::pieces: a face region, taken as the convex
// hull of its outer boundary; a segment; a point). Floating point.
double piece_distance_lower_bound(const ReachedPiece& a, const ReachedPiece& b);

// A piece of a termination set, with the C-space (slice) it lies in.
struct SlicePiece {
  const CSpace* cspace = nullptr;
  int slice = -1;
  ReachedPiece piece;
};

// A confusable pair: piece `a` of the first list and `b` of the second, their distance and force-angle
// bounds.
struct Confusion {
  int a = -1, b = -1;
  double distance = 0;
  double force_angle = 0;
};

// May the sensors confuse a point of piece a (friction cone ca) with one of piece b (cone cb)? Their distance
// bound <= 2 eps_s + margin and their force-angle lower bound <= 2 theta_f; `out` gets both bounds.
bool confusable(const ReachedPiece& a, const FrictionCone& ca, const ReachedPiece& b, const FrictionCone& cb,
                double eps_s, double theta_f, double margin, Confusion* out);

// Every pair (a in first, b in second) that may be confused (`confusable`). Empty: the two sets are
// distinguishable by position or force at every pair.
std::vector<Confusion> confusable_pairs(const std::vector<SlicePiece>& first,
                                        const std::vector<SlicePiece>& second, double eps_s, double theta_f,
                                        double margin);

}  // namespace cmt

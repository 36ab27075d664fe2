// Floating-point geometry of the verifier's output pieces (ReachedPiece, task coordinates) for validation:
// distances and area-uniform lattices. Doubles suffice: results are compared with tolerances and radii far
// above rounding (docs/validation.md).
#pragma once

#include <vector>

#include "models/cspace.h"
#include "verifier/reached_set.h"
#include "verifier/verify.h"

namespace cmt {

// Euclidean distance from p to a closed piece: a face region with holes, a segment, a point.
double distance_to_piece(const CSpace& cspace, const ReachedPiece& piece, const Vec3& p);

// Distance of a final end from where an unreliable verdict says the strategy fails: its offending
// termination pieces (VerifyResult::outside_goal) and a spring's free rest ball; +infinity when it names no
// such place (an earlier step failed, or a motion may slide forever).
double distance_to_failure(const CSpace& cspace, const VerifyResult& prediction, const Vec3& end);

// Points of the square lattice of spacing h (cell centres) that lie in a face region piece (outer loop minus
// holes). The lattice is fixed in an orthonormal frame of the face's plane anchored at the plane's point
// nearest the origin, so the samples do not depend on how a region was cut into pieces.
std::vector<Vec3> region_lattice(const CSpace& cspace, const ReachedPiece& piece, double h);

}  // namespace cmt

// How far a motion end is from leaving a predicted set (docs/falsify.md "Scores"): the signed distance the
// falsification search maximizes, as robustness is in falsification of cyber-physical systems (S-TaLiRo,
// Breach). Floating point: it only guides the search; an end counts as outside by
// distance_to_prediction > the contact tolerance, exactly as in `cmt validate`.
#pragma once

#include <vector>

#include "models/cspace.h"
#include "verifier/reached_set.h"
#include "verifier/verify.h"

namespace cmt {

// One step's prediction prepared for scoring (its pieces computed once).
struct PredictedStep {
  const VerifyStep* step = nullptr;
  std::vector<ReachedPiece> pieces;
};
std::vector<PredictedStep> predicted_steps(const VerifyResult& prediction);

// Signed distance of p from the step's predicted termination set: the distance (> 0) when p is farther than
// `tolerance` from it; otherwise minus the depth of p in the piece that holds it deepest (a face region: the
// distance to its outline and holes; a segment or edge interval: to its nearer end; a point: 0; the spring's
// free rest ball: its radius less the distance to its centre). A piece holds p when p is within `tolerance`
// of it. The depth ignores that a neighbouring piece may continue the set past an outline, so it
// under-estimates how deep p is: the search is drawn to every outline, the true boundary among them.
double signed_distance(const CSpace& cspace, const PredictedStep& step, const Vec3& p, double tolerance);

}  // namespace cmt

// Signed distances to predicted sets (experiments/falsify/robustness.h).
#include "experiments/falsify/robustness.h"

#include <algorithm>
#include <limits>

#include "experiments/validation/piece_geometry.h"
#include "experiments/validation/validation.h"
#include "models/polygon_distance.h"

namespace cmt {
namespace {

double ring_distance(const std::vector<Vec3>& ring, const Vec3& p) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ring.size(); ++i)
    d = std::min(d, distance_to_segment(p, ring[i], ring[(i + 1) % ring.size()]));
  return d;
}

// Depth of p in a piece that holds it.
double depth_in_piece(const ReachedPiece& piece, const Vec3& p) {
  if (piece.polygon.size() >= 3) {
    double d = ring_distance(piece.polygon, p);
    for (const std::vector<Vec3>& hole : piece.holes) d = std::min(d, ring_distance(hole, p));
    return d;
  }
  if (piece.polygon.size() == 2)
    return std::min((p - piece.polygon[0]).norm(), (p - piece.polygon[1]).norm());
  return 0;
}

}  // namespace

std::vector<PredictedStep> predicted_steps(const VerifyResult& prediction) {
  std::vector<PredictedStep> out;
  for (const VerifyStep& step : prediction.steps) out.push_back({&step, step.termination.pieces()});
  return out;
}

double signed_distance(const CSpace& cspace, const PredictedStep& step, const Vec3& p, double tolerance) {
  const double outside = distance_to_prediction(*step.step, p);
  if (outside > tolerance) return outside;
  double depth = 0;
  for (const ReachedPiece& piece : step.pieces)
    if (distance_to_piece(cspace, piece, p) <= tolerance) depth = std::max(depth, depth_in_piece(piece, p));
  if (step.step->free_termination)
    depth = std::max(depth, step.step->free_radius - (p - step.step->free_center).norm());
  return -depth;
}

}  // namespace cmt

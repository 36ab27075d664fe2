// Coverage of a prediction (experiments/validation/validation.h, docs/validation.md "Coverage"): how much of
// each motion's predicted termination set lies within a radius of an observed end of that motion, measured on
// a deterministic lattice (area-uniform on face regions, length-uniform on segments).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "experiments/validation/piece_geometry.h"
#include "experiments/validation/validation.h"

namespace cmt {
namespace {

// Is p within r of some end?
bool near_an_end(const Vec3& p, const std::vector<Vec3>& ends, double r) {
  const double r2 = r * r;
  return std::any_of(ends.begin(), ends.end(), [&](const Vec3& e) { return (e - p).squaredNorm() <= r2; });
}

// Planar tasks (dimension 2) are extruded across a y slab whose walls are phantoms (models/task_loader.h), so
// a piece is measured by its trace in the x-z plane: a face region (a band across the slab) is the segment
// between its two farthest points, an edge interval across the slab (a 2-D vertex) or a segment along y is a
// point. Ends are taken at y = 0 too (planar rollouts stay there).
std::vector<ReachedPiece> in_plane(std::vector<ReachedPiece> pieces) {
  // Below this (task units) a projected segment is a point: the slab's own coordinates are exact doubles.
  constexpr double kSame = 1e-12;
  for (ReachedPiece& p : pieces) {
    for (Vec3& q : p.polygon) q.y() = 0;
    p.holes.clear();
    p.area = 0;
    std::size_t a = 0, b = 0;
    for (std::size_t i = 0; i < p.polygon.size(); ++i)
      for (std::size_t j = i + 1; j < p.polygon.size(); ++j)
        if ((p.polygon[i] - p.polygon[j]).norm() > (p.polygon[a] - p.polygon[b]).norm()) a = i, b = j;
    p.polygon = (p.polygon[a] - p.polygon[b]).norm() > kSame ? std::vector<Vec3>{p.polygon[a], p.polygon[b]}
                                                             : std::vector<Vec3>{p.polygon[a]};
  }
  return pieces;
}

// Splits a step's measured pieces by dimension (planar tasks: their traces in the x-z plane).
struct PiecesByDimension {
  std::vector<ReachedPiece> regions, segments, points;
  double area = 0, length = 0;
};

PiecesByDimension split_pieces(const LoadedTask& task, const VerifyStep& step) {
  PiecesByDimension out;
  std::vector<ReachedPiece> pieces = step.termination.pieces();
  if (task.task.dimension == 2) pieces = in_plane(std::move(pieces));
  for (ReachedPiece& p : pieces) {
    if (p.kind == AtomKind::kFace && p.polygon.size() >= 3) {
      out.area += p.area;
      out.regions.push_back(std::move(p));
    } else if (p.polygon.size() == 2) {
      out.length += (p.polygon[1] - p.polygon[0]).norm();
      out.segments.push_back(std::move(p));
    } else {
      out.points.push_back(std::move(p));
    }
  }
  return out;
}

// radius > 0: that radius instead of the one from the sample size.
StepValidation cover_step(const LoadedTask& task, const VerifyStep& step, std::vector<Vec3> ends,
                          double contact_tolerance, double radius) {
  StepValidation s;
  s.motion = step.motion;
  s.ends = static_cast<int>(ends.size());
  for (Vec3& e : ends) e = coverage_position(task, e);
  const CoverageLattice lattice = coverage_lattice(task, step);
  s.measure = lattice.measure;
  s.predicted = lattice.predicted;
  if (lattice.measure == "none" || ends.empty()) return s;
  const double n = static_cast<double>(ends.size());
  if (lattice.measure ==
      "points")  // no measure to derive a radius from: reached within the contact tolerance
    s.radius = contact_tolerance;
  else if (radius > 0)
    s.radius = radius;
  else if (lattice.measure == "area")
    s.radius = std::sqrt(kCoverageConstant * lattice.predicted / (std::numbers::pi * n));
  else
    s.radius = kCoverageConstant * lattice.predicted / (2 * n);
  long hit = 0;
  for (const Vec3& q : lattice.points) hit += near_an_end(q, ends, s.radius);
  // Each lattice point stands for an equal share of the measure.
  const long total = static_cast<long>(lattice.points.size());
  s.coverage = total > 0 ? static_cast<double>(hit) / total : 0;
  s.covered = s.coverage * s.predicted;
  return s;
}

}  // namespace

Vec3 coverage_position(const LoadedTask& task, Vec3 end) {
  if (task.task.dimension == 2) end.y() = 0;
  return end;
}

// The highest-dimensional part of the prediction carries the measure; lower-dimensional parts (the boundary
// closure of face regions, say) have none beside it.
CoverageLattice coverage_lattice(const LoadedTask& task, const VerifyStep& step) {
  const PiecesByDimension pieces = split_pieces(task, step);
  CoverageLattice out;
  if (pieces.area > 0) {
    out.measure = "area";
    out.predicted = pieces.area;
    const double h = std::sqrt(pieces.area / kCoverageSamples);
    for (const ReachedPiece& p : pieces.regions)
      for (const Vec3& q : region_lattice(task.cspace, p, h)) out.points.push_back(q);
  } else if (pieces.length > 0) {
    out.measure = "length";
    out.predicted = pieces.length;
    const double h = pieces.length / kCoverageSamples;
    for (const ReachedPiece& p : pieces.segments) {
      const Vec3 d = p.polygon[1] - p.polygon[0];
      const double len = d.norm();
      for (double t = h / 2; t <= len; t += h) out.points.push_back(p.polygon[0] + (t / len) * d);
    }
  } else if (!pieces.points.empty()) {
    out.measure = "points";
    out.predicted = static_cast<double>(pieces.points.size());
    for (const ReachedPiece& p : pieces.points) out.points.push_back(p.polygon[0]);
  }
  return out;
}

void score_coverage(const LoadedTask& task, ValidationResult* r, const std::vector<StepValidation>& radii) {
  const std::vector<VerifyStep>& steps = r->prediction.steps;
  r->steps.clear();
  for (std::size_t mi = 0; mi < steps.size(); ++mi) {
    std::vector<Vec3> ends;
    int outside = 0;
    for (const ObservedEnd& e : r->ends)
      if (e.motion == static_cast<int>(mi)) {
        ends.push_back(e.end);
        outside += !e.inside;
      }
    const double radius = mi < radii.size() ? radii[mi].radius : 0;
    StepValidation s = cover_step(task, steps[mi], ends, r->contact_tolerance, radius);
    s.outside = outside;
    r->steps.push_back(s);
  }
  // Pooled over the motions whose predictions have the highest-dimensional measure of the strategy, weighted
  // by that measure (the fraction of all predicted area, or length, or points, that the rollouts reached).
  std::string measure = "none";
  for (const char* m : {"points", "length", "area"})
    for (const StepValidation& s : r->steps)
      if (s.measure == m) measure = m;
  double predicted = 0, covered = 0;
  r->coverage_radius = 0;
  for (const StepValidation& s : r->steps)
    if (s.measure == measure) {
      predicted += s.predicted;
      covered += s.covered;
      r->coverage_radius = std::max(r->coverage_radius, s.radius);
    }
  r->coverage = predicted > 0 ? covered / predicted : 0;
}

}  // namespace cmt

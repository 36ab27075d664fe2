// Distances and lattices on ReachedPieces (experiments/validation/piece_geometry.h).
#include "experiments/validation/piece_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/polygon_distance.h"

namespace cmt {
namespace {

using Vec2 = Eigen::Vector2d;

// An orthonormal frame (e1, e2) of a face's plane, from its normal alone.
struct PlaneFrame {
  Vec3 n, e1, e2;
  double offset = 0;
  explicit PlaneFrame(const Face& face) : n(face.normal), offset(face.offset) {
    const Vec3 a = n.cwiseAbs();
    const Vec3 axis =
        (a.x() <= a.y() && a.x() <= a.z()) ? Vec3::UnitX() : (a.y() <= a.z() ? Vec3::UnitY() : Vec3::UnitZ());
    e1 = n.cross(axis).normalized();
    e2 = n.cross(e1);
  }
  Vec2 to2(const Vec3& p) const { return {p.dot(e1), p.dot(e2)}; }
  Vec3 to3(const Vec2& q) const { return offset * n + q.x() * e1 + q.y() * e2; }
  std::vector<Vec2> to2(const std::vector<Vec3>& loop) const {
    std::vector<Vec2> out;
    for (const Vec3& p : loop) out.push_back(to2(p));
    return out;
  }
};

// Even-odd point-in-polygon test.
bool inside_loop(const std::vector<Vec2>& loop, const Vec2& q) {
  bool in = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Vec2 &a = loop[i], &b = loop[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < a.x() + (q.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y()))
      in = !in;
  }
  return in;
}

bool inside_region(const std::vector<Vec2>& outer, const std::vector<std::vector<Vec2>>& holes,
                   const Vec2& q) {
  return inside_loop(outer, q) &&
         std::none_of(holes.begin(), holes.end(), [&](const auto& h) { return inside_loop(h, q); });
}

double distance_to_loop(const std::vector<Vec3>& loop, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < loop.size(); ++i)
    best = std::min(best, distance_to_segment(p, loop[i], loop[(i + 1) % loop.size()]));
  return best;
}

}  // namespace

double distance_to_piece(const CSpace& c, const ReachedPiece& piece, const Vec3& p) {
  if (piece.polygon.empty()) return std::numeric_limits<double>::infinity();
  if (piece.polygon.size() == 1) return (p - piece.polygon[0]).norm();
  if (piece.polygon.size() == 2) return distance_to_segment(p, piece.polygon[0], piece.polygon[1]);
  const PlaneFrame frame(c.faces()[c.atom_index(piece.atom)]);
  const double height = frame.n.dot(p) - frame.offset;
  const Vec3 foot = p - height * frame.n;
  std::vector<std::vector<Vec2>> holes;
  for (const auto& h : piece.holes) holes.push_back(frame.to2(h));
  if (inside_region(frame.to2(piece.polygon), holes, frame.to2(foot))) return std::abs(height);
  double in_plane = distance_to_loop(piece.polygon, foot);
  for (const auto& h : piece.holes) in_plane = std::min(in_plane, distance_to_loop(h, foot));
  return std::hypot(height, in_plane);
}

std::vector<Vec3> region_lattice(const CSpace& c, const ReachedPiece& piece, double h) {
  const PlaneFrame frame(c.faces()[c.atom_index(piece.atom)]);
  const std::vector<Vec2> outer = frame.to2(piece.polygon);
  std::vector<std::vector<Vec2>> holes;
  for (const auto& hole : piece.holes) holes.push_back(frame.to2(hole));
  Vec2 lo = outer[0], hi = outer[0];
  for (const Vec2& q : outer) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  std::vector<Vec3> out;
  for (long i = std::lround(std::floor(lo.x() / h)); (i + 0.5) * h <= hi.x(); ++i)
    for (long j = std::lround(std::floor(lo.y() / h)); (j + 0.5) * h <= hi.y(); ++j) {
      const Vec2 q((i + 0.5) * h, (j + 0.5) * h);
      if (inside_region(outer, holes, q)) out.push_back(frame.to3(q));
    }
  return out;
}

double distance_to_failure(const CSpace& cspace, const VerifyResult& prediction, const Vec3& end) {
  double d = std::numeric_limits<double>::infinity();
  for (const ReachedPiece& p : prediction.outside_goal) d = std::min(d, distance_to_piece(cspace, p, end));
  const int fs = prediction.failed_step;
  if (fs >= 0 && prediction.steps[static_cast<std::size_t>(fs)].free_termination) {
    const VerifyStep& s = prediction.steps[static_cast<std::size_t>(fs)];
    d = std::min(d, std::max(0.0, (end - s.free_center).norm() - s.free_radius));
  }
  return d;
}

}  // namespace cmt

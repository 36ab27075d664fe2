// Sets of commanded positions (cposition_set.h).
#include "verifier/planner/cposition_set.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cmt::planner {
namespace {

HalfSpace flipped(const HalfSpace& h) { return {-h.normal, -h.offset}; }

bool satisfies(const std::vector<HalfSpace>& hs, const Vec3& x, double slack) {
  for (const HalfSpace& h : hs)
    if (h.normal.dot(x) > h.offset + slack) return false;
  return true;
}

// A convex polytope as its faces: each a convex loop of points on the plane of one half-space (index into
// the piece's list). Built from the domain box and clipped by one half-space at a time.
struct FaceLoop {
  int plane = 0;
  std::vector<Vec3> points;
};

std::vector<FaceLoop> box_faces(const AxisBox& box) {
  const Vec3& lo = box.min;
  const Vec3& hi = box.max;
  const auto corner = [&](int i) {
    return Vec3((i & 1) ? hi.x() : lo.x(), (i & 2) ? hi.y() : lo.y(), (i & 4) ? hi.z() : lo.z());
  };
  // box_halfspaces order: +x, -x, +y, -y, +z, -z; each face's four corners in cyclic order.
  const int loops[6][4] = {{1, 3, 7, 5}, {0, 4, 6, 2}, {2, 6, 7, 3},
                           {0, 1, 5, 4}, {4, 5, 7, 6}, {0, 2, 3, 1}};
  std::vector<FaceLoop> faces;
  for (int f = 0; f < 6; ++f) {
    FaceLoop face{f, {}};
    for (int k : loops[f]) face.points.push_back(corner(k));
    faces.push_back(std::move(face));
  }
  return faces;
}

// Points in a plane ordered by angle about their centroid (a convex loop when they are in convex position),
// near-duplicates merged.
std::vector<Vec3> convex_loop(std::vector<Vec3> points, const Vec3& normal, double merge) {
  std::vector<Vec3> unique;
  for (const Vec3& p : points)
    if (std::none_of(unique.begin(), unique.end(), [&](const Vec3& u) { return (u - p).norm() <= merge; }))
      unique.push_back(p);
  if (unique.size() < 3) return unique;
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : unique) c += p;
  c /= static_cast<double>(unique.size());
  const Vec3 u = (unique[0] - c).normalized(), w = normal.cross(u);
  std::sort(unique.begin(), unique.end(), [&](const Vec3& a, const Vec3& b) {
    return std::atan2((a - c).dot(w), (a - c).dot(u)) < std::atan2((b - c).dot(w), (b - c).dot(u));
  });
  return unique;
}

enum class Clip { kUnchanged, kCut, kEmpty };

// Clips the polytope to h relaxed by `slack` (normal . x <= offset + slack), the new face on h's plane
// labelled `plane`.
Clip clip_faces(std::vector<FaceLoop>& faces, const HalfSpace& h, int plane, double slack) {
  const double level = h.offset + slack;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const FaceLoop& f : faces)
    for (const Vec3& p : f.points) {
      lo = std::min(lo, h.normal.dot(p) - level);
      hi = std::max(hi, h.normal.dot(p) - level);
    }
  if (hi <= 0) return Clip::kUnchanged;
  if (lo > 0) return Clip::kEmpty;
  std::vector<FaceLoop> kept;
  std::vector<Vec3> cap;
  for (const FaceLoop& f : faces) {
    FaceLoop out{f.plane, {}};
    for (std::size_t i = 0; i < f.points.size(); ++i) {
      const Vec3& a = f.points[i];
      const Vec3& b = f.points[(i + 1) % f.points.size()];
      const double da = h.normal.dot(a) - level, db = h.normal.dot(b) - level;
      if (da <= 0) out.points.push_back(a);
      if (da == 0) cap.push_back(a);
      if ((da < 0 && db > 0) || (da > 0 && db < 0)) {
        const Vec3 x = a + (b - a) * (da / (da - db));
        out.points.push_back(x);
        cap.push_back(x);
      }
    }
    if (out.points.size() >= 3) kept.push_back(std::move(out));
  }
  if (kept.empty()) return Clip::kEmpty;
  FaceLoop cap_face{plane, convex_loop(cap, h.normal, slack)};
  if (cap_face.points.size() >= 3) kept.push_back(std::move(cap_face));
  faces = std::move(kept);
  return Clip::kCut;
}

// Whether every vertex lies in h (within the slack): the polytope is inside h.
bool inside(const std::vector<Vec3>& vertices, const HalfSpace& h, double slack) {
  return std::all_of(vertices.begin(), vertices.end(),
                     [&](const Vec3& v) { return h.normal.dot(v) <= h.offset + slack; });
}

// Whether every vertex lies strictly outside h: the polytope misses h's interior.
bool outside(const std::vector<Vec3>& vertices, const HalfSpace& h, double slack) {
  return std::all_of(vertices.begin(), vertices.end(),
                     [&](const Vec3& v) { return h.normal.dot(v) >= h.offset - slack; });
}

}  // namespace

std::vector<HalfSpace> box_halfspaces(const AxisBox& box) {
  std::vector<HalfSpace> hs;
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 e = Vec3::Zero();
    e[axis] = 1;
    hs.push_back({e, box.max[axis]});
    hs.push_back({-e, -box.min[axis]});
  }
  return hs;
}

CPositionSet CPositionSet::domain(const AxisBox& box) {
  CPositionSet s(box);
  s.add_piece({});
  return s;
}

CPositionSet CPositionSet::none(const AxisBox& box) { return CPositionSet(box); }

CPositionSet CPositionSet::convex(const std::vector<HalfSpace>& halfspaces, const AxisBox& box) {
  CPositionSet s(box);
  s.add_piece(halfspaces);
  return s;
}

CPositionSet CPositionSet::of(const Polyhedron& polyhedron, const AxisBox& box) {
  switch (polyhedron.kind) {
    case Polyhedron::Kind::kEmpty:
      return none(box);
    case Polyhedron::Kind::kEverything:
      return domain(box);
    case Polyhedron::Kind::kConvex:
      return convex(polyhedron.halfspaces, box);
    case Polyhedron::Kind::kComplement:
      return domain(box).minus(convex(polyhedron.halfspaces, box));
  }
  return none(box);
}

CPositionSet CPositionSet::of_union(const std::vector<Polyhedron>& polyhedra, const AxisBox& box) {
  CPositionSet s(box);
  for (const Polyhedron& p : polyhedra) s = s.unite(of(p, box));
  return s;
}

void CPositionSet::add_piece(std::vector<HalfSpace> halfspaces) {
  // Exact copies (a facet shared by two operands) are kept once; the box's own faces come first.
  std::vector<HalfSpace> unique = box_halfspaces(box_);
  for (const HalfSpace& h : halfspaces)
    if (std::none_of(unique.begin(), unique.end(),
                     [&](const HalfSpace& u) { return u.offset == h.offset && u.normal == h.normal; }))
      unique.push_back(h);
  const double slack = kPieceSlack * diagonal();
  std::vector<FaceLoop> faces = box_faces(box_);
  for (std::size_t i = 6; i < unique.size(); ++i)
    if (clip_faces(faces, unique[i], static_cast<int>(i), slack) == Clip::kEmpty) return;
  // The half-spaces that own a face; the corners of the faces.
  ConvexPiece piece;
  std::vector<bool> owns(unique.size(), false);
  for (const FaceLoop& f : faces) {
    owns[static_cast<std::size_t>(f.plane)] = true;
    for (const Vec3& p : f.points)
      if (std::none_of(piece.vertices.begin(), piece.vertices.end(),
                       [&](const Vec3& v) { return (v - p).norm() <= slack; }))
        piece.vertices.push_back(p);
  }
  for (std::size_t i = 0; i < unique.size(); ++i)
    if (owns[i]) piece.halfspaces.push_back(unique[i]);
  pieces_.push_back(std::move(piece));
}

CPositionSet CPositionSet::intersect(const CPositionSet& other) const {
  CPositionSet out(box_);
  for (const ConvexPiece& a : pieces_)
    for (const ConvexPiece& b : other.pieces_) {
      std::vector<HalfSpace> hs = a.halfspaces;
      hs.insert(hs.end(), b.halfspaces.begin(), b.halfspaces.end());
      out.add_piece(std::move(hs));
    }
  return out;
}

CPositionSet CPositionSet::minus(const CPositionSet& other) const {
  const double slack = kPieceSlack * diagonal();
  std::vector<ConvexPiece> current = pieces_;
  for (const ConvexPiece& q : other.pieces_) {
    CPositionSet next(box_);
    for (const ConvexPiece& p : current) {
      const bool disjoint = std::any_of(q.halfspaces.begin(), q.halfspaces.end(),
                                        [&](const HalfSpace& h) { return outside(p.vertices, h, slack); });
      if (disjoint) {
        next.pieces_.push_back(p);
        continue;
      }
      // p − q = ∪_j p ∩ h_1 ∩ ... ∩ h_{j−1} ∩ ¬h_j over q's facets h_j.
      std::vector<HalfSpace> kept = p.halfspaces;
      for (const HalfSpace& h : q.halfspaces) {
        if (inside(p.vertices, h, slack)) continue;  // p ∩ ¬h is at most a boundary face of p
        std::vector<HalfSpace> piece = kept;
        piece.push_back(flipped(h));
        next.add_piece(std::move(piece));
        kept.push_back(h);
      }
    }
    current = std::move(next.pieces_);
  }
  CPositionSet out(box_);
  out.pieces_ = std::move(current);
  return out;
}

CPositionSet CPositionSet::unite(const CPositionSet& other) const {
  CPositionSet out = *this;
  out.pieces_.insert(out.pieces_.end(), other.pieces_.begin(), other.pieces_.end());
  return out;
}

bool CPositionSet::contains(const Vec3& p) const {
  return std::any_of(pieces_.begin(), pieces_.end(),
                     [&](const ConvexPiece& piece) { return satisfies(piece.halfspaces, p, 0); });
}

std::optional<CPositionSet::InteriorPoint> CPositionSet::interior_point() const {
  std::optional<InteriorPoint> best;
  for (const ConvexPiece& piece : pieces_) {
    Vec3 c = Vec3::Zero();
    for (const Vec3& v : piece.vertices) c += v;
    c /= static_cast<double>(piece.vertices.size());
    double depth = std::numeric_limits<double>::infinity();
    for (const HalfSpace& h : piece.halfspaces) depth = std::min(depth, h.offset - h.normal.dot(c));
    if (!best || depth > best->depth) best = InteriorPoint{c, depth};
  }
  if (!best || best->depth < kMinCommandDepth * diagonal()) return std::nullopt;
  return best;
}

}  // namespace cmt::planner

// Floating-point queries on a built C-space: distances, point classification, nearest atom. The construction
// itself is exact (cspace_builder.cc); these queries take explicit tolerances from their callers.
#include "models/cspace.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "models/polygon_distance.h"

namespace cmt {

const char* atom_kind_name(AtomKind kind) {
  switch (kind) {
    case AtomKind::kFace:
      return "face";
    case AtomKind::kEdge:
      return "edge";
    case AtomKind::kVertex:
      return "vertex";
  }
  return "face";
}

const char* edge_shape_name(EdgeShape shape) {
  switch (shape) {
    case EdgeShape::kConcave:
      return "concave";
    case EdgeShape::kConvex:
      return "convex";
    case EdgeShape::kFlat:
      return "flat";
    case EdgeShape::kNonManifold:
      return "non-manifold";
  }
  return "flat";
}

AtomKind CSpace::atom_kind(int atom_id) const {
  const int nf = static_cast<int>(faces_.size()), ne = static_cast<int>(edges_.size());
  if (atom_id < nf) return AtomKind::kFace;
  if (atom_id < nf + ne) return AtomKind::kEdge;
  return AtomKind::kVertex;
}

int CSpace::atom_index(int atom_id) const {
  const int nf = static_cast<int>(faces_.size()), ne = static_cast<int>(edges_.size());
  if (atom_id < nf) return atom_id;
  if (atom_id < nf + ne) return atom_id - nf;
  return atom_id - nf - ne;
}

std::string CSpace::atom_name(int atom_id) const {
  static const char prefix[] = {'f', 'e', 'v'};
  return prefix[static_cast<int>(atom_kind(atom_id))] + std::to_string(atom_index(atom_id));
}

double CSpace::distance_to_atom(const Vec3& p, int atom_id) const {
  switch (atom_kind(atom_id)) {
    case AtomKind::kFace: {
      const Face& f = faces_[atom_index(atom_id)];
      return distance_to_convex_polygon(p, f.polygon, f.normal);
    }
    case AtomKind::kEdge: {
      const Edge& e = edges_[atom_index(atom_id)];
      return distance_to_segment(p, e.a, e.b);
    }
    case AtomKind::kVertex:
      return (p - vertices_[atom_index(atom_id)].point).norm();
  }
  return std::numeric_limits<double>::infinity();
}

double CSpace::distance_to_surface(const Vec3& p) const {
  double best = std::numeric_limits<double>::infinity();
  for (const Face& f : faces_) best = std::min(best, distance_to_convex_polygon(p, f.polygon, f.normal));
  return best;
}

PointClass CSpace::classify(const Vec3& p, double tolerance) const {
  if (distance_to_surface(p) <= tolerance) return PointClass::kOnSurface;
  if (has_bounds_) {
    for (int k = 0; k < 3; ++k) {
      if (planar_ && k == 1) continue;  // the y slab of a planar task is not a wall
      if (p[k] < bounds_.min[k] || p[k] > bounds_.max[k]) return PointClass::kInsideObstacle;
    }
  }
  for (const ConvexObstacle& ob : obstacles_) {
    bool inside = true;
    for (std::size_t k = 0; k < ob.normals.size() && inside; ++k)
      inside = ob.normals[k].dot(p) < ob.offsets[k];
    if (inside) return PointClass::kInsideObstacle;
  }
  return PointClass::kFree;
}

bool CSpace::covered_by_bounds(const Vec3& n, double d) const {
  if (!has_bounds_) return false;
  // An axis facet's normal is exact (its other coefficients are exact zeros), but its offset is a quotient of
  // two rounded doubles: a facet on the bounds plane may come out an ulp or two inside it.
  const double tol = kBoundsPlaneRelativeTolerance * scale_;
  for (int k = 0; k < 3; ++k) {
    if (planar_ && k == 1) continue;
    if (n == Vec3::Unit(k)) return d >= bounds_.max[k] - tol;
    if (n == -Vec3::Unit(k)) return -d <= bounds_.min[k] + tol;
  }
  return false;
}

double CSpace::solid_depth(const Vec3& p) const {
  double deepest = 0;
  for (const ConvexObstacle& ob : obstacles_) {
    double depth = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < ob.normals.size() && depth > 0; ++k)
      if (!covered_by_bounds(ob.normals[k], ob.offsets[k]))
        depth = std::min(depth, ob.offsets[k] - ob.normals[k].dot(p));
    if (std::isfinite(depth)) deepest = std::max(deepest, depth);
  }
  return deepest;
}

int CSpace::nearest_atom(const Vec3& p, double tolerance) const {
  const int nf = static_cast<int>(faces_.size()), ne = static_cast<int>(edges_.size());
  const int ranges[3][2] = {{nf + ne, atom_count()}, {nf, nf + ne}, {0, nf}};  // vertices, edges, faces
  for (const auto& range : ranges) {
    int best = -1;
    double best_d = tolerance;
    for (int id = range[0]; id < range[1]; ++id) {
      const double d = distance_to_atom(p, id);
      if (d <= best_d) {
        best = id;
        best_d = d;
      }
    }
    if (best >= 0) return best;
  }
  return -1;
}

}  // namespace cmt

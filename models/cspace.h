// The configuration space of a robot that translates in 3-D (Buckley ch. 2, §6.1): C-obstacles, the boundary
// of free space decomposed into atoms (open convex faces, open edges, vertices; Buckley L1677, L1846) with
// their adjacency, outward normals and friction. Built once from a Task by exact construction
// (cspace_builder.cc, CGAL Epeck) and immutable afterwards; coordinates are stored as doubles rounded from
// the exact values.
#pragma once

#include <string>
#include <vector>

#include "models/task.h"

namespace cmt {

enum class AtomKind { kFace, kEdge, kVertex };
const char* atom_kind_name(AtomKind kind);

// How the free space meets an edge. Concave: the free-space dihedral angle is < pi, so the robot can touch
// both faces at once (a corner it can be pushed into). Convex: an obstacle corner (angle > pi). Flat: the two
// faces are coplanar pieces of one plane split into convex parts. Non-manifold: more than two faces meet.
enum class EdgeShape { kConcave, kConvex, kFlat, kNonManifold };
const char* edge_shape_name(EdgeShape shape);

struct Face {
  int id = 0;                 // atom id (faces come first)
  Vec3 normal;                // unit outward normal, pointing into free space
  double offset = 0;          // plane: normal . x == offset
  std::vector<Vec3> polygon;  // convex, counter-clockwise seen from free space, corners only
  double friction = 0;        // Coulomb coefficient of the part pair that generates the face
  std::vector<int> edges;     // atom ids of the edges on its boundary
  std::vector<int> vertices;  // atom ids of the vertices on its boundary
};

struct Edge {
  int id = 0;
  Vec3 a, b;                       // end points (the vertices vertex_a, vertex_b)
  int vertex_a = 0, vertex_b = 0;  // atom ids
  std::vector<int> faces;          // atom ids of the faces it bounds
  EdgeShape shape = EdgeShape::kFlat;
};

struct Vertex {
  int id = 0;
  Vec3 point;
  std::vector<int> faces;  // atom ids
  std::vector<int> edges;  // atom ids
};

// A convex C-obstacle as half-spaces normal . x <= offset (unit outward normals), with its vertices.
struct ConvexObstacle {
  std::vector<Vec3> normals;
  std::vector<double> offsets;
  std::vector<Vec3> vertices;
  double friction = 0;
  std::string source;  // the parts it comes from, e.g. "robot[0] x environment[2]"
};

enum class PointClass { kFree, kOnSurface, kInsideObstacle };

// How far inside a bounds plane (relative to the scene scale) an axis facet of a C-obstacle still counts as
// lying on it (CSpace::covered_by_bounds): far above the rounding of a facet's double offset (a few ulps,
// ~1e-16 relative), far below any feature of a task.
inline constexpr double kBoundsPlaneRelativeTolerance = 1e-9;

// Physical form: C-obstacle vertex coordinates (exact differences o - r of environment and robot coordinates)
// and bounds coordinates within this fraction of the parts' extent of each other along an axis are taken as
// one of their values (CSpace::build; a coordinate no other comes near is kept). Differences that are equal
// in the task (adjacent boxes, a part flush with another or with the bounds) come out a few ulps of the
// largest coordinate apart when the task's decimal coordinates are rounded to doubles far from the origin
// (1e4 mm: ~1e-12 mm), and the exact construction would build sliver faces between the planes; every feature
// of a task is far wider than 1e-9 of its extent.
inline constexpr double kCoincidentCoordinateRelativeTolerance = 1e-9;

class CSpace {
 public:
  // Builds the C-space of `task` (exact arithmetic). Throws TaskError on degenerate geometry.
  static CSpace build(const Task& task);

  const std::vector<Face>& faces() const { return faces_; }
  const std::vector<Edge>& edges() const { return edges_; }
  const std::vector<Vertex>& vertices() const { return vertices_; }
  const std::vector<ConvexObstacle>& obstacles() const { return obstacles_; }
  int atom_count() const { return static_cast<int>(faces_.size() + edges_.size() + vertices_.size()); }
  AtomKind atom_kind(int atom_id) const;
  // Index of an atom within its kind's list.
  int atom_index(int atom_id) const;
  std::string atom_name(int atom_id) const;  // "f3", "e10", "v2"

  // The closing box (task bounds), if any; outside it everything is obstacle.
  bool has_bounds() const { return has_bounds_; }
  const AxisBox& bounds() const { return bounds_; }
  bool planar() const { return planar_; }
  // Length scale of the scene: diagonal of the bounding box of all atoms (tolerances are relative to it).
  double scale() const { return scale_; }

  // Euclidean distance from p to the closed contact surface (union of closed faces).
  double distance_to_surface(const Vec3& p) const;
  // Free, on the surface (within `tolerance`), or strictly inside an obstacle / outside the bounds.
  PointClass classify(const Vec3& p, double tolerance) const;
  // Whether the outside of the bounds covers the facet n . x <= d of a C-obstacle: an axis facet (n = +-e_k)
  // on or beyond the bounds plane it faces (within kBoundsPlaneRelativeTolerance x scale, the rounding of
  // the facet's double offset), so that only solid lies beyond it (a planar task's y slab is not a wall).
  // False without bounds.
  bool covered_by_bounds(const Vec3& n, double d) const;
  // How deep p lies in the solid (the C-obstacles and the outside of the bounds), a lower bound: the largest,
  // over the convex C-obstacles, of the distance from p to their facets that the bounds do not cover (an
  // axis facet on or beyond the bounds plane it faces has only solid beyond it); 0 when p is in none. A ball
  // of that radius about p lies in the solid.
  double solid_depth(const Vec3& p) const;
  // The lowest-dimensional atom within `tolerance` of p (vertex before edge before face), or -1.
  int nearest_atom(const Vec3& p, double tolerance) const;
  // Distance from p to the closure of one atom.
  double distance_to_atom(const Vec3& p, int atom_id) const;

 private:
  friend class CSpaceBuilder;
  std::vector<Face> faces_;
  std::vector<Edge> edges_;
  std::vector<Vertex> vertices_;
  std::vector<ConvexObstacle> obstacles_;
  AxisBox bounds_;
  bool has_bounds_ = false;
  bool planar_ = false;
  double scale_ = 1;
};

}  // namespace cmt

// Sets of commanded positions, the "cpositions" of Buckley's arcs (§6.6.2, §6.7): finite unions of closed
// convex polyhedra in half-space form, each clipped to the planner's domain box so that every piece is a
// bounded polytope with its vertices listed. Set algebra on the half-spaces (intersection: the union of the
// pieces' pairwise intersections; difference: the split of a convex piece by the facets of the subtracted
// one); a piece's faces and vertices come from clipping the domain box by its half-spaces in double
// arithmetic, each relaxed by one named slack (kPieceSlack).
#pragma once

#include <optional>
#include <vector>

#include "models/task.h"
#include "verifier/polyhedron.h"

namespace cmt::planner {

// A piece is dropped as empty only when no point satisfies all its half-spaces with each relaxed by
// kPieceSlack x the domain's diagonal; its listed half-spaces are those that own a face of that relaxed
// polytope, and a piece is not split off a difference where it lies within the slack of the subtracted
// facet. The sets are thus exact up to slivers of about that width; commanded positions are chosen
// kMinCommandDepth x the diagonal (10^4 times deeper) inside their piece, and every planned strategy is
// checked by the verifier.
inline constexpr double kPieceSlack = 1e-10;
inline constexpr double kMinCommandDepth = 1e-6;

struct ConvexPiece {
  std::vector<HalfSpace> halfspaces;  // normal . x <= offset, unit normals, none redundant
  std::vector<Vec3> vertices;         // its corners
};

class CPositionSet {
 public:
  CPositionSet() = default;
  // The whole domain box, or nothing.
  static CPositionSet domain(const AxisBox& box);
  static CPositionSet none(const AxisBox& box);
  // The convex set of the half-spaces, within the box.
  static CPositionSet convex(const std::vector<HalfSpace>& halfspaces, const AxisBox& box);
  // A Polyhedron of any kind (a complement becomes the disjoint pieces outside one facet and inside the
  // ones before it), or a union of them, within the box.
  static CPositionSet of(const Polyhedron& polyhedron, const AxisBox& box);
  static CPositionSet of_union(const std::vector<Polyhedron>& polyhedra, const AxisBox& box);

  CPositionSet intersect(const CPositionSet& other) const;
  CPositionSet minus(const CPositionSet& other) const;
  CPositionSet unite(const CPositionSet& other) const;  // pieces concatenated (they may overlap)

  bool empty() const { return pieces_.empty(); }
  bool contains(const Vec3& p) const;  // exact half-space tests, no slack
  const std::vector<ConvexPiece>& pieces() const { return pieces_; }
  const AxisBox& box() const { return box_; }
  double diagonal() const { return (box_.max - box_.min).norm(); }

  // A point deep inside one piece: the vertex centroid of the piece where it is deepest, with its depth (the
  // least distance to a facet of that piece). Nothing when no piece holds a point kMinCommandDepth deep.
  struct InteriorPoint {
    Vec3 point;
    double depth = 0;
  };
  std::optional<InteriorPoint> interior_point() const;

 private:
  CPositionSet(const AxisBox& box) : box_(box) {}
  void add_piece(std::vector<HalfSpace> halfspaces);

  AxisBox box_;
  std::vector<ConvexPiece> pieces_;
};

// The six half-spaces of an axis box.
std::vector<HalfSpace> box_halfspaces(const AxisBox& box);

}  // namespace cmt::planner

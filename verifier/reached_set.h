// A set of contact points on the C-space surface (Buckley ch. 4): the start of a motion, its forward
// projection, its termination set. Per face: regions in the face's 2-D chart (closed, on the grid of
// kRegionCell, rounded outward) plus 1-D and 0-D seeds (segments, points: a start segment lies in a face
// without area); per edge: closed intervals of the parameter t in [0, 1] along a -> b; per vertex: a flag.
// CGAL and Clipper types stay in the .cc files (verifier/internal/face_regions.h); this header is free of
// them.
#pragma once

#include <memory>
#include <vector>

#include "models/loaded_task.h"

namespace cmt {

// The region kernel's grid (docs/verifier.md, "Region kernel"): face regions have vertices on multiples of
// region_cell(scale) in chart coordinates (task units), 2^-36 of the scene scale rounded up to a power of
// two. A polygon entering a region is rounded outward onto the grid, one subtracted inward; an overlay
// rounds the crossings it creates to the nearest grid point (at most 0.71 cell). Chart coordinates beyond
// kRegionRangeCells cells from the origin are a std::range_error (accepted tasks stay far inside).
inline constexpr int kRegionCellBits = 36;
inline constexpr double kRegionRangeCells = 0x1p60;
double region_cell(double scale);

struct EdgeInterval {
  double t0 = 0, t1 = 0;  // 0 <= t0 <= t1 <= 1, along edge a -> b
};

// One output piece in task coordinates (doubles): a face region (outer boundary, counter-clockwise about the
// face normal, with holes), a segment (2 points) or a point (1 point) on a face, an edge interval (2 points,
// or 1 when degenerate), or a vertex (1 point).
struct ReachedPiece {
  int atom = -1;
  AtomKind kind = AtomKind::kFace;
  std::vector<Vec3> polygon;
  std::vector<std::vector<Vec3>> holes;
  double area = 0;  // face regions only
};

class ReachedSet {
 public:
  struct Impl;  // verifier/internal/face_regions.h

  explicit ReachedSet(const CSpace& cspace);
  ~ReachedSet();
  ReachedSet(const ReachedSet& other);
  ReachedSet& operator=(const ReachedSet& other);
  ReachedSet(ReachedSet&&) noexcept;
  ReachedSet& operator=(ReachedSet&&) noexcept;

  // Locates a task region (start or goal) on the atoms it lies on, within LoadedTask::surface_tolerance():
  // a point goes to CSpace::nearest_atom; a segment or polygon is clipped (in the chart) to every
  // face whose plane holds it and, for a segment, to every edge whose line holds it. The closure is added
  // (edge intervals and vertices covered by the face parts). In a planar task a region stands for its
  // extrusion across the y slab (a point becomes a segment along y, a segment a rectangle). Throws TaskError
  // when a region sample is on no located piece. With `partial`, the located part alone, possibly empty (a
  // goal in a slice of a task with model error may leave the surface: load_task_slice).
  static ReachedSet from_region(const LoadedTask& task, const Region& region, bool partial = false);
  static ReachedSet from_regions(const LoadedTask& task, const std::vector<Region>& regions,
                                 bool partial = false);
  // The inverse of pieces(), for sets stored as pieces (JSON): face pieces of 3+ points are regions (outer
  // boundary minus holes; where rounding to doubles broke a ring, a superset: the outer boundary's convex
  // hull, the hole not subtracted), of 2 or 1 points segments and points; an edge piece's ends become
  // parameters on its edge (clamped to [0, 1]); vertices as they are.
  static ReachedSet from_pieces(const CSpace& cspace, const std::vector<ReachedPiece>& pieces);

  const CSpace& cspace() const;

  // Building blocks (coordinates in task units; face inputs are projected into the face's chart).
  void add_whole_atom(int atom_id);
  void add_face_polygon(int face_atom, const std::vector<Vec3>& convex_polygon);
  void add_face_segment(int face_atom, const Vec3& a, const Vec3& b);
  void add_face_point(int face_atom, const Vec3& p);
  void add_edge_interval(int edge_atom, double t0, double t1);
  void add_vertex(int vertex_atom);
  // Adds the edge intervals and vertices covered by the closed face parts.
  void add_boundary_closure();
  void unite(const ReachedSet& other);
  // Only the atoms with keep[atom] true.
  ReachedSet restricted(const std::vector<bool>& keep) const;

  // The part of this set inside the closed axis box (verifier/reached_set_clip.cc): face regions, segments
  // and points by the face polygon clipped by the box's six planes in the face's chart (regions on the grid);
  // edge intervals in doubles rounded outward by kEdgeParamSlack; vertices by a double comparison. Where the
  // box meets a face only in a segment or a point (its plane touches the box along an edge or at a corner),
  // that whole contact is kept when the face holds anything: an over-approximation, as callers need (sensing
  // termination, §4.5).
  ReachedSet within_box(const AxisBox& box) const;
  // This set less the part inside the closed axis box, never removing more than that part (the dual of
  // within_box, for the points that surely pass a sensing test, Buckley Def 4.2): face regions by their
  // difference on the grid (the box's polygon rounded outward: the remainder may lose up to 1.5 cells more
  // than the box; callers pass a box shrunk by a margin far above that), face segments and points exactly;
  // edge intervals lose only the box's interval shrunk by kEdgeParamSlack where it cuts the edge (not at an
  // edge end inside the box); vertices are removed by a double comparison, so callers pass a box already
  // shrunk by a margin above rounding.
  ReachedSet without_box(const AxisBox& box) const;
  // The intersection with another set on the same C-space: face regions by their overlay on the grid (its
  // crossings rounded to the nearest grid point), face segments clipped exactly to the other set's region
  // pieces and segments, points by exact membership, edge intervals and vertices exactly.
  ReachedSet intersected(const ReachedSet& other) const;

  bool empty() const;
  bool contains_atom(int atom_id) const;
  std::vector<int> atoms() const;  // ascending ids of atoms with a non-empty part
  double face_area(int face_atom) const;
  double area() const;  // sum over faces
  std::vector<EdgeInterval> edge_intervals(int edge_atom) const;
  bool has_vertex(int vertex_atom) const;
  // Is p (projected into the face's chart, rounded to the nearest grid point) in the closed region of the
  // face (regions only)?
  bool face_region_contains(int face_atom, const Vec3& p) const;
  // Euclidean distance (task units) from p to the closed set: face regions (with holes), face segments and
  // points, edge intervals, vertices; +infinity when the set is empty. Floating point, for comparison with
  // tolerances far above rounding (verifier/reached_set_distance.cc).
  double distance(const Vec3& p) const;

  std::vector<ReachedPiece> pieces() const;
  // The pieces of this set not contained in `container`: face regions by their difference on the grid (a
  // remainder within `tolerance` of the container's closed parts is contained, else it is reported); face
  // segments/points, edge intervals and vertices within `tolerance` (task units) of the container's closed
  // face regions, edge intervals or vertices count as contained.
  std::vector<ReachedPiece> pieces_outside(const ReachedSet& container, double tolerance) const;

  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace cmt

// Private to verifier/ .cc files: the worklists of the fixpoints over a ReachedSet (Buckley Alg 4.1 steps
// 1-3 forward, Alg 5.2 backward): what was added to the set and is not processed yet.
#pragma once

#include <vector>

#include "verifier/internal/face_regions.h"
#include "verifier/internal/fixpoint.h"

namespace cmt::face_geometry {

// A face part's boundary on the face's edges and vertices (the same points): each edge's parameter interval
// inside a part (rounded outward by kEdgeParamSlack) and each vertex inside one.
template <class AddInterval, class AddVertex>
void add_boundary_closure(const ReachedSet::Impl& r, int fi, const std::vector<Points2>& parts,
                          AddInterval add_interval, AddVertex add_vertex) {
  const CSpace& c = *r.cspace;
  const int nf = static_cast<int>(c.faces().size()), ne = static_cast<int>(c.edges().size());
  const Face& face = c.faces()[fi];
  const FaceChart& chart = r.charts[fi];
  for (const Points2& part : parts) {
    for (int e : face.edges) {
      const Edge& edge = c.edges()[e - nf];
      FT t0, t1;
      if (clip_segment(part, chart.project(edge.a), chart.project(edge.b), &t0, &t1))
        add_interval(e - nf, CGAL::to_interval(t0).first - kEdgeParamSlack,
                     CGAL::to_interval(t1).second + kEdgeParamSlack);
    }
    for (int vid : face.vertices)
      if (inside_closed(part, chart.project(c.vertices()[vid - nf - ne].point))) add_vertex(vid - nf - ne);
  }
}

// The damper projections' worklist (damper_projection.cc, backprojection.cc). The adders store into the set
// and queue only what is new: a face region's growth wider than kRegionGrowthCells, segments and points not
// covered yet, edge growth longer than 4 kEdgeParamSlack (shorter is rounding: stored, not propagated; so is
// an extension of a held interval by at most kRegionGrowthCells region cells, which still reaches an end's
// vertex within that bound), vertices not held yet. Each returns whether something new was queued.
class DamperWorklist {
 public:
  explicit DamperWorklist(ReachedSet::Impl& set);  // everything already in the set is pending

  bool add_region(int fi, const ChartRegion& part);
  bool add_convex(int fi, const Points2& pts);  // a region, a segment or a point by its size
  bool add_segment(int fi, const Point2& a, const Point2& b);
  bool add_point(int fi, const Point2& p);
  void add_interval(int ei, double t0, double t1);
  void add_vertex(int vi);
  void add_closure(int fi, const std::vector<Points2>& parts);  // add_boundary_closure
  // The edge's end vertices that the intervals reach (within kEdgeParamSlack).
  void add_interval_ends(int ei, const std::vector<EdgeInterval>& intervals);

  // The pending parts, removed from the worklist: a face's as convex pieces, segments and points.
  std::vector<Points2> take_face(int fi);
  std::vector<EdgeInterval> take_edge(int ei);
  void take_vertex(int vi) { vertex_[vi] = 0; }

  // Processes every pending part until nothing is pending or `steps` passes max_steps (sweep_until_stable);
  // true when work was still pending at the cap.
  template <class Face, class Edge, class Vertex>
  bool run(const int& steps, int max_steps, Face face, Edge edge, Vertex vertex) {
    return sweep_until_stable(
        static_cast<int>(region_.size()), static_cast<int>(edge_.size()), static_cast<int>(vertex_.size()),
        steps, max_steps,
        [&](int fi) { return !region_[fi].is_empty() || !seg_[fi].empty() || !pt_[fi].empty(); }, face,
        [&](int ei) { return !edge_[ei].empty(); }, edge, [&](int vi) { return vertex_[vi] != 0; }, vertex);
  }

 private:
  ReachedSet::Impl& reached_impl_;
  std::vector<ChartRegion> region_;
  std::vector<std::vector<Points2>> seg_, pt_;
  std::vector<std::vector<EdgeInterval>> edge_;
  std::vector<char> vertex_;
};

}  // namespace cmt::face_geometry

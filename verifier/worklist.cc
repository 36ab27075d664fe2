// The damper projections' worklist (verifier/internal/worklist.h).
#include "verifier/internal/worklist.h"

#include <algorithm>
#include <cmath>

namespace cmt::face_geometry {

DamperWorklist::DamperWorklist(ReachedSet::Impl& set) : reached_impl_(set) {
  const std::size_t nf = set.faces.size();
  region_.resize(nf);
  seg_.resize(nf);
  pt_.resize(nf);
  for (std::size_t fi = 0; fi < nf; ++fi) {
    region_[fi] = set.faces[fi].region;
    for (const Segment2& s : set.faces[fi].segments) seg_[fi].push_back({s.source(), s.target()});
    for (const Point2& p : set.faces[fi].points) pt_[fi].push_back({p});
  }
  edge_ = set.edges;
  vertex_ = set.vertices;
}

bool DamperWorklist::add_region(int fi, const ChartRegion& part) {
  ChartRegion added;
  if (!reached_impl_.add_region(fi, part, &added)) return false;
  region_[fi].join(added);
  return true;
}

bool DamperWorklist::add_convex(int fi, const Points2& pts) {
  if (pts.size() >= 3) return add_region(fi, ChartRegion(to_polygon(pts), reached_impl_.charts[fi].cell));
  if (pts.size() == 2) return add_segment(fi, pts[0], pts[1]);
  if (pts.size() == 1) return add_point(fi, pts[0]);
  return false;
}

bool DamperWorklist::add_segment(int fi, const Point2& a, const Point2& b) {
  if (!reached_impl_.add_segment(fi, a, b)) return false;
  seg_[fi].push_back({a, b});
  return true;
}

bool DamperWorklist::add_point(int fi, const Point2& p) {
  if (!reached_impl_.add_point(fi, p)) return false;
  pt_[fi].push_back({p});
  return true;
}

void DamperWorklist::add_interval(int ei, double t0, double t1) {
  const std::vector<EdgeInterval> before = reached_impl_.edges[ei];
  std::vector<EdgeInterval> added;
  const double fresh = reached_impl_.add_interval(ei, t0, t1, &added);
  if (fresh < 0) return;
  // Growth below the parameter slack is rounding, not reach: stored, not propagated. So is an extension of a
  // held interval by no more than kRegionGrowthCells region cells: the face regions' outward rounding (up to
  // 1.5 cells per overlay) reaches their closure's edges, and without this an edge could creep a cell per
  // round through its faces. A new interval apart from the held ones is reach, however short, and an
  // extension that comes within that bound of an end reaches the end's vertex.
  if (added.size() == 1 && added[0].t0 == added[0].t1) {
    edge_[ei].push_back(added[0]);
    return;
  }
  if (fresh <= 4 * kEdgeParamSlack) return;
  const Edge& e = reached_impl_.cspace->edges()[ei];
  const double rounding =
      kRegionGrowthCells * region_cell(reached_impl_.cspace->scale()) / (e.b - e.a).norm();
  const int first_vertex =
      static_cast<int>(reached_impl_.cspace->faces().size() + reached_impl_.cspace->edges().size());
  for (const EdgeInterval& gap : added) {
    const bool extends = std::any_of(before.begin(), before.end(), [&](const EdgeInterval& held) {
      return std::abs(gap.t0 - held.t1) <= kEdgeParamSlack || std::abs(gap.t1 - held.t0) <= kEdgeParamSlack;
    });
    if (fresh > rounding || !extends) {
      edge_[ei].push_back(gap);
      continue;
    }
    if (gap.t0 <= rounding && e.vertex_a >= 0) add_vertex(e.vertex_a - first_vertex);
    if (gap.t1 >= 1 - rounding && e.vertex_b >= 0) add_vertex(e.vertex_b - first_vertex);
  }
}

void DamperWorklist::add_vertex(int vi) {
  if (reached_impl_.add_vertex(vi)) vertex_[vi] = 1;
}

void DamperWorklist::add_closure(int fi, const std::vector<Points2>& parts) {
  add_boundary_closure(
      reached_impl_, fi, parts, [&](int ei, double t0, double t1) { add_interval(ei, t0, t1); },
      [&](int vi) { add_vertex(vi); });
}

void DamperWorklist::add_interval_ends(int ei, const std::vector<EdgeInterval>& intervals) {
  const CSpace& c = *reached_impl_.cspace;
  const int first_vertex = static_cast<int>(c.faces().size() + c.edges().size());
  const Edge& e = c.edges()[ei];
  for (const EdgeInterval& iv : intervals) {
    if (iv.t0 <= kEdgeParamSlack && e.vertex_a >= 0) add_vertex(e.vertex_a - first_vertex);
    if (iv.t1 >= 1 - kEdgeParamSlack && e.vertex_b >= 0) add_vertex(e.vertex_b - first_vertex);
  }
}

std::vector<Points2> DamperWorklist::take_face(int fi) {
  std::vector<Points2> parts = convex_pieces(region_[fi]);
  region_[fi] = ChartRegion();
  for (Points2& s : seg_[fi]) parts.push_back(std::move(s));
  for (Points2& p : pt_[fi]) parts.push_back(std::move(p));
  seg_[fi].clear();
  pt_[fi].clear();
  return parts;
}

std::vector<EdgeInterval> DamperWorklist::take_edge(int ei) {
  std::vector<EdgeInterval> out = std::move(edge_[ei]);
  edge_[ei].clear();
  return out;
}

}  // namespace cmt::face_geometry

// ReachedSet::within_box and without_box (verifier/reached_set.h): the part of a set of contact points inside
// an axis box (Buckley's weakly consistent positions, §4.5 Def 4.1, of a position set P_s) and the rest
// (removing the strongly consistent ones, Def 4.2, for conditional tests, §4.2).
#include <algorithm>
#include <array>

#include "verifier/internal/face_regions.h"
#include "verifier/reached_set.h"

namespace cmt {

using face_geometry::ChartRegion;
using face_geometry::FT;
using face_geometry::Point2;
using face_geometry::Points2;

namespace {

// The six closed half-spaces of the box, each as a plane whose positive side is the box's side:
// x_k - min_k >= 0 and max_k - x_k >= 0 (exact planes through the double bounds).
std::array<face_geometry::Plane3, 6> box_planes(const AxisBox& box) {
  std::array<face_geometry::Plane3, 6> out;
  for (int k = 0; k < 3; ++k) {
    const FT e[3] = {k == 0 ? 1 : 0, k == 1 ? 1 : 0, k == 2 ? 1 : 0};
    out[2 * k] = face_geometry::Plane3(e[0], e[1], e[2], -FT(box.min[k]));
    out[2 * k + 1] = face_geometry::Plane3(-e[0], -e[1], -e[2], FT(box.max[k]));
  }
  return out;
}

// Parameters of segment a + t (b - a), t in [0, 1], inside the box; false when empty. Floating point: the
// caller rounds the result outward.
bool box_interval(const AxisBox& box, const Vec3& a, const Vec3& b, double* t0, double* t1) {
  double lo = 0, hi = 1;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    if (d == 0) {
      if (a[k] < box.min[k] || a[k] > box.max[k]) return false;
      continue;
    }
    double ta = (box.min[k] - a[k]) / d, tb = (box.max[k] - a[k]) / d;
    if (ta > tb) std::swap(ta, tb);
    lo = std::max(lo, ta);
    hi = std::min(hi, tb);
  }
  if (lo > hi) return false;
  *t0 = lo;
  *t1 = hi;
  return true;
}

// face ∩ box in the face's chart: the convex face polygon clipped by the box's half-spaces restricted to the
// face's plane (exact); fewer than 3 points where the plane only touches the box.
Points2 box_window(const ReachedSet::Impl& in, std::size_t fi,
                   const std::array<face_geometry::Plane3, 6>& planes) {
  Points2 window = in.face_polygon[fi];
  for (const face_geometry::Plane3& pl : planes)
    window = face_geometry::clip(window, face_geometry::restrict_to_chart(pl, in.charts[fi]));
  return window;
}

bool in_box(const AxisBox& box, const Vec3& p) {
  for (int k = 0; k < 3; ++k)
    if (p[k] < box.min[k] || p[k] > box.max[k]) return false;
  return true;
}

}  // namespace

ReachedSet ReachedSet::within_box(const AxisBox& box) const {
  const CSpace& c = cspace();
  ReachedSet out(c);
  Impl& o = *out.impl_;
  const Impl& in = *impl_;
  const std::array<face_geometry::Plane3, 6> planes = box_planes(box);

  for (std::size_t fi = 0; fi < in.faces.size(); ++fi) {
    const face_geometry::FaceSet& fs = in.faces[fi];
    if (fs.empty()) continue;
    const Points2 window = box_window(in, fi, planes);
    if (window.empty()) continue;
    const int f = static_cast<int>(fi);
    if (window.size() >= 3) {
      if (!fs.region.is_empty()) {
        ChartRegion part = fs.region;
        part.intersection(face_geometry::to_polygon(window));
        if (!part.is_empty()) o.add_region(f, part, nullptr);
      }
    } else if (!fs.region.is_empty()) {
      // A lower-dimensional window (the plane touches the box): keep all of it (over-approximation).
      if (window.size() == 2)
        o.add_segment(f, window[0], window[1]);
      else
        o.add_point(f, window[0]);
    }
    for (const face_geometry::Segment2& s : fs.segments) {
      FT t0, t1;
      if (face_geometry::clip_segment(window, s.source(), s.target(), &t0, &t1))
        o.add_segment(f, s.source() + (s.target() - s.source()) * t0,
                      s.source() + (s.target() - s.source()) * t1);
    }
    for (const Point2& p : fs.points)
      if (face_geometry::inside_closed(window, p)) o.add_point(f, p);
  }

  for (std::size_t ei = 0; ei < in.edges.size(); ++ei) {
    if (in.edges[ei].empty()) continue;
    const Edge& e = c.edges()[ei];
    double b0 = 0, b1 = 0;
    if (!box_interval(box, e.a, e.b, &b0, &b1)) continue;
    b0 = std::max(0.0, b0 - kEdgeParamSlack);
    b1 = std::min(1.0, b1 + kEdgeParamSlack);
    for (const EdgeInterval& iv : in.edges[ei]) {
      const double t0 = std::max(iv.t0, b0), t1 = std::min(iv.t1, b1);
      if (t0 <= t1) o.add_interval(static_cast<int>(ei), t0, t1, nullptr);
    }
  }

  for (std::size_t vi = 0; vi < in.vertices.size(); ++vi)
    if (in.vertices[vi] && in_box(box, c.vertices()[vi].point)) o.add_vertex(static_cast<int>(vi));
  return out;
}

ReachedSet ReachedSet::without_box(const AxisBox& box) const {
  const CSpace& c = cspace();
  ReachedSet out(c);
  Impl& o = *out.impl_;
  const Impl& in = *impl_;
  const std::array<face_geometry::Plane3, 6> planes = box_planes(box);

  for (std::size_t fi = 0; fi < in.faces.size(); ++fi) {
    const face_geometry::FaceSet& fs = in.faces[fi];
    if (fs.empty()) continue;
    const int f = static_cast<int>(fi);
    const Points2 window = box_window(in, fi, planes);
    if (!fs.region.is_empty()) {
      ChartRegion rest = fs.region;
      // A window without area removes nothing from a regularized region.
      if (window.size() >= 3) rest.difference(face_geometry::to_polygon(window));
      if (!rest.is_empty()) o.add_region(f, rest, nullptr);
    }
    for (const face_geometry::Segment2& s : fs.segments) {
      FT t0, t1;
      if (window.empty() || !face_geometry::clip_segment(window, s.source(), s.target(), &t0, &t1)) {
        o.add_segment(f, s.source(), s.target());
        continue;
      }
      // Keep the closed parts before t0 and after t1.
      const auto at = [&](const FT& t) { return s.source() + (s.target() - s.source()) * t; };
      if (t0 > 0) o.add_segment(f, s.source(), at(t0));
      if (t1 < 1) o.add_segment(f, at(t1), s.target());
    }
    for (const Point2& p : fs.points)
      if (window.empty() || !face_geometry::inside_closed(window, p)) o.add_point(f, p);
  }

  for (std::size_t ei = 0; ei < in.edges.size(); ++ei) {
    if (in.edges[ei].empty()) continue;
    const Edge& e = c.edges()[ei];
    double b0 = 0, b1 = 0;
    const bool cut = box_interval(box, e.a, e.b, &b0, &b1);
    // The removed interval, shrunk where it cuts the edge (a rounded parameter): what is removed is surely
    // inside the box. An end of the edge inside the box (0 or 1, decided on the same double point as the
    // vertex below) is not shrunk, so an edge inside the box goes whole.
    if (b0 > 0) b0 += kEdgeParamSlack;
    if (b1 < 1) b1 -= kEdgeParamSlack;
    for (const EdgeInterval& iv : in.edges[ei]) {
      if (!cut || b0 >= b1 || iv.t1 < b0 || iv.t0 > b1) {
        o.add_interval(static_cast<int>(ei), iv.t0, iv.t1, nullptr);
        continue;
      }
      if (iv.t0 < b0) o.add_interval(static_cast<int>(ei), iv.t0, b0, nullptr);
      if (iv.t1 > b1) o.add_interval(static_cast<int>(ei), b1, iv.t1, nullptr);
    }
  }

  for (std::size_t vi = 0; vi < in.vertices.size(); ++vi)
    if (in.vertices[vi] && !in_box(box, c.vertices()[vi].point)) o.add_vertex(static_cast<int>(vi));
  return out;
}

namespace {

// The part of segment [a, b] in the closed face set `other` (its region's convex pieces, its segments where
// collinear and overlapping, its points on the segment), added to `out`'s face fi.
void intersect_segment(const face_geometry::FaceSet& other, int fi, const Point2& a, const Point2& b,
                       ReachedSet::Impl& out) {
  const face_geometry::Segment2 seg(a, b);
  if (!other.region.is_empty())
    for (const Points2& piece : face_geometry::convex_pieces(other.region)) {
      FT t0, t1;
      if (face_geometry::clip_segment(piece, a, b, &t0, &t1))
        out.add_segment(fi, a + t0 * (b - a), a + t1 * (b - a));
    }
  for (const face_geometry::Segment2& o : other.segments) {
    const auto x = CGAL::intersection(seg, o);
    if (!x) continue;
    if (const Point2* p = boost::get<Point2>(&*x)) out.add_point(fi, *p);
    if (const face_geometry::Segment2* q = boost::get<face_geometry::Segment2>(&*x))
      out.add_segment(fi, q->source(), q->target());
  }
  for (const Point2& p : other.points)
    if (seg.has_on(p)) out.add_point(fi, p);
}

}  // namespace

ReachedSet ReachedSet::intersected(const ReachedSet& other) const {
  const Impl& a = *impl_;
  const Impl& b = *other.impl_;
  ReachedSet out(cspace());
  Impl& o = *out.impl_;
  for (std::size_t fi = 0; fi < a.faces.size(); ++fi) {
    const face_geometry::FaceSet& fa = a.faces[fi];
    const face_geometry::FaceSet& fb = b.faces[fi];
    if (fa.empty() || fb.empty()) continue;
    const int f = static_cast<int>(fi);
    if (!fa.region.is_empty() && !fb.region.is_empty()) {
      ChartRegion part = fa.region;
      part.intersection(fb.region);
      if (!part.is_empty()) o.add_region(f, part, nullptr);
    }
    // Segments and points of each set against the whole of the other (regions, segments, points).
    for (const face_geometry::Segment2& seg : fa.segments)
      intersect_segment(fb, f, seg.source(), seg.target(), o);
    for (const face_geometry::Segment2& seg : fb.segments) {
      face_geometry::FaceSet region_only;
      region_only.region = fa.region;
      intersect_segment(region_only, f, seg.source(), seg.target(), o);
    }
    for (const Point2& p : fa.points)
      if (b.covered(f, p)) o.add_point(f, p);
    for (const Point2& p : fb.points)
      if (!fa.region.is_empty() && fa.region.oriented_side(p) != CGAL::ON_NEGATIVE_SIDE) o.add_point(f, p);
  }
  for (std::size_t ei = 0; ei < a.edges.size(); ++ei)
    for (const EdgeInterval& x : a.edges[ei])
      for (const EdgeInterval& y : b.edges[ei]) {
        const double t0 = std::max(x.t0, y.t0), t1 = std::min(x.t1, y.t1);
        if (t0 <= t1) o.add_interval(static_cast<int>(ei), t0, t1, nullptr);
      }
  for (std::size_t vi = 0; vi < a.vertices.size(); ++vi) o.vertices[vi] = a.vertices[vi] && b.vertices[vi];
  return out;
}

}  // namespace cmt

// Exact 2-D stage of the C-space construction: Boolean operations on the facets lying in one plane and the
// convex decomposition of the resulting regions into faces (Buckley §6.1: atoms are convex faces).
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "models/internal/exact_kernel.h"

namespace cmt::exact {
namespace {

using Polygon2 = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles2 = CGAL::Polygon_with_holes_2<Kernel>;
using PolygonSet2 = CGAL::Polygon_set_2<Kernel>;
using Segment2 = Kernel::Segment_2;
using Ray2 = Kernel::Ray_2;
using Traits = CGAL::Arr_segment_traits_2<Kernel>;
using Arrangement = CGAL::Arrangement_2<Traits>;

// Removes repeated and collinear points of a closed polygon.
Polygon2Points strip_collinear(const Polygon2Points& in) {
  Polygon2Points pts;
  for (const Point2& p : in)
    if (pts.empty() || pts.back() != p) pts.push_back(p);
  while (pts.size() > 1 && pts.front() == pts.back()) pts.pop_back();
  bool changed = true;
  while (changed && pts.size() >= 3) {
    changed = false;
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const Point2& a = pts[(i + pts.size() - 1) % pts.size()];
      const Point2& c = pts[(i + 1) % pts.size()];
      if (CGAL::collinear(a, pts[i], c)) {
        pts.erase(pts.begin() + static_cast<std::ptrdiff_t>(i));
        changed = true;
        break;
      }
    }
  }
  return pts;
}

// A convex polygon as a counter-clockwise Polygon_2 (the hull of its points; degenerate input gives empty).
std::optional<Polygon2> convex_ccw(const Polygon2Points& pts) {
  Polygon2Points hull;
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
  if (hull.size() < 3) return std::nullopt;
  return Polygon2(hull.begin(), hull.end());
}

Polygon2Points points_of(const Polygon2& p) { return Polygon2Points(p.vertices_begin(), p.vertices_end()); }

}  // namespace

std::vector<RegionWithHoles> planar_region(const std::vector<Polygon2Points>& below,
                                           const std::vector<Polygon2Points>& above,
                                           const Polygon2Points& clip, bool use_clip) {
  PolygonSet2 set;
  for (const auto& b : below)
    if (auto p = convex_ccw(b)) set.join(*p);
  for (const auto& a : above)
    if (auto p = convex_ccw(a)) set.difference(*p);
  if (use_clip) {
    auto c = convex_ccw(clip);
    if (!c) return {};
    set.intersection(*c);
  }
  std::vector<PolygonWithHoles2> pieces;
  set.polygons_with_holes(std::back_inserter(pieces));
  std::vector<RegionWithHoles> out;
  for (const auto& pwh : pieces) {
    RegionWithHoles r;
    r.outer = strip_collinear(points_of(pwh.outer_boundary()));
    for (auto h = pwh.holes_begin(); h != pwh.holes_end(); ++h)
      r.holes.push_back(strip_collinear(points_of(*h)));
    if (r.outer.size() >= 3) out.push_back(std::move(r));
  }
  return out;
}

std::vector<Polygon2Points> convex_pieces(const RegionWithHoles& region) {
  if (region.holes.empty()) {
    Polygon2 outer(region.outer.begin(), region.outer.end());
    if (outer.is_convex()) return {region.outer};
  }
  // Boundary loops, each directed with the region on its left (outer CCW, holes CW).
  std::vector<Polygon2Points> loops{region.outer};
  for (const auto& h : region.holes) loops.push_back(h);
  std::vector<Segment2> segments;
  struct Reflex {
    Point2 at, prev, next;
  };
  std::vector<Reflex> reflex;
  for (const auto& loop : loops) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      segments.emplace_back(loop[i], loop[(i + 1) % n]);
      const Point2& prev = loop[(i + n - 1) % n];
      const Point2& next = loop[(i + 1) % n];
      if (CGAL::orientation(prev, loop[i], next) == CGAL::RIGHT_TURN) reflex.push_back({loop[i], prev, next});
    }
  }
  // Deterministic cut order, independent of how the Boolean stage ordered the loops.
  std::sort(reflex.begin(), reflex.end(),
            [](const Reflex& a, const Reflex& b) { return CGAL::compare_xy(a.at, b.at) == CGAL::SMALLER; });
  for (const Reflex& r : reflex) {
    const Kernel::Vector_2 d_in = r.at - r.prev;   // continue the incoming edge
    const Kernel::Vector_2 d_out = r.at - r.next;  // continue the outgoing edge backwards
    // Prefer the direction most aligned with the second axis: compare y^2/|d|^2 exactly.
    const FT a_in = d_in.y() * d_in.y() * d_out.squared_length();
    const FT a_out = d_out.y() * d_out.y() * d_in.squared_length();
    const Ray2 ray(r.at, a_out > a_in ? d_out : d_in);
    std::optional<Point2> hit;
    FT best = 0;
    for (const Segment2& s : segments) {
      if (s.source() == r.at || s.target() == r.at) continue;
      const auto x = CGAL::intersection(ray, s);
      if (!x) continue;
      Point2 candidate;
      if (const Point2* p = boost::get<Point2>(&*x)) {
        candidate = *p;
      } else if (const Segment2* seg = boost::get<Segment2>(&*x)) {
        candidate = CGAL::has_smaller_distance_to_point(r.at, seg->source(), seg->target()) ? seg->source()
                                                                                            : seg->target();
      } else {
        continue;
      }
      if (candidate == r.at) continue;
      const FT dist = CGAL::squared_distance(r.at, candidate);
      if (!hit || dist < best) {
        hit = candidate;
        best = dist;
      }
    }
    if (hit) segments.emplace_back(r.at, *hit);
  }

  Arrangement arrangement;
  CGAL::insert(arrangement, segments.begin(), segments.end());
  PolygonSet2 inside;
  {
    Polygon2 outer(region.outer.begin(), region.outer.end());
    std::vector<Polygon2> holes;
    for (const auto& h : region.holes) holes.emplace_back(h.begin(), h.end());
    inside.insert(PolygonWithHoles2(outer, holes.begin(), holes.end()));
  }
  std::vector<Polygon2Points> pieces;
  for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f) {
    if (f->is_unbounded() || f->number_of_holes() > 0) continue;
    Polygon2Points pts;
    auto curr = f->outer_ccb();
    const auto first = curr;
    do {
      pts.push_back(curr->source()->point());
    } while (++curr != first);
    pts = strip_collinear(pts);
    if (pts.size() < 3) continue;
    Polygon2 poly(pts.begin(), pts.end());
    if (!poly.is_simple() || !poly.is_convex()) continue;  // not a piece of the region (pieces are convex)
    FT cx = 0, cy = 0;
    for (const Point2& p : pts) {
      cx += p.x();
      cy += p.y();
    }
    const Point2 centroid(cx / static_cast<int>(pts.size()), cy / static_cast<int>(pts.size()));
    if (inside.oriented_side(centroid) != CGAL::ON_POSITIVE_SIDE) continue;
    if (poly.is_clockwise_oriented()) std::reverse(pts.begin(), pts.end());
    pieces.push_back(std::move(pts));
  }
  // Soundness check: the pieces must tile the region exactly (no surface may be lost).
  FT region_area = Polygon2(region.outer.begin(), region.outer.end()).area();
  for (const auto& h : region.holes) region_area -= CGAL::abs(Polygon2(h.begin(), h.end()).area());
  FT pieces_area = 0;
  for (const auto& p : pieces) pieces_area += Polygon2(p.begin(), p.end()).area();
  if (pieces_area != region_area)
    throw std::logic_error("convex decomposition lost area (internal error): please report the task file");
  return pieces;
}

}  // namespace cmt::exact

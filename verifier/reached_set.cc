// ReachedSet (verifier/reached_set.h): the per-face exact regions and seeds, edge intervals, vertex flags.
#include "verifier/reached_set.h"

#include <algorithm>
#include <cmath>

#include "models/polygon_distance.h"
#include "models/task_error.h"
#include "models/task_loader.h"
#include "verifier/internal/face_regions.h"

namespace cmt {

using face_geometry::ChartRegion;
using face_geometry::FT;
using face_geometry::Point2;
using face_geometry::Points2;
using face_geometry::PolygonWithHoles2;

namespace {

// Is the segment inside the closed region? Exactly when both ends are and so is the midpoint of every piece
// between its crossings with the region's boundary (each piece is then inside or outside as a whole).
bool region_contains_segment(const ChartRegion& region, const face_geometry::Segment2& seg) {
  const Point2 &a = seg.source(), &b = seg.target();
  if (region.oriented_side(a) == CGAL::ON_NEGATIVE_SIDE || region.oriented_side(b) == CGAL::ON_NEGATIVE_SIDE)
    return false;
  std::vector<FT> ts{0, 1};
  const FT len2 = seg.squared_length();
  std::vector<PolygonWithHoles2> pwhs;
  region.polygons_with_holes(std::back_inserter(pwhs));
  auto scan = [&](const face_geometry::Polygon2& poly) {
    for (auto e = poly.edges_begin(); e != poly.edges_end(); ++e) {
      const auto x = CGAL::intersection(seg, *e);
      if (!x) continue;
      if (const Point2* p = boost::get<Point2>(&*x)) ts.push_back(((*p - a) * (b - a)) / len2);
      if (const face_geometry::Segment2* s = boost::get<face_geometry::Segment2>(&*x)) {
        ts.push_back(((s->source() - a) * (b - a)) / len2);
        ts.push_back(((s->target() - a) * (b - a)) / len2);
      }
    }
  };
  for (const PolygonWithHoles2& pwh : pwhs) {
    scan(pwh.outer_boundary());
    for (auto h = pwh.holes_begin(); h != pwh.holes_end(); ++h) scan(*h);
  }
  std::sort(ts.begin(), ts.end());
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    if (ts[i] == ts[i + 1]) continue;
    if (region.oriented_side(a + (b - a) * ((ts[i] + ts[i + 1]) / 2)) == CGAL::ON_NEGATIVE_SIDE) return false;
  }
  return true;
}

}  // namespace

// ---- Impl ----

ReachedSet::Impl::Impl(const CSpace& c) : cspace(&c) {
  for (const Face& f : c.faces()) {
    charts.push_back(face_geometry::make_chart(f));
    charts.back().cell = region_cell(c.scale());
    Points2 pts;
    for (const Vec3& p : f.polygon) pts.push_back(charts.back().project(p));
    face_polygon.push_back(face_geometry::convex_hull(pts));
  }
  faces.resize(c.faces().size());
  edges.resize(c.edges().size());
  vertices.assign(c.vertices().size(), 0);
}

bool ReachedSet::Impl::add_region(int fi, const ChartRegion& part, ChartRegion* added) {
  ChartRegion diff = part;
  diff.difference(faces[fi].region);
  if (diff.is_empty()) return false;
  faces[fi].region.join(part);
  // Growth no wider than a few grid cells is the region kernel's rounding, not reach: stored, not new.
  if (!diff.wider_than(face_geometry::kRegionGrowthCells)) return false;
  if (added) *added = std::move(diff);
  return true;
}

bool ReachedSet::Impl::covered(int fi, const Point2& p) const {
  const face_geometry::FaceSet& fs = faces[fi];
  if (!fs.region.is_empty() && fs.region.oriented_side(p) != CGAL::ON_NEGATIVE_SIDE) return true;
  for (const face_geometry::Segment2& s : fs.segments)
    if (s.has_on(p)) return true;
  return std::find(fs.points.begin(), fs.points.end(), p) != fs.points.end();
}

bool ReachedSet::Impl::add_segment(int fi, const Point2& a, const Point2& b) {
  if (a == b) return add_point(fi, a);
  face_geometry::FaceSet& fs = faces[fi];
  const face_geometry::Segment2 seg(a, b);
  for (const face_geometry::Segment2& s : fs.segments)
    if (s.has_on(a) && s.has_on(b)) return false;
  if (!fs.region.is_empty() && region_contains_segment(fs.region, seg)) return false;
  fs.segments.push_back(seg);
  return true;
}

bool ReachedSet::Impl::add_point(int fi, const Point2& p) {
  if (covered(fi, p)) return false;
  faces[fi].points.push_back(p);
  return true;
}

double ReachedSet::Impl::add_interval(int ei, double t0, double t1, std::vector<EdgeInterval>* added) {
  t0 = std::clamp(t0, 0.0, 1.0);
  t1 = std::clamp(t1, 0.0, 1.0);
  if (t0 > t1) std::swap(t0, t1);
  auto& list = edges[ei];
  std::vector<EdgeInterval> gaps;
  if (t0 == t1) {
    bool in = false;
    for (const EdgeInterval& iv : list) in = in || (iv.t0 <= t0 && t0 <= iv.t1);
    if (in) return -1;
    gaps.push_back({t0, t1});
  } else {
    // Uncovered parts of [t0, t1].
    double cursor = t0;
    for (const EdgeInterval& iv : list) {
      if (iv.t1 < cursor) continue;
      if (iv.t0 > t1) break;
      if (iv.t0 > cursor) gaps.push_back({cursor, std::min(iv.t0, t1)});
      cursor = std::max(cursor, iv.t1);
    }
    if (cursor < t1) gaps.push_back({cursor, t1});
    if (gaps.empty()) return -1;
  }
  double fresh = 0;
  for (const EdgeInterval& g : gaps) fresh += g.t1 - g.t0;
  list.push_back({t0, t1});
  std::sort(list.begin(), list.end(),
            [](const EdgeInterval& a, const EdgeInterval& b) { return a.t0 < b.t0; });
  std::vector<EdgeInterval> merged;
  for (const EdgeInterval& iv : list) {
    if (!merged.empty() && iv.t0 <= merged.back().t1 + kEdgeParamSlack)
      merged.back().t1 = std::max(merged.back().t1, iv.t1);
    else
      merged.push_back(iv);
  }
  list = std::move(merged);
  if (added) *added = std::move(gaps);
  return fresh;
}

bool ReachedSet::Impl::add_vertex(int vi) {
  if (vertices[vi]) return false;
  vertices[vi] = 1;
  return true;
}

// ---- ReachedSet ----

ReachedSet::ReachedSet(const CSpace& cspace) : impl_(std::make_unique<Impl>(cspace)) {}
ReachedSet::~ReachedSet() = default;
ReachedSet::ReachedSet(const ReachedSet& other) : impl_(std::make_unique<Impl>(*other.impl_)) {}
ReachedSet& ReachedSet::operator=(const ReachedSet& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
ReachedSet::ReachedSet(ReachedSet&&) noexcept = default;
ReachedSet& ReachedSet::operator=(ReachedSet&&) noexcept = default;

const CSpace& ReachedSet::cspace() const { return *impl_->cspace; }

void ReachedSet::add_whole_atom(int id) {
  const CSpace& c = cspace();
  const int k = c.atom_index(id);
  switch (c.atom_kind(id)) {
    case AtomKind::kFace: {
      ChartRegion whole(face_geometry::to_polygon(impl_->face_polygon[k]), impl_->charts[k].cell);
      impl_->add_region(k, whole, nullptr);
      break;
    }
    case AtomKind::kEdge:
      impl_->add_interval(k, 0, 1, nullptr);
      break;
    case AtomKind::kVertex:
      impl_->add_vertex(k);
      break;
  }
}

void ReachedSet::add_face_polygon(int id, const std::vector<Vec3>& polygon) {
  const int k = cspace().atom_index(id);
  Points2 pts;
  for (const Vec3& p : polygon) pts.push_back(impl_->charts[k].project(p));
  pts = face_geometry::convex_hull(pts);
  if (pts.size() >= 3)
    impl_->add_region(k, ChartRegion(face_geometry::to_polygon(pts), impl_->charts[k].cell), nullptr);
  else if (pts.size() == 2)
    impl_->add_segment(k, pts[0], pts[1]);
  else if (pts.size() == 1)
    impl_->add_point(k, pts[0]);
}

void ReachedSet::add_face_segment(int id, const Vec3& a, const Vec3& b) {
  const int k = cspace().atom_index(id);
  impl_->add_segment(k, impl_->charts[k].project(a), impl_->charts[k].project(b));
}

void ReachedSet::add_face_point(int id, const Vec3& p) {
  const int k = cspace().atom_index(id);
  impl_->add_point(k, impl_->charts[k].project(p));
}

void ReachedSet::add_edge_interval(int id, double t0, double t1) {
  impl_->add_interval(cspace().atom_index(id), t0, t1, nullptr);
}

void ReachedSet::add_vertex(int id) { impl_->add_vertex(cspace().atom_index(id)); }

namespace {

// Edge parameters of an exact interval, rounded outward by kEdgeParamSlack.
EdgeInterval outward(const FT& t0, const FT& t1) {
  return {std::max(0.0, CGAL::to_interval(t0).first - kEdgeParamSlack),
          std::min(1.0, CGAL::to_interval(t1).second + kEdgeParamSlack)};
}

}  // namespace

void ReachedSet::add_boundary_closure() {
  const CSpace& c = cspace();
  const int nf = static_cast<int>(c.faces().size()), ne = static_cast<int>(c.edges().size());
  for (int fi = 0; fi < nf; ++fi) {
    const face_geometry::FaceSet& fs = impl_->faces[fi];
    if (fs.empty()) continue;
    std::vector<Points2> parts = face_geometry::convex_pieces(fs.region);
    for (const face_geometry::Segment2& s : fs.segments) parts.push_back({s.source(), s.target()});
    for (const Point2& p : fs.points) parts.push_back({p});
    const Face& face = c.faces()[fi];
    const face_geometry::FaceChart& chart = impl_->charts[fi];
    for (const Points2& part : parts) {
      for (int e : face.edges) {
        const Edge& edge = c.edges()[e - nf];
        FT t0, t1;
        if (face_geometry::clip_segment(part, chart.project(edge.a), chart.project(edge.b), &t0, &t1)) {
          const EdgeInterval iv = outward(t0, t1);
          impl_->add_interval(e - nf, iv.t0, iv.t1, nullptr);
        }
      }
      for (int v : face.vertices)
        if (face_geometry::inside_closed(part, chart.project(c.vertices()[v - nf - ne].point)))
          impl_->add_vertex(v - nf - ne);
    }
  }
  for (int ei = 0; ei < ne; ++ei)
    for (const EdgeInterval& iv : impl_->edges[ei]) {
      const Edge& e = c.edges()[ei];
      if (iv.t0 <= kEdgeParamSlack && e.vertex_a >= 0) impl_->add_vertex(e.vertex_a - nf - ne);
      if (iv.t1 >= 1 - kEdgeParamSlack && e.vertex_b >= 0) impl_->add_vertex(e.vertex_b - nf - ne);
    }
}

void ReachedSet::unite(const ReachedSet& other) {
  const Impl& o = *other.impl_;
  for (std::size_t fi = 0; fi < o.faces.size(); ++fi) {
    if (!o.faces[fi].region.is_empty()) impl_->add_region(static_cast<int>(fi), o.faces[fi].region, nullptr);
    for (const face_geometry::Segment2& s : o.faces[fi].segments)
      impl_->add_segment(static_cast<int>(fi), s.source(), s.target());
    for (const Point2& p : o.faces[fi].points) impl_->add_point(static_cast<int>(fi), p);
  }
  for (std::size_t ei = 0; ei < o.edges.size(); ++ei)
    for (const EdgeInterval& iv : o.edges[ei])
      impl_->add_interval(static_cast<int>(ei), iv.t0, iv.t1, nullptr);
  for (std::size_t vi = 0; vi < o.vertices.size(); ++vi)
    if (o.vertices[vi]) impl_->vertices[vi] = 1;
}

ReachedSet ReachedSet::restricted(const std::vector<bool>& keep) const {
  ReachedSet out = *this;
  const CSpace& c = cspace();
  for (int id = 0; id < c.atom_count(); ++id) {
    if (keep[id]) continue;
    const int k = c.atom_index(id);
    switch (c.atom_kind(id)) {
      case AtomKind::kFace:
        out.impl_->faces[k] = face_geometry::FaceSet();
        break;
      case AtomKind::kEdge:
        out.impl_->edges[k].clear();
        break;
      case AtomKind::kVertex:
        out.impl_->vertices[k] = 0;
        break;
    }
  }
  return out;
}

bool ReachedSet::contains_atom(int id) const {
  const CSpace& c = cspace();
  const int k = c.atom_index(id);
  switch (c.atom_kind(id)) {
    case AtomKind::kFace:
      return !impl_->faces[k].empty();
    case AtomKind::kEdge:
      return !impl_->edges[k].empty();
    case AtomKind::kVertex:
      return impl_->vertices[k] != 0;
  }
  return false;
}

std::vector<int> ReachedSet::atoms() const {
  std::vector<int> out;
  for (int id = 0; id < cspace().atom_count(); ++id)
    if (contains_atom(id)) out.push_back(id);
  return out;
}

bool ReachedSet::empty() const { return atoms().empty(); }

double ReachedSet::face_area(int id) const {
  const int k = cspace().atom_index(id);
  // Chart areas shrink by |n_drop| (projection along the dropped axis).
  return face_geometry::area(impl_->faces[k].region) /
         std::abs(cspace().faces()[k].normal[impl_->charts[k].drop]);
}

double ReachedSet::area() const {
  double total = 0;
  for (const Face& f : cspace().faces()) total += face_area(f.id);
  return total;
}

std::vector<EdgeInterval> ReachedSet::edge_intervals(int id) const {
  return impl_->edges[cspace().atom_index(id)];
}

bool ReachedSet::has_vertex(int id) const { return impl_->vertices[cspace().atom_index(id)] != 0; }

bool ReachedSet::face_region_contains(int id, const Vec3& p) const {
  const int k = cspace().atom_index(id);
  const ChartRegion& r = impl_->faces[k].region;
  return !r.is_empty() && r.oriented_side(impl_->charts[k].project(p)) != CGAL::ON_NEGATIVE_SIDE;
}

namespace {

std::vector<Vec3> lift_loop(const face_geometry::Polygon2& poly, const face_geometry::FaceChart& chart) {
  std::vector<Vec3> out;
  for (auto v = poly.vertices_begin(); v != poly.vertices_end(); ++v) out.push_back(chart.lift_double(*v));
  if (chart.flips) std::reverse(out.begin(), out.end());
  return out;
}

void region_pieces(const ChartRegion& region, int atom, const face_geometry::FaceChart& chart,
                   double area_scale, std::vector<ReachedPiece>* out) {
  std::vector<PolygonWithHoles2> pwhs;
  region.polygons_with_holes(std::back_inserter(pwhs));
  for (const PolygonWithHoles2& pwh : pwhs) {
    ReachedPiece p;
    p.atom = atom;
    p.kind = AtomKind::kFace;
    p.polygon = lift_loop(pwh.outer_boundary(), chart);
    double a = std::abs(CGAL::to_double(pwh.outer_boundary().area()));
    for (auto h = pwh.holes_begin(); h != pwh.holes_end(); ++h) {
      p.holes.push_back(lift_loop(*h, chart));
      a -= std::abs(CGAL::to_double(h->area()));
    }
    p.area = a * area_scale;
    out->push_back(std::move(p));
  }
}

}  // namespace

std::vector<ReachedPiece> ReachedSet::pieces() const {
  const CSpace& c = cspace();
  const int nf = static_cast<int>(c.faces().size()), ne = static_cast<int>(c.edges().size());
  std::vector<ReachedPiece> out;
  for (int fi = 0; fi < nf; ++fi) {
    const face_geometry::FaceSet& fs = impl_->faces[fi];
    const face_geometry::FaceChart& chart = impl_->charts[fi];
    region_pieces(fs.region, fi, chart, 1 / std::abs(c.faces()[fi].normal[chart.drop]), &out);
    for (const face_geometry::Segment2& s : fs.segments) {
      // Swallowed by a region grown later: only when the whole segment lies in it (a segment that leaves the
      // region must be reported, e.g. to the goal check, pieces_outside).
      if (!fs.region.is_empty() && region_contains_segment(fs.region, s)) continue;
      out.push_back(
          {fi, AtomKind::kFace, {chart.lift_double(s.source()), chart.lift_double(s.target())}, {}, 0});
    }
    for (const Point2& p : fs.points)
      if (fs.region.is_empty() || fs.region.oriented_side(p) == CGAL::ON_NEGATIVE_SIDE)
        out.push_back({fi, AtomKind::kFace, {chart.lift_double(p)}, {}, 0});
  }
  for (int ei = 0; ei < ne; ++ei) {
    const Edge& e = c.edges()[ei];
    for (const EdgeInterval& iv : impl_->edges[ei]) {
      ReachedPiece p{nf + ei, AtomKind::kEdge, {e.a + iv.t0 * (e.b - e.a)}, {}, 0};
      if (iv.t1 > iv.t0) p.polygon.push_back(e.a + iv.t1 * (e.b - e.a));
      out.push_back(std::move(p));
    }
  }
  for (std::size_t vi = 0; vi < impl_->vertices.size(); ++vi)
    if (impl_->vertices[vi])
      out.push_back({nf + ne + static_cast<int>(vi), AtomKind::kVertex, {c.vertices()[vi].point}, {}, 0});
  return out;
}

namespace {

// The parameters s in [0, 1] of the points of [a, b] within tol of q, pushed onto `cover` (none when no point
// is that close).
void cover_near_point(const Vec3& a, const Vec3& b, const Vec3& q, double tol,
                      std::vector<std::pair<double, double>>* cover) {
  const Vec3 aq = a - q, d = b - a;
  const double qa = d.squaredNorm();
  if (qa == 0) {
    if (aq.norm() <= tol) cover->push_back({0, 1});
    return;
  }
  const double qb = d.dot(aq), qc = aq.squaredNorm() - tol * tol;
  const double disc = qb * qb - qa * qc;
  if (disc < 0) return;
  const double root = std::sqrt(disc);
  const double s0 = (-qb - root) / qa, s1 = (-qb + root) / qa;
  if (s1 >= 0 && s0 <= 1) cover->push_back({std::max(0.0, s0), std::min(1.0, s1)});
}

// The part of [a, b] along the part [t0, t1] of segment [p, q] (both ends of [a, b] within tol of [p, q]),
// pushed onto `cover`, as parameters on [0, 1] of [a, b].
void cover_along(const Vec3& a, const Vec3& b, const Vec3& p, const Vec3& q, double t0, double t1, double tol,
                 std::vector<std::pair<double, double>>* cover) {
  if (distance_to_segment(a, p, q) > tol || distance_to_segment(b, p, q) > tol) return;
  const Vec3 d = q - p;
  const double l2 = d.squaredNorm();
  if (l2 == 0) return cover_near_point(a, b, p, tol, cover);
  const double ta = (a - p).dot(d) / l2, tb = (b - p).dot(d) / l2, slack = tol / std::sqrt(l2);
  if (tb == ta) {
    if (ta >= t0 - slack && ta <= t1 + slack) cover->push_back({0, 1});
    return;
  }
  double s0 = (t0 - slack - ta) / (tb - ta), s1 = (t1 + slack - ta) / (tb - ta);
  if (s0 > s1) std::swap(s0, s1);
  if (s1 >= 0 && s0 <= 1) cover->push_back({std::max(0.0, s0), std::min(1.0, s1)});
}

// Is the segment [a, b] (a == b: a point) within `tol` of the container (its closed face regions, face
// segments and points, edge intervals, vertices)? Coverage is accumulated as parameter intervals on [0, 1].
bool segment_covered(const Vec3& a, const Vec3& b, const ReachedSet& container, double tol) {
  const ReachedSet::Impl& im = container.impl();
  const CSpace& c = container.cspace();
  const int nf = static_cast<int>(c.faces().size());
  std::vector<std::pair<double, double>> cover;
  const double len = (b - a).norm();
  for (int fi = 0; fi < nf; ++fi) {
    const face_geometry::FaceSet& fs = im.faces[fi];
    if (fs.region.is_empty()) continue;
    const Face& f = c.faces()[fi];
    if (std::abs(f.normal.dot(a) - f.offset) > tol || std::abs(f.normal.dot(b) - f.offset) > tol) continue;
    const face_geometry::FaceChart& chart = im.charts[fi];
    const Point2 a2 = chart.project(a), b2 = chart.project(b);
    for (const Points2& piece : face_geometry::convex_pieces(fs.region)) {
      // Grow the piece by tol: each side moved outward (chart lengths are at most 3-D lengths).
      Points2 grown = piece;
      std::vector<face_geometry::HalfPlane2> sides;
      for (std::size_t i = 0; i < piece.size(); ++i) {
        const Point2 &p = piece[i], &q = piece[(i + 1) % piece.size()];
        const FT dx = q.x() - p.x(), dy = q.y() - p.y();
        const double norm = std::sqrt(CGAL::to_double(dx * dx + dy * dy));
        sides.push_back({-dy, dx, dy * p.x() - dx * p.y() + FT(tol * norm)});
      }
      FT lo = 0, hi = 1;
      bool ok = true;
      for (const face_geometry::HalfPlane2& h : sides) {
        const FT fa = h.a * a2.x() + h.b * a2.y() + h.c, fb = h.a * b2.x() + h.b * b2.y() + h.c;
        if (fa < 0 && fb < 0) {
          ok = false;
          break;
        }
        if (fa < 0) lo = CGAL::max(lo, fa / (fa - fb));
        if (fb < 0) hi = CGAL::min(hi, fa / (fa - fb));
      }
      if (ok && lo <= hi) cover.push_back({CGAL::to_double(lo), CGAL::to_double(hi)});
    }
  }
  // A face's segments and points (a segment or point goal on a face, stored beside its regions) cover what
  // lies within tol of them.
  for (int fi = 0; fi < nf; ++fi) {
    const face_geometry::FaceSet& fs = im.faces[fi];
    const face_geometry::FaceChart& chart = im.charts[fi];
    for (const face_geometry::Segment2& seg : fs.segments)
      cover_along(a, b, chart.lift_double(seg.source()), chart.lift_double(seg.target()), 0, 1, tol, &cover);
    for (const Point2& q : fs.points) cover_near_point(a, b, chart.lift_double(q), tol, &cover);
  }
  const int ne = static_cast<int>(c.edges().size());
  for (int ei = 0; ei < ne; ++ei) {
    const Edge& e = c.edges()[ei];
    for (const EdgeInterval& iv : im.edges[ei]) cover_along(a, b, e.a, e.b, iv.t0, iv.t1, tol, &cover);
  }
  // A vertex covers the part of [a, b] within tol of it: the s in [0, 1] with |a + s (b − a) − v| <= tol (a
  // rounding sliver of an edge or face beside a goal vertex is contained, as the tolerance promises).
  for (std::size_t vi = 0; vi < im.vertices.size(); ++vi)
    if (im.vertices[vi]) cover_near_point(a, b, c.vertices()[vi].point, tol, &cover);
  std::sort(cover.begin(), cover.end());
  double reach = 0;
  const double gap = len > 0 ? tol / len : 0;
  for (const auto& [s0, s1] : cover) {
    if (s0 > reach + gap) return false;
    reach = std::max(reach, s1);
  }
  return !cover.empty() && reach >= 1 - gap;
}

// Does every point of the convex hull of `pts` lie within `tol` of one convex part of the container (a
// vertex, an edge interval, a face segment or point, a convex piece of a face region)? The distance to a
// convex set is a convex function, so its largest value over a convex hull is at one of the points.
bool convex_piece_near(const std::vector<Vec3>& pts, const ReachedSet& container, double tol) {
  const ReachedSet::Impl& im = container.impl();
  const CSpace& c = container.cspace();
  const auto all_within = [&](const auto& dist) {
    for (const Vec3& p : pts)
      if (!(dist(p) <= tol)) return false;
    return true;
  };
  for (std::size_t vi = 0; vi < im.vertices.size(); ++vi)
    if (im.vertices[vi] && all_within([&](const Vec3& p) { return (p - c.vertices()[vi].point).norm(); }))
      return true;
  for (std::size_t ei = 0; ei < im.edges.size(); ++ei) {
    const Edge& e = c.edges()[ei];
    for (const EdgeInterval& iv : im.edges[ei]) {
      const Vec3 a = e.a + iv.t0 * (e.b - e.a), b = e.a + iv.t1 * (e.b - e.a);
      if (all_within([&](const Vec3& p) { return distance_to_segment(p, a, b); })) return true;
    }
  }
  for (std::size_t fi = 0; fi < im.faces.size(); ++fi) {
    const face_geometry::FaceSet& fs = im.faces[fi];
    const face_geometry::FaceChart& chart = im.charts[fi];
    for (const face_geometry::Segment2& sg : fs.segments) {
      const Vec3 a = chart.lift_double(sg.source()), b = chart.lift_double(sg.target());
      if (all_within([&](const Vec3& p) { return distance_to_segment(p, a, b); })) return true;
    }
    for (const Point2& q : fs.points) {
      const Vec3 a = chart.lift_double(q);
      if (all_within([&](const Vec3& p) { return (p - a).norm(); })) return true;
    }
    if (fs.region.is_empty()) continue;
    const Vec3& n = c.faces()[fi].normal;
    for (const Points2& piece : face_geometry::convex_pieces(fs.region)) {
      std::vector<Vec3> poly;
      for (const Point2& q : piece) poly.push_back(chart.lift_double(q));
      if (chart.flips) std::reverse(poly.begin(), poly.end());  // counter-clockwise about the normal
      if (all_within([&](const Vec3& p) { return distance_to_convex_polygon(p, poly, n); })) return true;
    }
  }
  return false;
}

}  // namespace

std::vector<ReachedPiece> ReachedSet::pieces_outside(const ReachedSet& container, double tol) const {
  const CSpace& c = cspace();
  const int nf = static_cast<int>(c.faces().size());
  std::vector<ReachedPiece> out;
  for (int fi = 0; fi < nf; ++fi) {
    const face_geometry::FaceSet& fs = impl_->faces[fi];
    if (fs.empty()) continue;
    const face_geometry::FaceChart& chart = impl_->charts[fi];
    ChartRegion rest = fs.region;
    rest.difference(container.impl_->faces[fi].region);  // exact containment per face
    if (rest.is_empty()) continue;
    // A remainder whose every convex piece lies within tol of one convex part of the container (a rounding
    // sliver beside a goal edge or vertex) is contained, as the tolerance promises; otherwise the whole
    // remainder is reported.
    bool near = true;
    for (const Points2& piece : face_geometry::convex_pieces(rest)) {
      std::vector<Vec3> pts;
      for (const Point2& q : piece) pts.push_back(chart.lift_double(q));
      if (!convex_piece_near(pts, container, tol)) {
        near = false;
        break;
      }
    }
    if (!near) region_pieces(rest, fi, chart, 1 / std::abs(c.faces()[fi].normal[chart.drop]), &out);
  }
  for (const ReachedPiece& p : pieces()) {
    if (p.kind == AtomKind::kFace && p.polygon.size() >= 3) continue;
    const Vec3& a = p.polygon.front();
    const Vec3& b = p.polygon.back();
    if (!segment_covered(a, b, container, tol)) out.push_back(p);
  }
  return out;
}

// ---- locating task regions ----

namespace {

// A planar task (dimension 2) is its [x, z] scene extruded along y and clipped to the slab
// |y| <= kPlanarClipHalfDepth (models/task_loader.h), whose y walls are phantoms: a planar point stands for
// the contact points above it across the slab (a segment along y), a planar segment for a rectangle. Without
// this a goal segment at y = 0 would not contain the slab-wide edge a planar motion sticks on.
Region extruded_across_slab(const Region& r) {
  const double h = kPlanarClipHalfDepth;
  const auto at = [](Vec3 p, double y) {
    p.y() = y;
    return p;
  };
  Region out = r;
  if (r.kind == Region::Kind::kPoint) {
    out.kind = Region::Kind::kSegment;
    out.points = {at(r.points[0], -h), at(r.points[0], h)};
  } else if (r.kind == Region::Kind::kSegment) {
    out.kind = Region::Kind::kPolygon;
    out.points = {at(r.points[0], -h), at(r.points[1], -h), at(r.points[1], h), at(r.points[0], h)};
  }
  return out;
}

}  // namespace

ReachedSet ReachedSet::from_region(const LoadedTask& task, const Region& planar_or_spatial, bool partial) {
  const Region region =
      task.task.dimension == 2 ? extruded_across_slab(planar_or_spatial) : planar_or_spatial;
  const CSpace& c = task.cspace;
  const double tol = task.surface_tolerance();
  ReachedSet rs(c);
  const int nf = static_cast<int>(c.faces().size()), ne = static_cast<int>(c.edges().size());
  if (region.kind == Region::Kind::kPoint) {
    const Vec3& p = region.points.at(0);
    const int id = c.nearest_atom(p, tol);
    if (id < 0 && partial) return rs;
    if (id < 0) throw TaskError(task.task.source_file, region.key, "the point is not on the contact surface");
    switch (c.atom_kind(id)) {
      case AtomKind::kFace:
        rs.add_face_point(id, p);
        break;
      case AtomKind::kEdge: {
        const Edge& e = c.edges()[id - nf];
        const double t = std::clamp((p - e.a).dot(e.b - e.a) / (e.b - e.a).squaredNorm(), 0.0, 1.0);
        rs.add_edge_interval(id, t, t);
        for (int f : e.faces) rs.add_face_point(f, e.a + t * (e.b - e.a));
        break;
      }
      case AtomKind::kVertex:
        rs.add_vertex(id);
        for (int f : c.vertices()[id - nf - ne].faces) rs.add_face_point(f, c.vertices()[id - nf - ne].point);
        break;
    }
  } else {
    for (const Face& f : c.faces()) {
      bool in_plane = true;
      for (const Vec3& p : region.points) in_plane = in_plane && std::abs(f.normal.dot(p) - f.offset) <= tol;
      if (!in_plane) continue;
      const face_geometry::FaceChart& chart = rs.impl_->charts[f.id];
      Points2 pts;
      for (const Vec3& p : region.points) pts.push_back(chart.project(p));
      const Points2 part = face_geometry::clip(face_geometry::convex_hull(pts), rs.impl_->face_polygon[f.id]);
      if (part.size() >= 3)
        rs.impl_->add_region(f.id, ChartRegion(face_geometry::to_polygon(part), rs.impl_->charts[f.id].cell),
                             nullptr);
      else if (part.size() == 2)
        rs.impl_->add_segment(f.id, part[0], part[1]);
      else if (part.size() == 1)
        rs.impl_->add_point(f.id, part[0]);
    }
    if (region.kind == Region::Kind::kSegment) {
      const Vec3 &a = region.points[0], &b = region.points[1];
      for (const Edge& e : c.edges()) {
        const Vec3 d = e.b - e.a;
        if ((a - e.a).cross(d).norm() > tol * d.norm() || (b - e.a).cross(d).norm() > tol * d.norm())
          continue;
        const double ta = (a - e.a).dot(d) / d.squaredNorm(), tb = (b - e.a).dot(d) / d.squaredNorm();
        const double t0 = std::max(0.0, std::min(ta, tb)), t1 = std::min(1.0, std::max(ta, tb));
        if (t0 <= t1) rs.add_edge_interval(e.id, t0, t1);
      }
    }
    rs.add_boundary_closure();
  }
  if (partial) return rs;
  // Every sample of the region must be near a located atom.
  for (const Vec3& s : region_samples(region, 8)) {
    const int id = c.nearest_atom(s, tol);
    bool ok = id >= 0 && rs.contains_atom(id);
    if (id >= 0 && !ok) {
      // A sample near an edge or vertex may be covered by an adjacent face's part.
      for (const Face& f : c.faces())
        ok = ok || (rs.contains_atom(f.id) && c.distance_to_atom(s, f.id) <= tol);
    }
    if (!ok) throw TaskError(task.task.source_file, region.key, "part of the region is on no contact face");
  }
  return rs;
}

ReachedSet ReachedSet::from_regions(const LoadedTask& task, const std::vector<Region>& regions,
                                    bool partial) {
  ReachedSet rs(task.cspace);
  for (const Region& r : regions) rs.unite(from_region(task, r, partial));
  return rs;
}

}  // namespace cmt

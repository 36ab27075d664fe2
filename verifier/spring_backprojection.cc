// Weak and strong spring backprojections (Buckley §5.4.4, Alg 5.2) under the via-point model: the forward
// spring projection's pointwise relations (spring_projection.cc) read backwards, as backprojection.cc does
// for the damper. Each rule "from y the robot may reach z" becomes "z in W puts y in W":
//  - flight: z within eps_t of seg[y, p + eps_o u] (u the direction from y to p): seg[y, p] meets
//    z ⊕ ball(eps_t), or z lies within eps_t + eps_o of p;
//  - sliding on a face toward p' (Fig 3.14): the same in the face's plane with the focus p'. The slide keeps
//    the via-point line of its own start until the robot leaves the face, so only the motion's stops on the
//    face (the base) and the points where it may leave the face or the face's edges restart it: a point of W
//    reached by a slide from the base does not start another slide (that would let W creep by eps_t per
//    round where the robot cannot hop);
//  - along an edge toward q: y on the far side of z from q, or anywhere when q's either-way part reaches z;
//  - entries from an edge or a vertex onto a face: the closure of the face part (its boundary points).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "verifier/backprojection.h"
#include "verifier/internal/spring_flight.h"
#include "verifier/internal/worklist.h"
#include "verifier/spring.h"

namespace cmt {
namespace {

using namespace face_geometry;

// Offsets of the reach sets' half-spaces are moved outward by this fraction of the scene scale: it covers the
// rounding of their double normals and offsets (relative 1e-15) and the cone test's tolerance (line_reach).
constexpr double kReachRelativeSlack = 1e-9;

// forward_project_spring's decision margin (x the scene scale) on its stay and leave tests, with the same
// sign: a face counts as one the robot may stay on, and a point as one it may leave from, within it.
constexpr double kLeaveDecisionMargin = 1e-9;

// Distance from x to the convex hull of a point, a segment or a planar convex polygon (its vertices in
// order).
double distance_to_part(const std::vector<Vec3>& part, const Vec3& x) {
  const auto to_segment = [&](const Vec3& a, const Vec3& b) {
    const Vec3 d = b - a;
    const double t = d.squaredNorm() > 0 ? std::clamp((x - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (a + t * d - x).norm();
  };
  if (part.size() == 1) return (part[0] - x).norm();
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < part.size(); ++i)
    best = std::min(best, to_segment(part[i], part[(i + 1) % part.size()]));
  if (part.size() < 3) return best;
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < part.size(); ++i) n += part[i].cross(part[(i + 1) % part.size()]);
  if (n.norm() == 0) return best;
  n.normalize();
  const Vec3 q = x - n.dot(x - part[0]) * n;  // x projected on the plane
  for (std::size_t i = 0; i < part.size(); ++i)
    if ((part[(i + 1) % part.size()] - part[i]).cross(q - part[i]).dot(n) < 0) return best;
  return std::abs(n.dot(x - part[0]));
}

// {x : seg[x, focus + overshoot u] comes within r of conv(part)}, u the direction from x to the focus: every
// point when the part lies within r + overshoot of the focus (decided up to the slack, toward "every"); else
// {x : seg[x, focus] meets K}, K = conv(part) ⊕ cube(r) (which holds part ⊕ ball(r)), as half-spaces. It is
// K + cone(K − focus) (a convex set): the cone over K with apex `focus`, cut by every supporting plane of K
// that has the focus strictly outside (a point of the cone in front of such a plane lies between the focus
// and K). Candidate normals: K's facets are among ±(d_i × d_j) for K's edge directions d (the part's edges
// and the axes); the cone's facets pass through the focus and an edge of K. Offsets are moved outward by
// `slack` (task units), which covers their rounding; `far` bounds the distance from the focus to any point
// that is asked about (the scene).
struct LineReach {
  bool everything = false;
  std::vector<HalfSpace> halfspaces;
  bool contains(const Vec3& x) const;
};
bool LineReach::contains(const Vec3& x) const {
  if (everything) return true;
  for (const HalfSpace& h : halfspaces)
    if (h.normal.dot(x) > h.offset) return false;
  return true;
}

LineReach line_reach(const std::vector<Vec3>& part, const Vec3& focus, double r, double overshoot,
                     double slack, double far) {
  if (distance_to_part(part, focus) <= r + overshoot + slack) return {true, {}};
  std::vector<Vec3> dirs = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  for (std::size_t i = 0; part.size() > 1 && i < part.size(); ++i) {
    const Vec3 d = part[(i + 1) % part.size()] - part[i];
    if (d.norm() > 0) dirs.push_back(d.normalized());
  }
  std::vector<Vec3> corners;  // K's vertices (a superset of them)
  for (const Vec3& q : part)
    for (int k = 0; k < 8; ++k)
      corners.push_back(q + r * Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  const auto support = [&](const Vec3& n) {
    double h = -std::numeric_limits<double>::infinity();
    for (const Vec3& q : part) h = std::max(h, n.dot(q));
    return h + r * n.lpNorm<1>();
  };
  LineReach out;
  const auto add = [&](const Vec3& n, double offset) {
    for (const HalfSpace& h : out.halfspaces)
      if (h.normal.dot(n) > 1 - 1e-15 && std::abs(h.offset - offset) <= slack) return;
    out.halfspaces.push_back({n, offset});
  };
  bool separated = false;
  for (std::size_t i = 0; i < dirs.size(); ++i)
    for (std::size_t j = i + 1; j < dirs.size(); ++j) {
      const Vec3 c = dirs[i].cross(dirs[j]);
      if (c.norm() < 1e-12) continue;
      for (const Vec3& n : {Vec3(c.normalized()), Vec3(-c.normalized())}) {
        const double h = support(n);
        if (n.dot(focus) > h + slack) add(n, h + slack), separated = true;
      }
    }
  if (!separated) return {true, {}};
  // A plane through the focus bounds the cone when no vertex of K lies in front of it by more than `tol`: a
  // point x of the cone is focus + lambda (k − focus), k in K, lambda <= far / d0 (d0 <= |k − focus|), so it
  // leaves the plane by at most tol far / d0 = slack / 2, inside the offset's slack.
  const double d0 = distance_to_part(part, focus) - std::sqrt(3.0) * r;
  if (d0 <= 0) return {true, {}};
  const double tol = 0.5 * slack * d0 / far;
  for (const Vec3& d : dirs)
    for (const Vec3& y : corners) {
      const Vec3 c = d.cross(y - focus);
      if (c.norm() < 1e-12 * (y - focus).norm()) continue;
      for (const Vec3& n : {Vec3(c.normalized()), Vec3(-c.normalized())}) {
        bool bounds = true;
        for (const Vec3& z : corners)
          if (n.dot(z - focus) > tol) {
            bounds = false;
            break;
          }
        if (bounds) add(n, n.dot(focus) + slack);
      }
    }
  return out;
}

class SpringBackProjector {
 public:
  SpringBackProjector(const LoadedTask& task, const ReachedSet& from, const Vec3& p)
      : cspace_(task.cspace),
        u_(task.task.uncertainty),
        p_(p),
        base_(from.impl()),
        weak_(from),
        reached_impl_(weak_.impl()),
        work_(reached_impl_) {
    // The forward projection's tubes are circumscribed polygons of the eps_t and eps_o disks
    // (kSpringDiskSides sides, radii grown by kSpringRelativeSlack): the backward reach uses the same outer
    // radii, so that the forward projection of the complement keeps clear of W.
    const double outer = (1 + kSpringRelativeSlack) / std::cos(M_PI / kSpringDiskSides);
    eps_t_ = eps_t(u_) * outer;
    eps_o_ = eps_o(u_) * outer;
    slack_ = kReachRelativeSlack * cspace_.scale();
    tan_v_ = std::tan(u_.theta_v);
    for (const Face& f : cspace_.faces()) {
      const int fi = f.id;
      const double depth = f.offset - f.normal.dot(p_);  // > 0: p behind the face's plane
      const Vec3 center = p_ + depth * f.normal;         // p', p's projection on the plane
      centers_.push_back(center);
      double far = 0;
      for (const Vec3& q : f.polygon) far = std::max(far, (q - center).norm());
      // forward_project_spring's may_stay: somewhere on the face some pull does not point into free space.
      may_stay_.push_back(
          !(-depth - u_.eps_s > tan_v_ * (far + u_.eps_s) + kLeaveDecisionMargin * cspace_.scale()));
      // Its no-leave disk: strictly inside it every pull points into the obstacle (no flight from there).
      // With theta_v = 0 it is the whole face when p lies more than eps_s behind it, else none.
      const double pull_in = depth - u_.eps_s - kLeaveDecisionMargin * cspace_.scale();
      const double no_leave =
          tan_v_ > 0 ? (depth - u_.eps_s) / tan_v_ - u_.eps_s - kLeaveDecisionMargin * cspace_.scale()
                     : (pull_in > 0 ? std::numeric_limits<double>::infinity() : 0.0);
      ChartRegion stay;
      if (std::isinf(no_leave)) {
        stay = ChartRegion(to_polygon(reached_impl_.face_polygon[fi]), reached_impl_.charts[fi].cell);
      } else if (no_leave > 4 * reached_impl_.charts[fi].cell) {
        const Points2 disk =
            clip(chart_disk(reached_impl_, fi, center, no_leave, false), reached_impl_.face_polygon[fi]);
        if (disk.size() >= 3) stay = ChartRegion(to_polygon(disk), reached_impl_.charts[fi].cell);
      }
      no_leave_.push_back(std::move(stay));
    }
    // Faces in one plane (same unit normal and offset up to the surface tolerance), each with itself.
    const double tol = task.surface_tolerance();
    for (const Face& f : cspace_.faces()) {
      plane_faces_.emplace_back();
      for (const Face& g : cspace_.faces())
        if (f.normal.dot(g.normal) > 1 - 1e-12 && std::abs(f.offset - g.offset) <= tol)
          plane_faces_.back().push_back(g.id);
    }
  }

  WeakBackprojection run() {
    // The base's own face parts start slides (process_face restarts slides only where the robot may leave).
    for (int fi = 0; fi < static_cast<int>(cspace_.faces().size()); ++fi)
      for (const Points2& part : base_parts(fi)) backslide(fi, lifted(fi, part));
    // So do its intervals on flat edges (process_edge starts no slides from flat edges).
    for (std::size_t ei = 0; ei < cspace_.edges().size(); ++ei) {
      const Edge& e = cspace_.edges()[ei];
      if (e.shape != EdgeShape::kFlat) continue;
      for (const EdgeInterval& iv : base_.edges[ei])
        for (int f : e.faces) backslide(f, {e.a + iv.t0 * (e.b - e.a), e.a + iv.t1 * (e.b - e.a)});
    }
    const bool capped = work_.run(
        steps_, kMaxBackprojectionSteps, [&](int fi) { process_face(fi); }, [&](int ei) { process_edge(ei); },
        [&](int vi) { process_vertex(vi); });
    return finish_weak_backprojection(std::move(weak_), capped, steps_);
  }

 private:
  // The largest distance from x to a vertex of the C-space (its bounding box's corners among them).
  double farthest(const Vec3& x) const {
    double d = 0;
    for (const Vertex& v : cspace_.vertices()) d = std::max(d, (v.point - x).norm());
    return d;
  }

  // Face fi ∩ reach, a convex chart polygon (empty: none). Half-spaces that hold the whole face or miss it by
  // far are decided in doubles; the rest cut the face exactly.
  Points2 clip_face(int fi, const LineReach& reach) const {
    Points2 poly = reached_impl_.face_polygon[fi];
    if (reach.everything) return poly;
    const Face& f = cspace_.faces()[fi];
    for (const HalfSpace& h : reach.halfspaces) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Vec3& q : f.polygon) {
        lo = std::min(lo, h.normal.dot(q) - h.offset);
        hi = std::max(hi, h.normal.dot(q) - h.offset);
      }
      if (hi <= 0) continue;
      if (lo > slack_) return {};
      const Plane3 plane(-h.normal.x(), -h.normal.y(), -h.normal.z(), h.offset);
      poly = clip(poly, restrict_to_chart(plane, reached_impl_.charts[fi]));
      if (poly.empty()) return {};
    }
    return poly;
  }

  // The parameter interval of edge ei inside reach, rounded outward.
  std::optional<std::pair<double, double>> clip_edge(int ei, const LineReach& reach) const {
    if (reach.everything) return std::make_pair(0.0, 1.0);
    const Edge& e = cspace_.edges()[ei];
    double t0 = 0, t1 = 1;
    for (const HalfSpace& h : reach.halfspaces) {
      const double a = h.normal.dot(e.a) - h.offset, b = h.normal.dot(e.b) - h.offset;
      if (a <= 0 && b <= 0) continue;
      if (a > slack_ && b > slack_) return std::nullopt;
      if (a > 0 && b > 0) {  // an end beyond the slack is out; one within it is kept (sound)
        if (a > slack_) t0 = 1;
        if (b > slack_) t1 = 0;
        continue;
      }
      const double t = a / (a - b);  // a + t (b − a) = 0
      if (a > 0)
        t0 = std::max(t0, t - kEdgeParamSlack);
      else
        t1 = std::min(t1, t + kEdgeParamSlack);
    }
    if (t0 > t1) return std::nullopt;
    return std::make_pair(std::max(0.0, t0), std::min(1.0, t1));
  }

  // Flight reversed: every contact point whose segment to p meets part ⊕ cube(eps_t); face points only where
  // the robot may leave the face, and none on the part's own face `face` (a forward flight from a face never
  // lands on it: spring_fly's source face; -1 for an edge or a vertex part).
  void fly_back(const std::vector<Vec3>& part, int face) {
    const LineReach reach = line_reach(part, p_, eps_t_, eps_o_, slack_, farthest(p_));
    for (int fi = 0; fi < static_cast<int>(cspace_.faces().size()); ++fi) {
      if (fi == face) continue;
      const Points2 piece = clip_face(fi, reach);
      if (piece.size() >= 3 && !no_leave_[fi].is_empty()) {
        ChartRegion region(to_polygon(piece), reached_impl_.charts[fi].cell);
        region.difference(no_leave_[fi]);
        if (!region.is_empty()) work_.add_region(fi, region);  // the face's edges: clip_edge below
      } else if (!piece.empty()) {
        work_.add_convex(fi, piece);
      }
    }
    for (int ei = 0; ei < static_cast<int>(cspace_.edges().size()); ++ei)
      if (const auto iv = clip_edge(ei, reach)) work_.add_interval(ei, iv->first, iv->second);
    for (std::size_t vi = 0; vi < cspace_.vertices().size(); ++vi)
      if (reach.contains(cspace_.vertices()[vi].point)) work_.add_vertex(static_cast<int>(vi));
  }

  // Sliding on face fi reversed: the points whose straight slide toward p' passes within r of part, on fi and
  // on the faces coplanar with it (a slide crosses a flat edge unchanged: same plane, same p').
  void backslide(int fi, const std::vector<Vec3>& part) {
    const LineReach reach = line_reach(part, centers_[fi], eps_t_, eps_o_, slack_, farthest(centers_[fi]));
    for (int g : plane_faces_[fi]) {
      if (!may_stay_[g]) continue;
      const Points2 piece = clip_face(g, reach);
      if (!piece.empty()) work_.add_convex(g, piece);
    }
  }

  // Sliding along edge ei reversed. Forward (spring_projection.cc): from [s0, s1] the robot slides toward q,
  // the projection of p on the edge's line at parameter tp, reaching [min(s0, tp − w), max(s1, tp + w)] (w
  // the either-way half-width), except that it cannot stay on the edge inside the must-leave interval (lo,
  // hi) = (tp − a, tp + a): from below it stops sliding at lo, from above at hi. Backward: the parameters
  // whose slide meets [t0, t1].
  void backslide_edge(int ei, double t0, double t1) {
    const Edge& e = cspace_.edges()[ei];
    if (e.shape == EdgeShape::kFlat) return;  // motion on the plane: the faces' rules
    const Vec3 d = e.b - e.a;
    const double len = d.norm();
    const double tp = (p_ - e.a).dot(d) / (len * len);
    const double w = edge_either_way_halfwidth(e, p_, u_, eps_o(u_)) / len + 2 * kEdgeParamSlack;
    const double a =
        edge_must_leave_halfwidth(cspace_, e, tp, p_, u_, kLeaveDecisionMargin * cspace_.scale());
    if (std::isinf(a)) return;  // the robot leaves the edge everywhere
    const auto add = [&](double lo, double hi) {
      lo = std::max(0.0, lo - kEdgeParamSlack), hi = std::min(1.0, hi + kEdgeParamSlack);
      if (lo <= hi) work_.add_interval(ei, lo, hi);
    };
    // Either-way reach: the slide from s covers tp − w when tp − w <= t1, tp + w when tp + w >= t0.
    const bool down_to = tp - w <= t1, up_to = tp + w >= t0;
    if (a <= 0) {  // [min(s, tp − w), max(s, tp + w)] meets [t0, t1]
      add(up_to ? 0.0 : t0, down_to ? 1.0 : t1);
      return;
    }
    // From s <= lo the robot covers [min(s, tp − w), lo] (tp + w > lo); from s >= hi, [hi, max(s, tp + w)].
    const double lo = tp - a, hi = tp + a;
    if (t0 <= lo) add(0.0, down_to ? lo : std::min(t1, lo));
    if (t1 >= hi) add(up_to ? hi : std::max(t0, hi), 1.0);
  }

  std::vector<Vec3> lifted(int fi, const Points2& part) const {
    std::vector<Vec3> pts;
    for (const Point2& q : part) pts.push_back(reached_impl_.charts[fi].lift_double(q));
    return pts;
  }

  // The convex pieces, segments and points of the base on face fi.
  std::vector<Points2> base_parts(int fi) const {
    const FaceSet& f = base_.faces[fi];
    std::vector<Points2> out = f.region.is_empty() ? std::vector<Points2>{} : convex_pieces(f.region);
    for (const Segment2& s : f.segments) out.push_back({s.source(), s.target()});
    for (const Point2& q : f.points) out.push_back({q});
    return out;
  }

  // The part of a face part from which the robot may leave the face: outside the no-leave disk.
  std::vector<Points2> leave_parts(int fi, const Points2& part) const {
    if (no_leave_[fi].is_empty()) return {part};
    if (part.size() < 3) {
      for (const Point2& q : part)
        if (no_leave_[fi].oriented_side(q) != CGAL::ON_POSITIVE_SIDE) return {part};
      return {};
    }
    ChartRegion region(to_polygon(part), reached_impl_.charts[fi].cell);
    region.difference(no_leave_[fi]);
    return region.is_empty() ? std::vector<Points2>{} : convex_pieces(region);
  }

  void process_face(int fi) {
    ++steps_;
    const std::vector<Points2> parts = work_.take_face(fi);
    work_.add_closure(fi, parts);
    for (const Points2& part : parts) {
      fly_back(lifted(fi, part), fi);
      for (const Points2& leave : leave_parts(fi, part)) backslide(fi, lifted(fi, leave));
    }
  }

  void process_edge(int ei) {
    ++steps_;
    const std::vector<EdgeInterval> ivs = work_.take_edge(ei);
    const Edge& e = cspace_.edges()[ei];
    work_.add_interval_ends(ei, ivs);
    for (const EdgeInterval& iv : ivs) {
      const std::vector<Vec3> seg = {e.a + iv.t0 * (e.b - e.a), e.a + iv.t1 * (e.b - e.a)};
      // A flat edge lies in its faces' plane: a slide across it is the faces' (backslide covers both).
      if (e.shape != EdgeShape::kFlat) {
        backslide_edge(ei, iv.t0, iv.t1);
        for (int f : e.faces) backslide(f, seg);
      }
      fly_back(seg, -1);
    }
  }

  void process_vertex(int vi) {
    ++steps_;
    work_.take_vertex(vi);
    const Vertex& vx = cspace_.vertices()[vi];
    const int nf = static_cast<int>(cspace_.faces().size());
    for (int e : vx.edges) {
      const Edge& edge = cspace_.edges()[e - nf];
      const double t = edge.vertex_a == vx.id ? 0.0 : 1.0;
      backslide_edge(e - nf, t, t);
    }
    for (int f : vx.faces) backslide(f, {vx.point});
    fly_back({vx.point}, -1);
  }

  const CSpace& cspace_;
  const Uncertainty u_;
  const Vec3 p_;
  const ReachedSet::Impl& base_;
  ReachedSet weak_;
  ReachedSet::Impl& reached_impl_;
  DamperWorklist work_;
  double eps_t_ = 0, eps_o_ = 0, slack_ = 0, tan_v_ = 0;
  int steps_ = 0;
  std::vector<Vec3> centers_;
  std::vector<bool> may_stay_;
  std::vector<std::vector<int>> plane_faces_;
  std::vector<ChartRegion> no_leave_;
};

}  // namespace

WeakBackprojection weak_backproject_spring(const LoadedTask& task, const ReachedSet& from, const Vec3& p) {
  return SpringBackProjector(task, from, p).run();
}

SpringBackprojection backproject_spring(const LoadedTask& task, const ReachedSet& target, const Vec3& p,
                                        double margin) {
  const CSpace& c = task.cspace;
  ReachedSet surface(c);
  for (int id = 0; id < c.atom_count(); ++id) surface.add_whole_atom(id);
  const SpringProjection stops = forward_project_spring(task, surface, p, SpringModel::kViaPoint);
  SpringBackprojection out{points_outside(stops.termination, target), ReachedSet(c), ReachedSet(c)};
  for (int atom : stops.slide_forever) out.base.add_whole_atom(atom);
  out.free_rest = stops.free_termination;
  out.fallback = stops.fallback;
  if (out.free_rest || out.fallback) {
    out.weak = surface;
  } else {
    WeakBackprojection w = weak_backproject_spring(task, out.base, p);
    out.fallback = w.fallback;
    out.steps = w.steps;
    out.weak = std::move(w.weak);
  }
  out.strong = surface_complement(out.weak, std::max(margin, kBackprojectionRelativeMargin * c.scale()));
  return out;
}

}  // namespace cmt

// Generalized-spring forward projection (Buckley §4.4, Alg 4.4 inside the Alg 4.1 framework). A worklist
// fixpoint like damper_projection.cc, with three kinds of face work:
//   entries  (start, landings from flight, seeds from edges/vertices): the robot may slide from them within
//            the eps_t strip toward p' (Fig 3.14); an entry is slid once (what was slid from is recorded, so
//            a landing already inside a reached region is still slid: its own strip may reach further);
//   new reached parts (entries and strips): reached edges/corners, and flight when the robot may leave the
//            face; strips are not slid again (the strip already bounds the whole slide, Fig 3.14);
//   the face's strong sticking configurations (Fig 3.16) are subtracted before sliding and flying (Alg 4.4).
// Termination: reached parts of faces inside the weak sticking configurations, reached edges and vertices
// whose weak sticking region holds p, and free-space rest near p.
#include "verifier/spring_projection.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>

#include "verifier/atom_cone.h"
#include "verifier/internal/fixpoint.h"
#include "verifier/internal/spring_flight.h"
#include "verifier/internal/spring_velocity.h"
#include "verifier/internal/worklist.h"
#include "verifier/slide_forever.h"
#include "verifier/spring.h"

namespace cmt {
namespace {

using namespace face_geometry;

// Widening's count of the fixpoint rounds (work items) in which an atom grew
// (SpringProjector::grew_this_round).
struct Growth {
  int rounds = 0;
  int last_step = -1;  // the work item of the last counted growth
};

// One face's part of a spring projection: what p and the uncertainty fix (center .. weak), then the
// fixpoint's work lists.
struct FaceState {
  Vec3 center;                     // p', p projected on the face's plane
  double depth = 0;                // offset − n . p (> 0: p lies behind the face, inside the obstacle)
  ChartRegion strong;              // strong sticking configurations, pulled in by the region rounding
  Points2 strong_poly;             // the same as a convex polygon
  ChartRegion no_slide, no_leave;  // pointwise leave/stay disks (inner polygons)
  Points2 weak;                    // weak sticking configurations (outer polygon)
  // Entries not yet slid, every entry so far, reached parts not yet processed (edges, corners, flight); the
  // *_lower lists hold the same as segments and points.
  ChartRegion pending_entry, entered, pending_new;
  std::vector<Points2> pending_entry_lower, entered_lower, pending_new_lower;
  Growth growth;
};

// One edge's fixpoint work: reached intervals not yet processed.
struct EdgeState {
  std::vector<EdgeInterval> pending;
  Growth growth;
};

class SpringProjector {
 public:
  SpringProjector(const LoadedTask& task, const ReachedSet& start, const Vec3& p, SpringModel model,
                  double stop_relative_speed, double contact_lift, double servo_coast, double spring_lag)
      : cspace_(task.cspace),
        u_(task.task.uncertainty),
        p_(p),
        model_(model),
        eps_t_(eps_t(u_)),
        eps_o_(eps_o(u_)),
        tan_v_(std::tan(u_.theta_v)),
        start_(start),
        kappa_(std::max(0.0, stop_relative_speed)),
        lift_(std::max(0.0, contact_lift)),
        reached_(cspace_),
        reached_impl_(reached_.impl()) {
    if (model_ == SpringModel::kVelocity) {
      const double reach = velocity_reach_bound(cspace_, start, p_, u_);
      velocity_ = {p_, u_, reach, velocity_invariant_half_spaces(cspace_, start, p_, u_, reach)};
      velocity_.coast = std::max(0.0, servo_coast);
      spring_lag_ = std::max(0.0, spring_lag);
      slow_radius_ = slow_stop_radius(start, p_, u_, stop_relative_speed);
    }
    // The weak sticking regions with the slow-stop radius added to the sensing error (strong ones keep
    // eps_s).
    Uncertainty u_weak = u_;
    u_weak.eps_s += slow_radius_;
    face_count_ = static_cast<int>(cspace_.faces().size());
    edge_count_ = static_cast<int>(cspace_.edges().size());
    vertex_count_ = static_cast<int>(cspace_.vertices().size());
    face_.resize(face_count_);
    edge_.resize(edge_count_);
    pend_vertex_.assign(vertex_count_, 0);
    for (int fi = 0; fi < face_count_; ++fi) {
      const Face& f = cspace_.faces()[fi];
      const FaceStickingRadii rad = face_sticking_radii(f, p_, u_);
      const double weak_radius = slow_radius_ > 0 ? face_sticking_radii(f, p_, u_weak).weak : rad.weak;
      FaceState& state = face_[fi];
      state.center = rad.center;
      state.depth = f.offset - f.normal.dot(p_);
      ChartRegion strong;
      Points2 strong_poly;
      if (rad.strong > 0) {
        // Pulled in by 4 grid cells (2 in the chart after its projection's shrink of up to 1/sqrt 3), more
        // than the region's outward rounding of what is subtracted.
        const double pull_in = 4 * reached_impl_.charts[fi].cell;
        const Points2 s = rad.strong > pull_in
                              ? clip(chart_disk(reached_impl_, fi, rad.center, rad.strong - pull_in, false),
                                     reached_impl_.face_polygon[fi])
                              : Points2{};
        if (s.size() >= 3) {
          strong = ChartRegion(to_polygon(s), reached_impl_.charts[fi].cell);
          strong_poly = s;
        }
      }
      state.strong_poly = strong_poly;
      state.no_slide = inner_disk_set(fi, rad.center, no_slide_radius(fi));
      state.no_leave = inner_disk_set(fi, rad.center, no_leave_radius(fi));
      Points2 w;
      if (std::isinf(weak_radius))
        w = reached_impl_.face_polygon[fi];
      else if (weak_radius >= 0)
        w = clip(chart_disk(reached_impl_, fi, rad.center, weak_radius, true),
                 reached_impl_.face_polygon[fi]);
      state.weak = w;
      state.strong = std::move(strong);
    }
    for (int id = face_count_; id < cspace_.atom_count(); ++id) {
      SpringStickingRegions reg;
      reg.strong = spring_strong_regions(cspace_, id, u_);
      const bool weak = spring_weak_region(cspace_, id, slow_radius_ > 0 ? u_weak : u_).contains(p_);
      // The velocity model also tests the force cone against the atom's cone directly (both are sound, so
      // both must allow sticking).
      weak_atom_.push_back(weak && (model_ != SpringModel::kVelocity || velocity_may_stick(id)));
      strong_atom_.push_back(reg.strongly_contains(p_));
    }
    // The start: entries on faces, new intervals and vertices.
    const ReachedSet::Impl& s = start.impl();
    for (int fi = 0; fi < face_count_; ++fi) {
      if (!s.faces[fi].region.is_empty()) add_entry_region(fi, s.faces[fi].region);
      for (const Segment2& seg : s.faces[fi].segments) add_entry_lower(fi, {seg.source(), seg.target()});
      for (const Point2& q : s.faces[fi].points) add_entry_lower(fi, {q});
    }
    for (int ei = 0; ei < edge_count_; ++ei)
      for (const EdgeInterval& iv : s.edges[ei]) add_interval(ei, iv.t0, iv.t1);
    for (int vi = 0; vi < vertex_count_; ++vi)
      if (s.vertices[vi]) add_vertex(vi);
  }

  SpringProjection run() {
    SpringProjection out{ReachedSet(cspace_), ReachedSet(cspace_)};
    const bool progress = sweep_until_stable(
        face_count_, edge_count_, vertex_count_, steps_, kMaxSpringFixpointSteps,
        [&](int fi) {
          return !face_[fi].pending_entry.is_empty() || !face_[fi].pending_entry_lower.empty() ||
                 !face_[fi].pending_new.is_empty() || !face_[fi].pending_new_lower.empty();
        },
        [&](int fi) { process_face(fi); }, [&](int ei) { return !edge_[ei].pending.empty(); },
        [&](int ei) { process_edge(ei); }, [&](int vi) { return pend_vertex_[vi] != 0; },
        [&](int vi) { process_vertex(vi); });
    if (progress) {
      out.fallback = true;
      flew_ = true;
      for (int id = 0; id < cspace_.atom_count(); ++id) reached_.add_whole_atom(id);
    }
    out.termination = termination();
    out.free_radius = std::max(spring_rest_radius(u_), u_.eps_s + slow_radius_);
    out.free_center = p_;
    out.free_termination = flew_ && rest_ball_meets_free(out.free_radius);
    out.may_not_terminate = out.termination.empty() && !out.free_termination;
    std::vector<bool> strong(static_cast<std::size_t>(cspace_.atom_count()), false);
    for (std::size_t k = 0; k < strong_atom_.size(); ++k)
      strong[static_cast<std::size_t>(face_count_) + k] = strong_atom_[k];
    out.slide_forever = spring_slide_forever_atoms(cspace_, reached_, start_, p_, u_, kappa_, strong);
    out.reached = std::move(reached_);
    out.steps = steps_;
    out.widened = widened_;
    return out;
  }

 private:
  // Velocity model, an edge or vertex: the robot may stick at some x of the atom iff the reaction cone FC
  // meets −F for an imparted force F within theta_v of p* − x, i.e. iff FC meets cone(x − p*, theta_v). Over
  // x in the atom (the directions to a segment lie within the larger of the angles to its ends from the
  // direction to its midpoint) and p* within eps_s (+ the slow-stop radius) of p, x − p* lies within that
  // angle + asin(r / dist(p, atom)) of m − p. Tighter than spring_sticking_regions' widened generators at
  // vertices, whose three or more cones rotated by theta_v can surround the origin (e.g. mu = .48,
  // theta_v = .25 at a corner of three orthogonal faces) although the sum widened by theta_v is pointed.
  bool velocity_may_stick(int id) const {
    const std::vector<Vec3> pts = atom_points(cspace_, id);
    Vec3 m = Vec3::Zero();
    for (const Vec3& x : pts) m += x;
    m /= static_cast<double>(pts.size());
    const double r = u_.eps_s + slow_radius_;
    double dist = (m - p_).norm();
    if (pts.size() == 2) {  // distance from p to the segment
      const Vec3 d = pts[1] - pts[0];
      const double t = std::clamp((p_ - pts[0]).dot(d) / d.squaredNorm(), 0.0, 1.0);
      dist = (pts[0] + t * d - p_).norm();
    }
    if (dist <= r * (1 + kSpringRelativeSlack) || (m - p_).norm() == 0) return true;
    const Vec3 axis = (m - p_).normalized();
    double spread = 0;
    for (const Vec3& x : pts) {
      const Vec3 dx = x - p_;
      if (dx.norm() == 0) return true;
      spread = std::max(spread, std::acos(std::clamp(axis.dot(dx.normalized()), -1.0, 1.0)));
    }
    const double half =
        (spread + u_.theta_v + std::asin(std::min(1.0, r / dist))) * (1 + kSpringRelativeSlack);
    if (half >= std::numbers::pi / 2) return true;  // not a pointed cone: no bound
    return atom_friction_cone(cspace_, id).may_intersect_cone(CircularCone{axis, half});
  }

  // ---- adding ----
  // Widening counts the fixpoint rounds (work items) in which an atom grew, not the additions: one flight's
  // pieces may add dozens of abutting slivers to an edge at once. Growth of rounding size (below the
  // propagation thresholds) counts no round: it differs between a task and its turned or scaled copy. Returns
  // the round count after this growth (unchanged when the atom already grew in this work item).
  int grew_this_round(Growth& g) const {
    if (g.last_step == steps_) return -1;
    g.last_step = steps_;
    return ++g.rounds;
  }
  void add_reached_region(int fi, const ChartRegion& part) {
    ChartRegion added;
    if (!reached_impl_.add_region(fi, part, &added)) return;
    face_[fi].pending_new.join(added);
    // The erosion test only where it can count (the face has not grown in this work item yet).
    const bool counts = face_[fi].growth.last_step != steps_ && added.wider_than(kRegionGrowthCells);
    const int rounds = counts ? grew_this_round(face_[fi].growth) : -1;
    if (rounds == kSpringWideningRounds) {  // widening, first stage: each region component's convex hull
      ++widened_;
      // Per component (outer boundary), not one hull of everything: a face may hold separate parts far
      // apart (landings below a rim and slides near the bottom), whose common hull would fill the gap.
      std::vector<PolygonWithHoles2> components;
      reached_impl_.faces[fi].region.polygons_with_holes(std::back_inserter(components));
      std::vector<Polygon2> hulls;
      for (const PolygonWithHoles2& c : components) {
        const Points2 hull =
            convex_hull(Points2(c.outer_boundary().vertices_begin(), c.outer_boundary().vertices_end()));
        if (hull.size() >= 3) hulls.push_back(to_polygon(hull));
      }
      const ChartRegion filled = union_of(hulls, reached_impl_.charts[fi].cell);
      if (!filled.is_empty()) add_reached_region(fi, filled);
    } else if (rounds == 2 * kSpringWideningRounds) {  // second stage: the whole face (a superset)
      // The velocity model bounds every point of the motion by the reach ball: the face's part inside it.
      const Points2 whole = model_ == SpringModel::kVelocity
                                ? velocity_reach_section(reached_impl_, fi, velocity_)
                                : reached_impl_.face_polygon[fi];
      if (whole.size() >= 3)
        add_reached_region(fi, ChartRegion(to_polygon(whole), reached_impl_.charts[fi].cell));
    }
  }
  void add_reached_lower(int fi, const Points2& pts) {
    const bool fresh =
        pts.size() == 2 ? reached_impl_.add_segment(fi, pts[0], pts[1]) : reached_impl_.add_point(fi, pts[0]);
    if (fresh) face_[fi].pending_new_lower.push_back(pts);
  }
  void add_entry_region(int fi, const ChartRegion& part) {
    add_reached_region(fi, part);
    ChartRegion fresh = part;
    fresh.difference(face_[fi].entered);
    if (fresh.is_empty()) return;
    face_[fi].entered.join(part);
    if (fresh.wider_than(kRegionGrowthCells)) face_[fi].pending_entry.join(fresh);
  }
  void add_entry_lower(int fi, const Points2& pts) {
    if (pts.empty()) return;
    add_reached_lower(fi, pts);
    for (const Points2& e : face_[fi].entered_lower)
      if (e == pts) return;
    face_[fi].entered_lower.push_back(pts);
    face_[fi].pending_entry_lower.push_back(pts);
  }
  // The velocity model's invariant half-spaces cut an edge interval (false: nothing of it is reachable).
  bool within_bounds(int ei, double* t0, double* t1) const {
    if (model_ != SpringModel::kVelocity) return true;
    const Edge& e = cspace_.edges()[ei];
    const double tol = kSpringRelativeSlack * cspace_.scale();
    for (const HalfSpace& hs : velocity_.bounds) {
      const double sa = hs.normal.dot(e.a), sb = hs.normal.dot(e.b), lim = hs.offset + tol;
      if (std::abs(sb - sa) <= tol) {
        if (std::min(sa, sb) > lim) return false;
        continue;
      }
      const double t = (lim - sa) / (sb - sa);
      if (sb > sa)
        *t1 = std::min(*t1, t + kEdgeParamSlack);
      else
        *t0 = std::max(*t0, t - kEdgeParamSlack);
    }
    return *t0 <= *t1;
  }
  void add_interval(int ei, double t0, double t1) {
    if (!within_bounds(ei, &t0, &t1)) return;
    std::vector<EdgeInterval> added;
    const double fresh = reached_impl_.add_interval(ei, t0, t1, &added);
    if (fresh < 0) return;
    if (fresh > 4 * kEdgeParamSlack || (added.size() == 1 && added[0].t0 == added[0].t1))
      for (const EdgeInterval& iv : added) edge_[ei].pending.push_back(iv);
    const int rounds = fresh > 4 * kEdgeParamSlack ? grew_this_round(edge_[ei].growth) : -1;
    // Widening, first stage: the hull [min t0, max t1] of what the edge holds.
    if (rounds == kSpringWideningRounds) {
      ++widened_;
      const std::vector<EdgeInterval>& held = reached_impl_.edges[ei];
      if (!held.empty()) add_interval(ei, held.front().t0, held.back().t1);
    } else if (rounds == 2 * kSpringWideningRounds) {  // second stage: the whole edge
      if (model_ != SpringModel::kVelocity) {
        add_interval(ei, 0, 1);
      } else {  // the part within the reach ball: |a + t d − p| <= reach, rounded outward
        const Edge& e = cspace_.edges()[ei];
        const Vec3 d = e.b - e.a, w = e.a - p_;
        const double A = d.squaredNorm(), B = 2 * d.dot(w),
                     C = w.squaredNorm() - velocity_.reach * velocity_.reach;
        const double disc = B * B - 4 * A * C;
        if (disc >= 0) {
          const double root = std::sqrt(disc);
          add_interval(ei, std::max(0.0, (-B - root) / (2 * A) - 1e-9),
                       std::min(1.0, (-B + root) / (2 * A) + 1e-9));
        }
      }
    }
  }
  void add_vertex(int vi) {
    if (reached_impl_.add_vertex(vi)) pend_vertex_[vi] = 1;
  }
  // ---- leaving and staying on a face ----
  // With x̂ within eps_s of x on the face, p − x̂ has normal part (toward free space) <= −depth + eps_s and
  // tangential part <= |x − p'| + eps_s; the velocity is within theta_v of it. It always points into the
  // obstacle side when (depth − eps_s) > tan(theta_v) (d + eps_s), always into free space when (−depth −
  // eps_s) > tan(theta_v) (d + eps_s). Compared with a relative margin that favours moving.
  bool may_leave(int fi, const std::vector<Vec3>& pts) const {
    return !(face_[fi].depth - u_.eps_s >
             tan_v_ * (max_dist(fi, pts) + u_.eps_s) + kDecisionMargin * cspace_.scale());
  }
  bool may_stay(int fi, const std::vector<Vec3>& pts) const {
    return !(-face_[fi].depth - u_.eps_s >
             tan_v_ * (max_dist(fi, pts) + u_.eps_s) + kDecisionMargin * cspace_.scale());
  }
  // From the edge onto face fi (m = the in-face unit normal of the edge pointing into the face): where
  // x -> (p − x) . m + eps_s + sin(theta_v) (|p − x| + eps_s) + decision margin is < 0, (p − x̂) . m <
  // −sin(theta_v) |p − x̂| for every sensed x̂ and the robot cannot enter. Convex along the edge.
  std::function<double(const Vec3&)> enter_margin(const Edge& e, int fi) const {
    const Face& f = cspace_.faces()[fi];
    Vec3 m = f.normal.cross(e.b - e.a).normalized();
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& q : f.polygon) centroid += q / static_cast<double>(f.polygon.size());
    if ((centroid - e.a).dot(m) < 0) m = -m;
    const double sv = std::sin(u_.theta_v), eps = u_.eps_s, margin = kDecisionMargin * cspace_.scale();
    const Vec3 p = p_;
    return [p, m, sv, eps, margin](const Vec3& x) {
      return (p - x).dot(m) + eps + sv * ((p - x).norm() + eps) + margin;
    };
  }
  // The parameter intervals within [t0, t1] of edge e from which the robot may enter face fi: the interval
  // minus the open part where enter_margin < 0 (a convex function's sublevel set: one interval, found by a
  // ternary search for the minimum and bisections for its ends, each end rounded outward).
  std::vector<std::pair<double, double>> enter_parts(const Edge& e, int fi, double t0, double t1) const {
    const auto g0 = enter_margin(e, fi);
    const Vec3 d = e.b - e.a;
    auto g = [&](double t) { return g0(e.a + t * d); };
    if (t1 <= t0)
      return g(t0) >= 0 ? std::vector<std::pair<double, double>>{{t0, t1}}
                        : std::vector<std::pair<double, double>>{};
    double lo = t0, hi = t1;
    for (int i = 0; i < 100; ++i) {  // ternary search for the minimum
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      if (g(m1) <= g(m2))
        hi = m2;
      else
        lo = m1;
    }
    const double tm = 0.5 * (lo + hi);
    if (g(tm) >= 0) return {{t0, t1}};
    std::vector<std::pair<double, double>> parts;
    if (g(t0) >= 0) {  // g decreases from t0 to tm: the last t with g >= 0, rounded up
      double a = t0, b = tm;
      for (int i = 0; i < 100; ++i) (g(0.5 * (a + b)) >= 0 ? a : b) = 0.5 * (a + b);
      parts.push_back({t0, std::min(t1, b + kEdgeParamSlack)});
    }
    if (g(t1) >= 0) {
      double a = tm, b = t1;
      for (int i = 0; i < 100; ++i) (g(0.5 * (a + b)) >= 0 ? b : a) = 0.5 * (a + b);
      parts.push_back({std::max(t0, a - kEdgeParamSlack), t1});
    }
    return parts;
  }
  // The same tests pointwise: a point of face fi strictly within no_slide_radius of p' must leave (the pull
  // points into free space for every sensed position), one within no_leave_radius must stay. 0: no such
  // points. From (−depth − eps_s) = tan(theta_v) (d + eps_s), resp. (depth − eps_s) = tan(theta_v) (d +
  // eps_s).
  double no_slide_radius(int fi) const {
    return std::max(0.0, (-face_[fi].depth - u_.eps_s) / tan_v_ - u_.eps_s);
  }
  double no_leave_radius(int fi) const {
    return std::max(0.0, (face_[fi].depth - u_.eps_s) / tan_v_ - u_.eps_s);
  }
  // The part of the face inside a polygon inscribed in that disk, shrunk by the decision margin (what is
  // subtracted is inside the open disk: sound).
  ChartRegion inner_disk_set(int fi, const Vec3& center, double radius) const {
    if (!std::isfinite(radius))
      return ChartRegion(to_polygon(reached_impl_.face_polygon[fi]), reached_impl_.charts[fi].cell);
    const double r = radius - kDecisionMargin * cspace_.scale();
    if (r <= 0) return ChartRegion();
    const Points2 d = clip(chart_disk(reached_impl_, fi, center, r, false), reached_impl_.face_polygon[fi]);
    return d.size() >= 3 ? ChartRegion(to_polygon(d), reached_impl_.charts[fi].cell) : ChartRegion();
  }
  // The overshoot of a slide on face fi, in the face's plane (Fig 3.14): sliding trajectories from s stay in
  // the projection of the free-space cylinder about seg[s, p + eps_o u(s)], u(s) = (p − s) / |p − s|, whose
  // overshoot end projects to p' + eps_o P(u(s)) with |P(u(s))| = d / sqrt(d^2 + h^2) (d = |s − p'|, h the
  // distance of p from the plane), increasing in d. Over the entries it is at most eps_o g(d_max + eps_s,
  // h − eps_s): the sensing error may move the aim point by eps_s (Fig 3.10), which can only bring it nearer
  // the plane and farther along it.
  double in_plane_overshoot(int fi, const std::vector<Vec3>& from) const {
    const double d = max_dist(fi, from) + u_.eps_s;
    const double h = std::max(0.0, std::abs(face_[fi].depth) - u_.eps_s);
    if (h == 0) return eps_o_;
    return eps_o_ * (d / std::hypot(d, h)) * (1 + kSpringRelativeSlack);
  }
  double max_dist(int fi, const std::vector<Vec3>& pts) const {
    double d = 0;
    for (const Vec3& x : pts) d = std::max(d, (x - face_[fi].center).norm());
    return d;
  }
  std::vector<Vec3> lifted(int fi, const Points2& part) const {
    std::vector<Vec3> out;
    for (const Point2& q : part) out.push_back(reached_impl_.charts[fi].lift_double(q));
    return out;
  }

  // ---- processing ----
  // Entries are slid first, so that one flight per face step covers the landings and their strips.
  void process_face(int fi) {
    ++steps_;
    slide_entries(fi);
    process_new_parts(fi);
  }

  // Alg 4.4: the entries minus the strong configurations and minus the no-slide disk, one strip from their
  // hull (it contains the strips from each: same generators, larger hull), clipped to the face; the part
  // outside the no-slide disk is reached.
  void slide_entries(int fi) {
    ChartRegion entry = std::move(face_[fi].pending_entry);
    face_[fi].pending_entry = ChartRegion();
    std::vector<Points2> lower = std::move(face_[fi].pending_entry_lower);
    face_[fi].pending_entry_lower.clear();
    if (entry.is_empty() && lower.empty()) return;
    entry.difference(face_[fi].strong);
    entry.difference(face_[fi].no_slide);
    if (model_ == SpringModel::kVelocity) {
      // Each convex entry piece and each lower entry on its own (their union is what the hull bounds, more
      // tightly: the spiral bounds are per source).
      std::vector<Points2> sources = convex_pieces(entry);
      for (const Points2& l : lower)
        if (!sticks_strongly(fi, l)) sources.push_back(l);
      // The slides are united in a balanced tree of overlays (union_of), not one after another.
      std::vector<ChartRegion> slid_parts;
      for (const Points2& src : sources) {
        if (src.empty() || !may_stay(fi, lifted(fi, src))) continue;
        Points2 lower_out;
        ChartRegion slid = velocity_slide(reached_impl_, fi, src, velocity_, &lower_out);
        if (!slid.is_empty())
          slid_parts.push_back(std::move(slid));
        else if (!lower_out.empty())
          add_reached_lower(fi, lower_out);
      }
      ChartRegion slid_all = union_of(std::move(slid_parts));
      if (!slid_all.is_empty()) {
        slid_all.difference(face_[fi].no_slide);
        add_reached_region(fi, slid_all);
      }
      return;
    }
    Points2 entry_pts;
    for (const Points2& part : convex_pieces(entry))
      entry_pts.insert(entry_pts.end(), part.begin(), part.end());
    for (const Points2& l : lower)
      if (!sticks_strongly(fi, l) && may_stay(fi, lifted(fi, l)))
        entry_pts.insert(entry_pts.end(), l.begin(), l.end());
    const Points2 entry_hull = hull_or_points(entry_pts);
    if (entry_hull.empty() || !may_stay(fi, lifted(fi, entry_hull))) return;
    const Points2 strip = spring_strip(reached_impl_, fi, entry_hull, face_[fi].center, eps_t_,
                                       in_plane_overshoot(fi, lifted(fi, entry_hull)));
    if (strip.size() >= 3) {
      // The slide ends where the robot must leave the face: the strip outside the no-slide disk.
      ChartRegion slid(to_polygon(strip), reached_impl_.charts[fi].cell);
      slid.difference(face_[fi].no_slide);
      add_reached_region(fi, slid);
    } else if (!strip.empty()) {
      add_reached_lower(fi, strip);
    }
  }

  // A lower entry inside the face's strong configurations sticks where it enters (Alg 4.4).
  bool sticks_strongly(int fi, const Points2& l) const {
    if (face_[fi].strong_poly.empty()) return false;
    for (const Point2& q : l)
      if (!inside_closed(face_[fi].strong_poly, q)) return false;
    return true;
  }

  // New reached parts: the edges and corners they touch, then one flight from the hull of what may leave.
  void process_new_parts(int fi) {
    const FaceChart& chart = reached_impl_.charts[fi];
    ChartRegion fresh = std::move(face_[fi].pending_new);
    face_[fi].pending_new = ChartRegion();
    std::vector<Points2> news = convex_pieces(fresh);
    for (Points2& l : face_[fi].pending_new_lower) news.push_back(std::move(l));
    face_[fi].pending_new_lower.clear();
    add_boundary_closure(
        reached_impl_, fi, news, [&](int ei, double t0, double t1) { add_interval(ei, t0, t1); },
        [&](int vi) { add_vertex(vi); });
    fresh.difference(face_[fi].strong);
    // Points inside the no-leave disk cannot leave the face: they do not fly.
    fresh.difference(face_[fi].no_leave);
    // One source per face step: the hull of everything new outside the strong configurations (the volume
    // from a hull contains the volumes from its parts: sound, looser, far fewer exact sections).
    Points2 fly_pts;
    for (const Points2& part : convex_pieces(fresh)) fly_pts.insert(fly_pts.end(), part.begin(), part.end());
    for (const Points2& l : news)
      if (l.size() < 3 && may_leave(fi, lifted(fi, l))) fly_pts.insert(fly_pts.end(), l.begin(), l.end());
    const Points2 fly_hull = hull_or_points(fly_pts);
    if (!fly_hull.empty() && may_leave(fi, lifted(fi, fly_hull))) {
      std::vector<Point3> src;
      for (const Point2& q : fly_hull) src.push_back(chart.lift(q));
      // First order also with the servo coast: where the pull turns to leave the face its normal component
      // passes zero, so the sliding velocity (its tangential part) meets the flight velocity without a jump
      // for the servo to lag behind (docs/verifier.md "Servo coast of springs").
      fly(src, fi);
    }
  }

  // Servo coast of springs (docs/verifier.md "Servo coast of springs"): velocity model with tau V > 0.
  bool coasts() const { return model_ == SpringModel::kVelocity && velocity_.coast > 0; }

  // The coast of a robot leaving from conv(pts): tau |u| <= tau V, and the spring's speed is at most lambda
  // (|p − x| + eps_s) (its drive before the top speed), so tau |u| <= lambda tau (|p − x| + eps_s).
  double coast_at(const std::vector<Vec3>& pts) const {
    double c = velocity_.coast;
    if (spring_lag_ > 0) {
      double far = 0;
      for (const Vec3& x : pts) far = std::max(far, (x - p_).norm());
      c = std::min(c, spring_lag_ * (far + u_.eps_s));
    }
    return c * (1 + kDecisionMargin);
  }

  // The coast displacements of every velocity in face fi's plane: the square circumscribing the disk of
  // radius c.
  std::vector<Vec3> in_plane_square(int fi, double c) const {
    const Vec3& n = cspace_.faces()[fi].normal;
    const Vec3 t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    return {c * (t1 + t2), c * (t1 - t2), c * (-t1 - t2), c * (-t1 + t2)};
  }

  // The coast displacements tau u (|tau u| <= c, coast_at) of a robot sliding on face fi at points of
  // conv(pts) (in the plane). Sliding, the in-plane velocity at x is within beta(d) = asin(sin(theta_v)
  // sqrt(d^2 + h^2) / d) of the direction to p*' (docs/verifier.md "Velocity-form spring model"; d the
  // in-plane distance, h <= |depth| + eps_s), and p*' lies within eps_s of p': within gamma = beta(d_min) +
  // asin(eps_s / d_min) of the direction to p', and over conv(pts) those directions lie within the largest
  // angle sigma between a vertex's and their mean: the wedge of half-angle alpha = sigma + gamma (at most
  // pi/3; otherwise, or near p', `fallback`).
  std::vector<Vec3> slide_wedge(int fi, const std::vector<Vec3>& pts, double c,
                                const std::vector<Vec3>& fallback) const {
    const Face& f = cspace_.faces()[fi];
    const Vec3 pp = p_ + face_[fi].depth * f.normal;  // p' (p projected on the plane)
    const double eps = u_.eps_s, h = std::abs(face_[fi].depth) + eps;
    std::vector<Vec3> dirs;
    Vec3 mean = Vec3::Zero();
    for (const Vec3& x : pts) {
      const Vec3 v = pp - x;
      if (v.norm() <= eps) return fallback;
      dirs.push_back(v.normalized());
      mean += dirs.back();
    }
    if (mean.norm() < 0.5 * static_cast<double>(pts.size())) return fallback;  // directions spread widely
    const Vec3 axis = mean.normalized();
    double sigma = 0;
    for (const Vec3& m : dirs) sigma = std::max(sigma, angle_between(axis, m));
    if (sigma >= std::numbers::pi / 3) return fallback;
    // A lower bound of the in-plane distance from p' over conv(pts): (p' − x) . axis is linear in x, so its
    // least value over the hull is at a vertex, and |p' − x| is at least that.
    double d_min = std::numeric_limits<double>::infinity();
    for (const Vec3& x : pts) d_min = std::min(d_min, (pp - x).dot(axis));
    d_min *= 1 - kDecisionMargin;
    if (d_min <= eps) return fallback;
    const double sin_beta = std::sin(u_.theta_v) * std::hypot(d_min, h) / d_min;
    if (sin_beta >= 1) return fallback;
    const double gamma = std::asin(sin_beta) + std::asin(eps / d_min);
    const double alpha = (sigma + gamma) * (1 + kDecisionMargin) + kDecisionMargin;
    if (alpha > std::numbers::pi / 3) return fallback;
    // The sector of radius c and half-angle alpha lies in the pentagon 0, c w(−alpha), R w(−alpha / 2),
    // R w(alpha / 2), c w(alpha), R = c / cos(alpha / 2) (its tangents at −alpha, 0 and alpha meet there).
    const Vec3 side = f.normal.cross(axis).normalized();
    const auto w = [&](double angle, double r) {
      return Vec3(r * (std::cos(angle) * axis + std::sin(angle) * side));
    };
    const double r = c / std::cos(alpha / 2);
    return {Vec3::Zero(), w(-alpha, c), w(-alpha / 2, r), w(alpha / 2, r), w(alpha, c)};
  }

  // slide_wedge toward edge e from conv(pts) (points of the edge), falling back to the outward half-disk of
  // radius tau V, in the triangle −2c t, 2c t, 2c out (|x| + y <= 2c on it).
  std::vector<Vec3> rim_sector(const Edge& e, int fi, const std::vector<Vec3>& pts) const {
    const Vec3 t = (e.b - e.a).normalized(), out = -into_face(e, fi);
    const double c = coast_at(pts);
    return slide_wedge(fi, pts, c, {-2 * c * t, 2 * c * t, 2 * c * out});
  }

  // slide_wedge from conv(pts) on face fi, falling back to the square circumscribing the disk of radius tau
  // V.
  std::vector<Vec3> face_sector(int fi, const std::vector<Vec3>& pts) const {
    const double c = coast_at(pts);
    return slide_wedge(fi, pts, c, in_plane_square(fi, c));
  }

  static Points2 hull_or_points(const Points2& pts) {
    if (pts.empty()) return {};
    Points2 h = convex_hull(pts);
    return h.empty() ? Points2{pts[0]} : h;
  }

  void fly(const std::vector<Point3>& src, int source_face) {
    absorb(model_ == SpringModel::kVelocity
               ? velocity_fly(reached_impl_, src, source_face, velocity_)
               : spring_fly(reached_impl_, spring_generators(src, p_, eps_o_), source_face, eps_t_));
  }

  // Servo coast of springs (docs/verifier.md "Servo coast of springs"): a robot that leaves `src` at a
  // sliding velocity u keeps it for about tau, so it flies from src + conv(0, tau u): one flight per face it
  // may slide on (velocity_fly grows each piece's region by that face's departure displacements of the
  // piece); with none, the first-order flight.
  void coast_fly(const std::vector<Point3>& src, int source_face,
                 const std::vector<CoastDeparture>& departures) {
    if (departures.empty()) {
      fly(src, source_face);
      return;
    }
    for (const CoastDeparture& d : departures)
      absorb(velocity_fly(reached_impl_, src, source_face, velocity_, d));
  }

  void absorb(std::vector<FlightHit> hits) {
    flew_ = true;
    for (FlightHit& h : hits) {
      if (model_ == SpringModel::kVelocity) {
        // No landing inside the no-slide disk: there every admissible velocity points out of the face, so
        // near such a point the height above the plane only grows and no path from free space reaches it
        // (docs/verifier.md "No landing where the pull leaves the face"). The start keeps its points.
        if (!h.region.is_empty()) {
          h.region.difference(face_[h.face].no_slide);
          if (h.region.is_empty()) continue;
        } else if (inside_no_slide(h.face, h.lower)) {
          continue;
        }
      }
      if (!h.region.is_empty())
        add_entry_region(h.face, h.region);
      else
        add_entry_lower(h.face, h.lower);
    }
  }

  // Every point of `pts` (chart points of face fi) strictly inside the no-slide disk (its inner polygon).
  bool inside_no_slide(int fi, const Points2& pts) const {
    if (pts.empty() || face_[fi].no_slide.is_empty()) return false;
    for (const Point2& q : pts)
      if (face_[fi].no_slide.oriented_side(q) != CGAL::ON_POSITIVE_SIDE) return false;
    return true;
  }

  // The edge's parameter interval about the projection q of p where motion along the edge may go either way
  // (|x − q| = s with s − eps_s <= sin(theta_v) (|p − x| + eps_s)), or the overshoot eps_o if larger.
  double edge_halfwidth(const Edge& e) const {
    // The via-point model may overshoot q by eps_o; the velocity forms do not overshoot p*.
    return edge_either_way_halfwidth(e, p_, u_, model_ == SpringModel::kVelocity ? 0.0 : eps_o_);
  }

  // Staying on an edge (Buckley §3.3.2 applied to edge contact): the robot keeps an edge contact only while
  // it may push into every face that meets there; pulling away from one face moves it off the edge line, into
  // free space at a convex edge, along the other face (a may-enter entry) at a concave one. The half-width of
  // the parameter interval about tp where it must leave (edge_must_leave_halfwidth), shrunk by the decision
  // margin (favours staying).
  double edge_leave_halfwidth(const Edge& e, double tp) const {
    return edge_must_leave_halfwidth(cspace_, e, tp, p_, u_, kDecisionMargin * cspace_.scale());
  }

  void process_edge(int ei) {
    ++steps_;
    std::vector<EdgeInterval> ivs = std::move(edge_[ei].pending);
    edge_[ei].pending.clear();
    const Edge& e = cspace_.edges()[ei];
    for (const EdgeInterval& iv : ivs) {
      if (iv.t0 <= kEdgeParamSlack) add_vertex(e.vertex_a - face_count_ - edge_count_);
      if (iv.t1 >= 1 - kEdgeParamSlack) add_vertex(e.vertex_b - face_count_ - edge_count_);
    }
    // Contact lift (docs/verifier.md "Contact lift"): a robot sliding on one face into this concave edge may
    // meet the other face up to lift_ above the edge, whatever the edge's class; there it may stick or slide.
    if (lift_ > 0 && e.shape == EdgeShape::kConcave && e.faces.size() == 2) add_lift_strips(ei, ivs);
    const Vec3 d = e.b - e.a;
    const double len = d.norm();
    const double tp = (p_ - e.a).dot(d) / (len * len);
    const double w = edge_halfwidth(e) / len + kEdgeParamSlack;
    // The robot cannot stay on the edge strictly inside (tp - leave, tp + leave) (edge_leave_halfwidth).
    const double leave = edge_leave_halfwidth(e, tp);
    for (const EdgeInterval& iv : ivs) {
      const Vec3 a = e.a + iv.t0 * d, b = e.a + iv.t1 * d;
      // Along the edge toward q (and either way near it), but not into the part where it must leave;
      // flat edges are motion on the plane (faces).
      if (e.shape != EdgeShape::kFlat) {
        if (leave <= 0) {
          add_interval(ei, std::max(0.0, std::min(iv.t0, tp - w)), std::min(1.0, std::max(iv.t1, tp + w)));
        } else {
          const double lo = tp - leave, hi = tp + leave;
          if (iv.t0 <= lo)  // from below the leaving part: toward q, stopping where it must leave
            add_interval(ei, std::max(0.0, std::min(iv.t0, tp - w)),
                         std::min({1.0, std::max(std::min(iv.t1, lo), tp + w), lo}));
          if (iv.t1 >= hi)  // from above it
            add_interval(ei, std::max({0.0, std::min(std::max(iv.t0, hi), tp - w), hi}),
                         std::min(1.0, std::max(iv.t1, tp + w)));
        }
      }
      // Onto an adjacent face when some admissible velocity points into it (see enter_parts).
      for (int f : e.faces) {
        const int fi = f;
        // Only the parts of the interval from which entering is possible.
        for (const auto& [s0, s1] : enter_parts(e, fi, iv.t0, iv.t1)) {
          const Point2 ca = reached_impl_.charts[fi].project(Vec3(e.a + s0 * d));
          const Point2 cb = reached_impl_.charts[fi].project(Vec3(e.a + s1 * d));
          add_entry_lower(fi, s1 > s0 ? Points2{ca, cb} : Points2{ca});
        }
      }
      // Flight: from a concave or flat edge only if every adjacent face may be left, from a convex one if
      // some may; non-manifold edges always.
      int leave = 0;
      for (int f : e.faces) leave += may_leave(f, {a, b}) ? 1 : 0;
      const int nfaces = static_cast<int>(e.faces.size());
      const bool flies =
          e.shape == EdgeShape::kNonManifold || (e.shape == EdgeShape::kConvex ? leave > 0 : leave == nfaces);
      if (!flies) continue;
      std::vector<Point3> src = {exact(a)};
      if (iv.t1 > iv.t0) src.push_back(exact(b));
      if (!coasts()) {
        fly(src, -1);
        continue;
      }
      // Servo coast: at a convex edge the robot may arrive sliding on a face toward it (may_approach) and
      // leave at that velocity: one departure wedge per such face, in its plane. (Sliding along the edge,
      // its coast is contact motion, which the first-order edge model bounds; not covered, as for dampers.)
      std::vector<CoastDeparture> departures;
      if (e.shape == EdgeShape::kConvex)
        for (int g : e.faces)
          if (may_approach(e, g, a, b))
            departures.push_back(
                [this, &e, g](const std::vector<Vec3>& piece) { return rim_sector(e, g, piece); });
      coast_fly(src, -1, departures);
    }
  }

  // In-face unit normal of edge e on face fi, pointing from the edge into the face.
  Vec3 into_face(const Edge& e, int fi) const {
    const Face& f = cspace_.faces()[fi];
    Vec3 m = f.normal.cross(e.b - e.a).normalized();
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& q : f.polygon) centroid += q / static_cast<double>(f.polygon.size());
    if ((centroid - e.a).dot(m) < 0) m = -m;
    return m;
  }

  // A robot sliding on face g may approach edge e at some point of seg[a, b]: not every admissible pull
  // points away from the edge. It surely points away at x when (p − x̂) . m > sin(theta_v) |p − x̂| for every
  // sensed x̂, i.e. (p − x) . m − eps_s − sin(theta_v) (|p − x| + eps_s) > 0 (m into g): then the sliding
  // velocity (the tangential part of the imparted force) has a positive m component. That function is
  // concave along the segment, so its least value is at an end. Decided with a margin that favours "may".
  bool may_approach(const Edge& e, int g, const Vec3& a, const Vec3& b) const {
    if (!slides_on(g)) return false;
    // Not all of the interval inside g's no-slide disk: there every admissible pull lifts the robot off g,
    // so it arrives in flight (the flights cover that), not sliding on g.
    const double r = no_slide_radius(g) - kDecisionMargin * cspace_.scale();
    if (r > 0 && max_dist(g, {a, b}) < r) return false;
    const Vec3 m = into_face(e, g);
    const double sv = std::sin(u_.theta_v), margin = kDecisionMargin * cspace_.scale();
    auto away = [&](const Vec3& x) {
      return (p_ - x).dot(m) - u_.eps_s - sv * ((p_ - x).norm() + u_.eps_s) - margin;
    };
    return std::min(away(a), away(b)) <= 0;
  }

  // Something reached on face g lies outside its strong configurations (where the robot sticks, Alg 4.4)
  // and outside its no-slide disk (where the pull lifts it off): the robot may slide on g, and a lift strip
  // needs slipping. (The disk is tested by distance, not by its polygon clipped to the face, so that
  // reached segments on the face's boundary count as inside it.)
  bool slides_on(int g) const {
    const double r = no_slide_radius(g) - kDecisionMargin * cspace_.scale();
    auto must_leave = [&](const Points2& l) { return r > 0 && max_dist(g, lifted(g, l)) < r; };
    const FaceSet& fs = reached_impl_.faces[g];
    if (!fs.region.is_empty()) {
      ChartRegion sliding = fs.region;
      sliding.difference(face_[g].strong);
      for (const Points2& piece : convex_pieces(sliding))
        if (!must_leave(piece)) return true;
    }
    for (const Segment2& sg : fs.segments) {
      const Points2 l = {sg.source(), sg.target()};
      if (!sticks_strongly(g, l) && !must_leave(l)) return true;
    }
    for (const Point2& q : fs.points)
      if (!sticks_strongly(g, {q}) && !must_leave({q})) return true;
    return false;
  }

  // Contact lift at a concave edge (the dampers' add_lift_bands, damper_projection.cc): sliding on face g
  // toward the edge, the robot may be up to lift_ off g (MuJoCo's slip hops; the bound
  // experiments/validation/verifier_model.h rollout_contact_lift holds for springs too, whose speed is at
  // most the top speed). Its velocity while off g is the model's, so it meets the other face f above the
  // reached edge interval [a, b]: f gets the strip [a, b] + [0, lift_] d (d in f, away from the edge),
  // clipped to f, as an entry: where f's strong configurations hold it, it sticks; elsewhere it may slide.
  void add_lift_strips(int ei, const std::vector<EdgeInterval>& ivs) {
    const Edge& e = cspace_.edges()[ei];
    const Vec3 dir = e.b - e.a;
    for (int f : e.faces) {
      int g = -1;
      for (int h : e.faces)
        if (h != f) g = h;
      if (g < 0) continue;
      const Vec3 d = into_face(e, f);
      const FaceChart& chart = reached_impl_.charts[f];
      for (const EdgeInterval& iv : ivs) {
        const Vec3 a = e.a + iv.t0 * dir, b = e.a + iv.t1 * dir;
        if (!may_approach(e, g, a, b)) continue;
        const Points2 rect =
            clip(convex_hull({chart.project(a), chart.project(b), chart.project(Vec3(b + lift_ * d)),
                              chart.project(Vec3(a + lift_ * d))}),
                 reached_impl_.face_polygon[f]);
        if (rect.size() >= 3)
          add_entry_region(f, ChartRegion(to_polygon(rect), reached_impl_.charts[f].cell));
        else if (!rect.empty())
          add_entry_lower(f, rect);
      }
    }
  }

  void process_vertex(int vi) {
    ++steps_;
    pend_vertex_[vi] = 0;
    const Vertex& vx = cspace_.vertices()[vi];
    if (strong_atom_[edge_count_ + vi]) return;  // p in the vertex's strong region: it sticks there
    for (int e : vx.edges) {
      const Edge& edge = cspace_.edges()[e - face_count_];
      const double t = edge.vertex_a == vx.id ? 0.0 : 1.0;
      add_interval(e - face_count_, t, t);
    }
    for (int f : vx.faces) add_entry_lower(f, {reached_impl_.charts[f].project(vx.point)});
    if (!coasts()) {
      fly({exact(vx.point)}, -1);
      return;
    }
    // Servo coast: one departure wedge per face at the vertex that the robot may slide on, in its plane (a
    // robot that arrived along an edge: its coast past the vertex is not covered, as for dampers).
    std::vector<CoastDeparture> departures;
    for (int f : vx.faces)
      if (slides_on(f)) {
        std::vector<Vec3> sector = face_sector(f, {vx.point});
        departures.push_back([sector](const std::vector<Vec3>&) { return sector; });
      }
    coast_fly({exact(vx.point)}, -1, departures);
  }

  // ---- results ----
  ReachedSet termination() const {
    ReachedSet out(cspace_);
    ReachedSet::Impl& t = out.impl();
    for (int fi = 0; fi < face_count_; ++fi) {
      const Points2& w = face_[fi].weak;
      if (w.empty()) continue;
      const FaceSet& f = reached_impl_.faces[fi];
      if (!f.region.is_empty() && w.size() >= 3) {
        ChartRegion part = f.region;
        part.intersection(to_polygon(w));
        ChartRegion added;
        if (!part.is_empty()) t.add_region(fi, part, &added);
      }
      for (const Segment2& s : f.segments) {
        FT t0, t1;
        if (clip_segment(w, s.source(), s.target(), &t0, &t1)) {
          const Point2 a = s.source() + (s.target() - s.source()) * t0;
          const Point2 b = s.source() + (s.target() - s.source()) * t1;
          if (t0 == t1)
            t.add_point(fi, a);
          else
            t.add_segment(fi, a, b);
        }
      }
      for (const Point2& q : f.points)
        if (inside_closed(w, q)) t.add_point(fi, q);
    }
    for (int ei = 0; ei < edge_count_; ++ei)
      if (weak_atom_[ei])
        for (const EdgeInterval& iv : reached_impl_.edges[ei]) t.add_interval(ei, iv.t0, iv.t1, nullptr);
    for (int vi = 0; vi < vertex_count_; ++vi)
      if (weak_atom_[edge_count_ + vi] && reached_impl_.vertices[vi]) t.add_vertex(vi);
    return out;
  }

  // Does the closed ball about p of radius r meet free space? p free, or within r of the contact surface
  // (every surface point is a limit of free points). Decided with a relative margin that favours "yes".
  bool rest_ball_meets_free(double r) const {
    if (cspace_.classify(p_, 0) == PointClass::kFree) return true;
    return cspace_.distance_to_surface(p_) <=
           r * (1 + kSpringRelativeSlack) + kDecisionMargin * cspace_.scale();
  }

  // Margin (x scene scale) by which floating-point decisions about leaving/staying/resting favour motion.
  static constexpr double kDecisionMargin = 1e-9;

  const CSpace& cspace_;
  Uncertainty u_;
  Vec3 p_;
  SpringModel model_;
  double eps_t_, eps_o_, tan_v_;
  VelocitySpring velocity_;  // the velocity model's shared data (kVelocity only)
  const ReachedSet& start_;  // alive during run() (forward_project_spring)
  double kappa_;             // the stop rule's relative speed
  double lift_;              // contact lift (task units; 0: first-order contact)
  double spring_lag_ = 0;    // lambda tau (VerifyOptions::spring_lag; 0: not used)
  ReachedSet reached_;
  ReachedSet::Impl& reached_impl_;
  int face_count_ = 0, edge_count_ = 0, vertex_count_ = 0;
  std::vector<FaceState> face_;
  std::vector<EdgeState> edge_;
  std::vector<bool> weak_atom_, strong_atom_;  // edges then vertices
  double slow_radius_ = 0;                     // slow_stop_radius (velocity model)
  std::vector<char> pend_vertex_;
  int widened_ = 0;
  bool flew_ = false;
  int steps_ = 0;
};

}  // namespace

double spring_rest_radius(const Uncertainty& u) { return std::max(u.eps_p, u.eps_s); }

double slow_stop_radius(const ReachedSet& start, const Vec3& p, const Uncertainty& u, double kappa) {
  if (kappa <= 0) return 0;
  double far = 0;  // max over the start of |p − x0| (a polygon's farthest point is a vertex)
  for (const ReachedPiece& piece : start.pieces())
    for (const Vec3& q : piece.polygon) far = std::max(far, (q - p).norm());
  return kappa * (far + u.eps_s);
}

const char* spring_model_name(SpringModel m) {
  return m == SpringModel::kVelocity ? "velocity" : "via-point";
}

SpringProjection forward_project_spring(const LoadedTask& task, const ReachedSet& start, const Vec3& p,
                                        SpringModel model, double stop_relative_speed, double contact_lift,
                                        double servo_coast, double spring_lag) {
  return SpringProjector(task, start, p, model, stop_relative_speed, contact_lift, servo_coast, spring_lag)
      .run();
}

}  // namespace cmt

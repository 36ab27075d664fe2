// Weak and strong damper backprojections (Buckley Alg 5.2, §5.4.3): the forward projection's relations
// (damper_projection.cc steps A-D) read backwards. Each forward rule "from a point y the robot may reach z"
// becomes "z in W puts y in W":
//  - A, sliding on a face: z in y + wedge, so y in z - wedge (the wedge swept back);
//  - B, along an edge toward an end: y behind z in that direction;
//  - C, from a vertex onto its edges and faces: the vertex is the end of those edges and a point of those
//    faces, so the closure rules and the backslides reach it;
//  - D, flight: z in y + cone(v), so y in z + cone(-v) (Fig 5.14: the two cones are the same), y on a face
//    from which some admissible velocity lifts off and in front of the face z lies on.
#include "verifier/backprojection.h"

#include <algorithm>
#include <cmath>

#include "verifier/damper.h"
#include "verifier/internal/damper_flight.h"
#include "verifier/internal/face_sweep.h"
#include "verifier/internal/worklist.h"

namespace cmt {
namespace {

using namespace face_geometry;

class BackProjector {
 public:
  BackProjector(const LoadedTask& task, const AtomCones& cones, const ReachedSet& from, const Vec3& v)
      : cspace_(task.cspace),
        v_(v.normalized()),
        theta_v_(task.task.uncertainty.theta_v),
        weak_(from),
        reached_impl_(weak_.impl()),
        work_(reached_impl_) {  // everything in `from` is pending
    face_count_ = static_cast<int>(cspace_.faces().size());
    edge_count_ = static_cast<int>(cspace_.edges().size());
    vertex_count_ = static_cast<int>(cspace_.vertices().size());
    for (int id = 0; id < cspace_.atom_count(); ++id)
      must_.push_back(classify_damper(cones, id, v_, theta_v_) == StickClass::kMust);
    for (const Face& f : cspace_.faces()) {
      sweeps_.push_back(face_sweep(f, v_, theta_v_, cspace_.scale()));
      // Forward flights leave a face only when some admissible velocity does (damper_projection.cc, D);
      // they land on it only when some admissible velocity enters it.
      lifts_off_.push_back(v_.dot(f.normal) > -std::sin(theta_v_ + kFlightAngleSlack));
      lands_on_.push_back(v_.dot(f.normal) < std::sin(theta_v_ + kFlightAngleSlack));
    }
    reverse_cone_ = flight_cone(-v_, theta_v_, cspace_.scale());
    walls_.resize(face_count_);
    for (const Edge& e : cspace_.edges())
      if (e.shape == EdgeShape::kConcave && e.faces.size() == 2)
        for (int k = 0; k < 2; ++k) walls_[e.faces[k]].push_back({e.faces[1 - k], exact(e.a), exact(e.b)});
  }

  WeakBackprojection run() {
    const bool capped = work_.run(
        steps_, kMaxBackprojectionSteps, [&](int fi) { process_face(fi); }, [&](int ei) { process_edge(ei); },
        [&](int vi) { process_vertex(vi); });
    return finish_weak_backprojection(std::move(weak_), capped, steps_);
  }

 private:
  // Step A reversed: the points of face fi whose sweep wedge reaches `part` (chart points of the face).
  void backslide(int fi, const Points2& part) {
    const Sweep& sw = sweeps_[fi];
    if (must_[fi] || sw.none) return;
    if (sw.whole) {
      work_.add_region(
          fi, ChartRegion(to_polygon(reached_impl_.face_polygon[fi]), reached_impl_.charts[fi].cell));
      return;
    }
    const FaceChart& chart = reached_impl_.charts[fi];
    const Vector2 bp = chart.project_direction(sw.far * sw.b_plus);
    const Vector2 bm = chart.project_direction(sw.far * sw.b_minus);
    Points2 pts = part;
    for (const Point2& p : part) {
      pts.push_back(p - bp);
      pts.push_back(p - bm);
    }
    work_.add_convex(fi, clip(convex_hull(pts), reached_impl_.face_polygon[fi]));
  }

  // Step D reversed: flight hits are starting points y; only faces the robot may lift off keep them as face
  // points (a must-stick face or one every admissible velocity presses into only adds their boundary, which
  // belongs to edges and vertices whose own rules decide).
  void absorb(const std::vector<FlightHit>& hits) {
    for (const FlightHit& h : hits) {
      std::vector<Points2> parts =
          h.region.is_empty() ? std::vector<Points2>{h.lower} : convex_pieces(h.region);
      if (must_[h.face] || !lifts_off_[h.face]) {
        work_.add_closure(h.face, parts);
        continue;
      }
      if (!h.region.is_empty())
        work_.add_region(h.face, h.region);
      else
        work_.add_convex(h.face, h.lower);
    }
  }

  void fly_back(const std::vector<Point3>& source, const std::vector<Plane3>& keep_front, int face) {
    FlightSource src;
    src.vertices = source;
    src.keep_front = keep_front;
    src.face = face;
    if (face >= 0) src.walls = walls_[face];
    absorb(fly(reached_impl_, src, reverse_cone_));
  }

  void process_face(int fi) {
    ++steps_;
    const std::vector<Points2> parts = work_.take_face(fi);
    work_.add_closure(fi, parts);
    for (const Points2& part : parts) backslide(fi, part);
    if (!lands_on_[fi]) return;
    const FaceChart& chart = reached_impl_.charts[fi];
    for (const Points2& part : parts) {
      std::vector<Point3> source;
      for (const Point2& p : part) source.push_back(chart.lift(p));
      fly_back(source, {chart.plane}, fi);
    }
  }

  void process_edge(int ei) {
    ++steps_;
    const std::vector<EdgeInterval> ivs = work_.take_edge(ei);
    const Edge& e = cspace_.edges()[ei];
    const int id = face_count_ + ei;
    work_.add_interval_ends(ei, ivs);
    // Step B reversed (a flat edge is no crease: its faces' wedges cover motion along it).
    if (!must_[id] && e.shape != EdgeShape::kFlat) {
      const EdgeSliding es = edge_sliding(cspace_, id, v_, theta_v_);
      for (const EdgeInterval& iv : ivs) {
        if (es.toward_b) work_.add_interval(ei, 0, iv.t1);
        if (es.toward_a) work_.add_interval(ei, iv.t0, 1);
      }
    }
    for (const EdgeInterval& iv : ivs) {
      const Vec3 a = e.a + iv.t0 * (e.b - e.a), b = e.a + iv.t1 * (e.b - e.a);
      for (int f : e.faces) {
        const FaceChart& chart = reached_impl_.charts[f];
        Points2 seg;
        seg.reserve(2);
        seg.push_back(chart.project(a));
        if (iv.t1 > iv.t0) seg.push_back(chart.project(b));
        backslide(f, seg);
      }
      std::vector<Point3> source;
      source.reserve(2);
      source.push_back(exact(a));
      if (iv.t1 > iv.t0) source.push_back(exact(b));
      // The straight segment from the edge into free space stays in front of one face at a convex edge (free
      // space is the union of the two fronts: one flight per front) and of both at a concave or flat one.
      if (e.shape == EdgeShape::kConvex) {
        for (int f : e.faces) fly_back(source, {reached_impl_.charts[f].plane}, -1);
      } else if (e.shape == EdgeShape::kConcave || e.shape == EdgeShape::kFlat) {
        std::vector<Plane3> fronts;
        for (int f : e.faces) fronts.push_back(reached_impl_.charts[f].plane);
        fly_back(source, fronts, -1);
      } else {
        fly_back(source, {}, -1);  // a non-manifold edge keeps no front, as the forward flight from it
      }
    }
  }

  void process_vertex(int vi) {
    ++steps_;
    work_.take_vertex(vi);
    const Vertex& vx = cspace_.vertices()[vi];
    for (int e : vx.edges) {
      const Edge& edge = cspace_.edges()[e - face_count_];
      if (must_[e] || edge.shape == EdgeShape::kFlat) continue;
      const EdgeSliding es = edge_sliding(cspace_, e, v_, theta_v_);
      if (edge.vertex_a == vx.id ? es.toward_a : es.toward_b) work_.add_interval(e - face_count_, 0, 1);
    }
    for (int f : vx.faces) backslide(f, {reached_impl_.charts[f].project(vx.point)});
    fly_back({exact(vx.point)}, {}, -1);  // as the forward flight from a vertex: no front is kept
  }

  const CSpace& cspace_;
  const Vec3 v_;
  const double theta_v_;
  ReachedSet weak_;
  ReachedSet::Impl& reached_impl_;
  DamperWorklist work_;
  int face_count_ = 0, edge_count_ = 0, vertex_count_ = 0, steps_ = 0;
  std::vector<bool> must_;
  std::vector<Sweep> sweeps_;
  std::vector<bool> lifts_off_, lands_on_;
  FlightCone reverse_cone_;
  std::vector<std::vector<FlightSource::Wall>> walls_;  // per face: its concave neighbours (damper_flight.h)
};

// The atoms where the motion may stop (forward_project_damper's termination atoms), less the target.
ReachedSet termination_base(const LoadedTask& task, const AtomCones& cones, const ReachedSet& target,
                            const Vec3& v, double stop_relative_speed) {
  const CSpace& c = task.cspace;
  const double theta_v = task.task.uncertainty.theta_v;
  const double stop_angle = std::asin(std::min(1.0, std::max(0.0, stop_relative_speed)));
  ReachedSet stops(c);
  for (int id = 0; id < c.atom_count(); ++id)
    if (classify_damper(cones, id, v, theta_v, stop_angle) != StickClass::kNever) stops.add_whole_atom(id);
  return points_outside(stops, target);
}

Points2 grown_hull(const std::vector<Point2>& pts, double margin) {
  Points2 out;
  for (const Point2& p : pts)
    for (const double dx : {-margin, margin})
      for (const double dy : {-margin, margin}) out.push_back(Point2(p.x() + dx, p.y() + dy));
  return convex_hull(out);
}

}  // namespace

WeakBackprojection finish_weak_backprojection(ReachedSet weak, bool capped, int steps) {
  WeakBackprojection out{std::move(weak)};
  if (capped) {
    out.fallback = true;
    for (int id = 0; id < out.weak.cspace().atom_count(); ++id) out.weak.add_whole_atom(id);
  }
  out.steps = steps;
  return out;
}

WeakBackprojection weak_backproject_damper(const LoadedTask& task, const AtomCones& cones,
                                           const ReachedSet& from, const Vec3& v) {
  return BackProjector(task, cones, from, v).run();
}

DamperBackprojection backproject_damper(const LoadedTask& task, const AtomCones& cones,
                                        const ReachedSet& target, const Vec3& v, double stop_relative_speed,
                                        double margin) {
  DamperBackprojection out{termination_base(task, cones, target, v, stop_relative_speed),
                           ReachedSet(task.cspace), ReachedSet(task.cspace)};
  WeakBackprojection w = weak_backproject_damper(task, cones, out.base, v);
  out.fallback = w.fallback;
  out.steps = w.steps;
  out.weak = std::move(w.weak);
  out.strong =
      surface_complement(out.weak, std::max(margin, kBackprojectionRelativeMargin * task.cspace.scale()));
  return out;
}

ReachedSet points_outside(const ReachedSet& set, const ReachedSet& target) {
  ReachedSet stops = set;
  const ReachedSet::Impl& x = target.impl();
  ReachedSet::Impl& b = stops.impl();
  for (std::size_t fi = 0; fi < b.faces.size(); ++fi)
    if (!b.faces[fi].region.is_empty() && !x.faces[fi].region.is_empty())
      b.faces[fi].region.difference(x.faces[fi].region);
  for (std::size_t ei = 0; ei < b.edges.size(); ++ei) {
    std::vector<EdgeInterval> rest;
    for (const EdgeInterval& iv : b.edges[ei]) {
      double t = iv.t0;
      for (const EdgeInterval& hole : x.edges[ei]) {
        if (hole.t1 < t || hole.t0 > iv.t1) continue;
        if (hole.t0 > t) rest.push_back({t, hole.t0});
        t = std::max(t, hole.t1);
      }
      if (t < iv.t1) rest.push_back({t, iv.t1});
    }
    b.edges[ei] = rest;
  }
  for (std::size_t vi = 0; vi < b.vertices.size(); ++vi)
    if (x.vertices[vi]) b.vertices[vi] = 0;
  return stops;
}

ReachedSet surface_complement(const ReachedSet& set, double margin) {
  const CSpace& c = set.cspace();
  const ReachedSet::Impl& w = set.impl();
  ReachedSet out(c);
  ReachedSet::Impl& s = out.impl();
  const int nf = static_cast<int>(c.faces().size()), ne = static_cast<int>(c.edges().size());
  const std::vector<std::pair<double, double>> square = {
      {-margin, -margin}, {margin, -margin}, {margin, margin}, {-margin, margin}};
  for (int fi = 0; fi < nf; ++fi) {
    const FaceChart& chart = w.charts[fi];
    ChartRegion rest(to_polygon(w.face_polygon[fi]), chart.cell);
    if (!w.faces[fi].region.is_empty()) rest.difference(w.faces[fi].region.minkowski_sum(square));
    auto cut = [&](const std::vector<Point2>& pts) { rest.difference(to_polygon(grown_hull(pts, margin))); };
    for (const Segment2& seg : w.faces[fi].segments) cut({seg.source(), seg.target()});
    for (const Point2& p : w.faces[fi].points) cut({p});
    for (int e : c.faces()[fi].edges) {
      const Edge& edge = c.edges()[e - nf];
      for (const EdgeInterval& iv : w.edges[e - nf])
        cut({chart.project(Vec3(edge.a + iv.t0 * (edge.b - edge.a))),
             chart.project(Vec3(edge.a + iv.t1 * (edge.b - edge.a)))});
    }
    for (int vid : c.faces()[fi].vertices)
      if (w.vertices[vid - nf - ne]) cut({chart.project(c.vertices()[vid - nf - ne].point)});
    s.faces[fi].region = std::move(rest);
  }
  for (int ei = 0; ei < ne; ++ei) {
    const Edge& edge = c.edges()[ei];
    const double dt = margin / (edge.b - edge.a).norm();
    std::vector<EdgeInterval> cuts = w.edges[ei];
    if (edge.vertex_a >= 0 && w.vertices[edge.vertex_a - nf - ne]) cuts.push_back({0, 0});
    if (edge.vertex_b >= 0 && w.vertices[edge.vertex_b - nf - ne]) cuts.push_back({1, 1});
    std::sort(cuts.begin(), cuts.end(),
              [](const EdgeInterval& a, const EdgeInterval& b) { return a.t0 < b.t0; });
    double t = 0;
    for (const EdgeInterval& cut : cuts) {
      if (cut.t0 - dt > t) s.edges[ei].push_back({t, cut.t0 - dt});
      t = std::max(t, cut.t1 + dt);
    }
    if (t < 1) s.edges[ei].push_back({t, 1});
  }
  for (std::size_t vi = 0; vi < c.vertices().size(); ++vi)
    s.vertices[vi] = set.distance(c.vertices()[vi].point) > margin ? 1 : 0;
  return out;
}

}  // namespace cmt

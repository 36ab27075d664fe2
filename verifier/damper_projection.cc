// Generalized-damper forward projection (Buckley Alg 4.1 framework, Alg 4.3 sliding), design steps A-F of
// docs/forward-projection-design.md. A worklist fixpoint over the ReachedSet: every newly reached part of a
// face (exact regularized difference against what was there), of an edge (intervals) or a vertex is processed
// once: sliding (A), edges (B), vertices (C), flight (D); the loop ends when nothing grows (E); termination
// keeps the atoms that may stick (F).
#include "verifier/damper_projection.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "verifier/damper.h"
#include "verifier/internal/damper_flight.h"
#include "verifier/internal/face_sweep.h"
#include "verifier/internal/worklist.h"
#include "verifier/slide_forever.h"

namespace cmt {
namespace {

using namespace face_geometry;
// Contact-lift strips seeded over an edge's reached intervals before the strip along the whole edge is taken.
constexpr int kLiftStripRounds = 8;
// Landing coasts that grew one face before its whole polygon is taken (coast_after_landing); rim coast
// flights from one face over one edge before they start from the whole edge (coast_over_rims).
constexpr int kCoastRounds = 24;
// A rim coast's hit on the rim's own faces within this fraction of the scene scale of the rim's line is the
// rim itself (coast_over_rims): far above the flight sections' rounding pads (kFlightSectionRelativeError)
// and the region grid's outward rounding (a few cells of at most 2^-35 scale), far below any landing a
// flight of nonzero cone width makes from in front of the face.
constexpr double kRimLineRelativeTolerance = 1e-9;
// Relative slack on the servo coast's length (covers rounding of the sector's double corners).
constexpr double kCoastRelativeSlack = 1e-9;

class Projector {
 public:
  Projector(const LoadedTask& task, const AtomCones& cones, const ReachedSet& start, const Vec3& v,
            double stop_relative_speed, double contact_lift, double servo_coast)
      : cspace_(task.cspace),
        v_(v.normalized()),
        lift_(std::max(0.0, contact_lift)),
        coast_(std::max(0.0, servo_coast) * (1 + kCoastRelativeSlack)),
        kappa_(std::max(0.0, stop_relative_speed)),
        theta_v_(task.task.uncertainty.theta_v),
        reached_(start),
        reached_impl_(reached_.impl()),
        work_(reached_impl_) {  // everything in the start is pending
    face_count_ = static_cast<int>(cspace_.faces().size());
    edge_count_ = static_cast<int>(cspace_.edges().size());
    vertex_count_ = static_cast<int>(cspace_.vertices().size());
    // The commanded speed is the reference speed (only the direction has an error), so a slide slower than
    // kappa times it has its velocity within asin(kappa) of the friction cone.
    const double stop_angle = std::asin(std::min(1.0, std::max(0.0, stop_relative_speed)));
    for (int id = 0; id < cspace_.atom_count(); ++id) {
      cls_.push_back(classify_damper(cones, id, v_, theta_v_));
      // Only a "never" atom can change class under the wider test.
      stops_.push_back(
          cls_.back() != StickClass::kNever ||
          (stop_angle > 0 && classify_damper(cones, id, v_, theta_v_, stop_angle) != StickClass::kNever));
    }
    for (const Face& f : cspace_.faces()) sweeps_.push_back(face_sweep(f, v_, theta_v_, cspace_.scale()));
    cone_ = flight_cone(v_, theta_v_, cspace_.scale());
    for (const Vec3& ray : cone_.rays) cone_coast_.push_back(coast_ * ray.normalized());
    for (int fi = 0; fi < face_count_; ++fi) {
      whole_face_.emplace_back(to_polygon(reached_impl_.face_polygon[fi]), reached_impl_.charts[fi].cell);
      sweep_holds_cone_.push_back(cls_[fi] != StickClass::kMust && sweep_holds_cone(fi));
    }
  }

  DamperProjection run() {
    DamperProjection out{ReachedSet(cspace_), ReachedSet(cspace_)};
    const bool progress = work_.run(
        steps_, kMaxFixpointSteps, [&](int fi) { process_face(fi); }, [&](int ei) { process_edge(ei); },
        [&](int vi) { process_vertex(vi); });
    if (progress) {  // cap reached: every atom (sound, uninformative)
      out.fallback = true;
      for (int id = 0; id < cspace_.atom_count(); ++id) reached_.add_whole_atom(id);
    }
    out.termination = reached_.restricted(stops_);
    out.may_not_terminate = out.termination.empty();
    std::vector<bool> must(cls_.size());
    for (std::size_t id = 0; id < cls_.size(); ++id) must[id] = cls_[id] == StickClass::kMust;
    out.slide_forever = damper_slide_forever_atoms(cspace_, reached_, v_, theta_v_, kappa_, must);
    out.reached = std::move(reached_);
    out.steps = steps_;
    return out;
  }

 private:
  // ---- processing ----
  void process_face(int fi) {
    ++steps_;
    const std::vector<Points2> parts = work_.take_face(fi);
    const Face& face = cspace_.faces()[fi];
    const FaceChart& chart = reached_impl_.charts[fi];
    work_.add_closure(fi, parts);  // reached parts of the face's edges and corners (closed regions)
    if (cls_[fi] == StickClass::kMust) return;  // nothing slides or lifts off a must-stick face
    if (coast_ > 0) coast_over_rims(fi, parts);
    // A. Sliding (Buckley Alg 4.3): the swept wedge, clipped to the face.
    const Sweep& sw = sweeps_[fi];
    if (sw.whole) {
      work_.add_region(fi, ChartRegion(to_polygon(reached_impl_.face_polygon[fi]), chart.cell));
    } else if (!sw.none) {
      const Vector2 bp = chart.project_direction(sw.far * sw.b_plus);
      const Vector2 bm = chart.project_direction(sw.far * sw.b_minus);
      for (const Points2& part : parts) {
        Points2 pts = part;
        for (const Point2& p : part) {
          pts.push_back(p + bp);
          pts.push_back(p + bm);
        }
        work_.add_convex(fi, clip(convex_hull(pts), reached_impl_.face_polygon[fi]));
      }
    }
    // D. Flight, when some admissible velocity leaves the face (angle(v, n) < pi/2 + theta_v); only points in
    // front of the face's plane are reachable from its interior.
    if (v_.dot(face.normal) <= -std::sin(theta_v_ + kFlightAngleSlack)) return;
    for (const Points2& part : parts) {
      FlightSource src;
      for (const Point2& p : part) src.vertices.push_back(chart.lift(p));
      src.keep_front.push_back(chart.plane);
      src.face = fi;
      absorb(fly(reached_impl_, src, cone_));
    }
  }

  void process_edge(int ei) {
    ++steps_;
    const std::vector<EdgeInterval> ivs = work_.take_edge(ei);
    const Edge& e = cspace_.edges()[ei];
    const int id = face_count_ + ei;
    work_.add_interval_ends(ei, ivs);
    // The lift bands first: the robot may reach them on its way to the edge, whatever the edge's class.
    if (lift_ > 0 && e.shape == EdgeShape::kConcave) add_lift_bands(ei, ivs);
    if (cls_[id] == StickClass::kMust) return;
    // B. Sliding along the edge toward an end reaches the end. A flat edge (a cut between coplanar faces) is
    // no crease: motion along it is motion on the plane, covered by both faces' sliding wedges (the segment
    // seeds both faces below), so edge_sliding's coarser "any component along the edge" is not applied.
    const EdgeSliding es =
        e.shape == EdgeShape::kFlat ? EdgeSliding{} : edge_sliding(cspace_, id, v_, theta_v_);
    for (const EdgeInterval& iv : ivs) {
      if (es.toward_b) work_.add_interval(ei, iv.t0, 1);
      if (es.toward_a) work_.add_interval(ei, 0, iv.t1);
    }
    std::vector<Plane3> keep;
    if (e.shape == EdgeShape::kConcave || e.shape == EdgeShape::kFlat)
      for (int f : e.faces) keep.push_back(reached_impl_.charts[f].plane);
    for (const EdgeInterval& iv : ivs) {
      const Vec3 a = e.a + iv.t0 * (e.b - e.a), b = e.a + iv.t1 * (e.b - e.a);
      // Onto either adjacent face (over-approximation: the whole segment seeds both).
      for (int f : e.faces)
        work_.add_segment(f, reached_impl_.charts[f].project(a), reached_impl_.charts[f].project(b));
      FlightSource src;
      src.vertices = {exact(a)};
      if (iv.t1 > iv.t0) src.vertices.push_back(exact(b));
      if (e.shape == EdgeShape::kConvex && e.faces.size() == 2) {
        // At a convex edge the obstacle is the wedge behind both faces, so free space is the union of the two
        // fronts: a segment from the edge that ends behind both planes entered the obstacle. One flight per
        // front gives exactly that union.
        for (int f : e.faces) {
          src.keep_front = {reached_impl_.charts[f].plane};
          absorb(fly(reached_impl_, src, cone_), e.faces);
        }
        continue;
      }
      src.keep_front = keep;
      absorb(fly(reached_impl_, src, cone_), e.faces);
    }
  }

  // Contact lift at a concave edge: a robot sliding on one face toward the edge may be up to lift_ off it.
  // While it is off the face its velocity is still within theta_v of the command, so its projection onto the
  // face moves within the face's sweep wedge (which holds the tangential flights): it stays over the reached
  // region and meets the other face above the reached segment [a, b] of the edge. That face gets the strip
  // [a, b] + [0, lift] d (d in the face, away from the edge), clipped to the face, when the first face is
  // reached and may slide toward the edge (the lift comes from slipping). When both faces slide into the
  // edge, each strip's sweep reaches the edge lift tan(alpha) further along it, and the strips creep along
  // the edge; after kLiftStripRounds strips on an edge, the strip along the whole edge is taken at once.
  void add_lift_bands(int ei, const std::vector<EdgeInterval>& ivs) {
    const Edge& e = cspace_.edges()[ei];
    const bool whole = ++lift_strips_[ei] > kLiftStripRounds;
    for (int f : e.faces) {
      bool fed = false;
      for (int g : e.faces)
        if (g != f) fed = fed || slides_toward(g, e);
      if (!fed) continue;
      const Face& face = cspace_.faces()[f];
      const Vec3 d = -outward_across(face, e);
      const FaceChart& chart = reached_impl_.charts[f];
      auto strip = [&](const Vec3& a, const Vec3& b) {
        const Points2 rect =
            convex_hull({chart.project(a), chart.project(b), chart.project(Vec3(b + lift_ * d)),
                         chart.project(Vec3(a + lift_ * d))});
        work_.add_convex(f, clip(rect, reached_impl_.face_polygon[f]));
      };
      if (whole) {
        strip(e.a, e.b);
        continue;
      }
      for (const EdgeInterval& iv : ivs) strip(e.a + iv.t0 * (e.b - e.a), e.a + iv.t1 * (e.b - e.a));
    }
  }

  static Vec3 face_centroid(const Face& face) {
    Vec3 centroid = Vec3::Zero();
    for (const Vec3& q : face.polygon) centroid += q / static_cast<double>(face.polygon.size());
    return centroid;
  }

  // The unit direction in `face` perpendicular to `edge`, pointing out of the face across the edge.
  static Vec3 outward_across(const Face& face, const Edge& edge) {
    Vec3 out = face.normal.cross(edge.b - edge.a).normalized();
    return out.dot(face_centroid(face) - edge.a) > 0 ? Vec3(-out) : out;
  }

  // Face g is reached and some sliding direction on it (its sweep wedge, tangential flights included) points
  // toward edge e.
  bool slides_toward(int g, const Edge& e) const {
    const Sweep& sw = sweeps_[g];
    if (cls_[g] == StickClass::kMust || sw.none || reached_impl_.faces[g].empty()) return false;
    if (sw.whole) return true;
    const Face& face = cspace_.faces()[g];
    const Vec3 m = outward_across(face, e);
    return sw.b_plus.dot(m) > 0 || sw.b_minus.dot(m) > 0;
  }

  void process_vertex(int vi) {
    ++steps_;
    work_.take_vertex(vi);
    const Vertex& vx = cspace_.vertices()[vi];
    if (cls_[face_count_ + edge_count_ + vi] == StickClass::kMust) return;
    // C. Onto adjacent edges and faces, and flight.
    for (int e : vx.edges) {
      const Edge& edge = cspace_.edges()[e - face_count_];
      const double t = edge.vertex_a == vx.id ? 0.0 : 1.0;
      work_.add_interval(e - face_count_, t, t);
    }
    for (int f : vx.faces) work_.add_point(f, reached_impl_.charts[f].project(vx.point));
    FlightSource src;
    src.vertices = {exact(vx.point)};
    absorb(fly(reached_impl_, src, cone_), vx.faces);
  }

  // `no_coast`: the faces of the source edge or vertex, whose landings are not coasted; `departure`: the
  // servo-coast displacements of the velocity the robot left a face with (a rim's coast sector), empty for
  // flights that start from rest or at a first-order velocity (see coast_after_landing).
  void absorb(const std::vector<FlightHit>& hits, const std::vector<int>& no_coast = {},
              const std::vector<Vec3>& departure = {}) {
    for (const FlightHit& h : hits) {
      if (!h.region.is_empty())
        work_.add_region(h.face, h.region);
      else
        work_.add_convex(h.face, h.lower);
      const bool adjacent = std::find(no_coast.begin(), no_coast.end(), h.face) != no_coast.end();
      const bool swept = sweeps_[h.face].whole || (departure.empty() && sweep_holds_cone_[h.face]);
      if (coast_ > 0 && !adjacent && !swept) coast_after_landing(h, departure);
    }
  }

  // Servo coast at an impact (docs/verifier.md "Servo coast"): the contact stops the normal velocity, but the
  // tangential one decays with the servo's time constant tau, so the robot may move on by tau u_t along the
  // face, u the velocity it lands with. In flight the velocity relaxes from the departure velocity toward
  // the commanded cone, so u lies in the hull of the departure velocities and the cone's velocities (speed
  // <= V): the landing region grows by tau times the projection of that hull onto the face (in the chart,
  // which only shortens in-plane vectors), clipped to the face. Not coasted: a flight from an edge or vertex
  // back onto one of its own faces (a robot leaving the edge for its face; coasting it would feed the edge a
  // longer interval each round, and the fixpoint would creep along the edge). After kCoastRounds growing
  // coasts on one face (coasts against the command can chain into cycles of landings), the whole face.
  void coast_after_landing(const FlightHit& h, const std::vector<Vec3>& departure) {
    const FaceChart& chart = reached_impl_.charts[h.face];
    if (coast_rounds_[h.face] > kCoastRounds) {
      work_.add_region(h.face, whole_face_[h.face]);
      return;
    }
    std::vector<Vec3> pattern = cone_coast_;
    pattern.insert(pattern.end(), departure.begin(), departure.end());
    bool grew = false;
    if (!h.region.is_empty()) {
      std::vector<std::pair<double, double>> chart_pattern;
      for (const Vec3& d : pattern) {
        const Vector2 q = chart.project_direction(d);
        chart_pattern.emplace_back(CGAL::to_double(q.x()), CGAL::to_double(q.y()));
      }
      ChartRegion grown = h.region.minkowski_sum(chart_pattern);
      grown.intersection(whole_face_[h.face]);
      grew = work_.add_region(h.face, grown);
    } else {
      Points2 pts;
      for (const Point2& p : h.lower) {
        pts.push_back(p);
        for (const Vec3& d : pattern) pts.push_back(p + chart.project_direction(d));
      }
      grew = work_.add_convex(h.face, clip(convex_hull(pts), reached_impl_.face_polygon[h.face]));
    }
    if (grew) ++coast_rounds_[h.face];
  }

  // Servo coast on leaving a face over a convex rim (docs/verifier.md "Servo coast"): free of contact, the
  // velocity relaxes from the sliding velocity u (in the face's sweep wedge, |u| <= V) toward the commanded
  // cone with time constant tau, so the position is p + a u + (a cone displacement), a in [0, tau]: the
  // first-order flight from the prism rim segment + tau (wedge ∩ disk of radius V), lifted up to the contact
  // lift (a hop may carry the robot over the rim that high). Free space at a convex edge is the union of the
  // two faces' fronts, so one flight per front, as from the edge itself (process_edge). A rim interval is
  // flown from once; when the coast's landings feed the rim a longer interval round after round (a robot
  // that coasts along the rim, lands on the other face and reaches the edge again), the flights after
  // kCoastRounds start from the whole edge.
  void coast_over_rims(int fi, const std::vector<Points2>& parts) {
    const Face& face = cspace_.faces()[fi];
    const FaceChart& chart = reached_impl_.charts[fi];
    for (int e : face.edges) {
      const Edge& edge = cspace_.edges()[e - face_count_];
      if (edge.shape != EdgeShape::kConvex || edge.faces.size() != 2 || !slides_toward(fi, edge)) continue;
      // One prism over the hull of the parts' rim intervals.
      double s0 = 1, s1 = 0;
      for (const Points2& part : parts) {
        FT t0, t1;
        if (!clip_segment(part, chart.project(edge.a), chart.project(edge.b), &t0, &t1)) continue;
        s0 = std::min(s0, std::max(0.0, CGAL::to_interval(t0).first - kEdgeParamSlack));
        s1 = std::max(s1, std::min(1.0, CGAL::to_interval(t1).second + kEdgeParamSlack));
      }
      if (s0 > s1) continue;
      RimCoast& done = rim_coasts_[{fi, e}];
      // Flown from already (growth within the parameter slack is rounding).
      const double slack = 4 * kEdgeParamSlack;
      if (std::any_of(done.flown.begin(), done.flown.end(), [&](const std::pair<double, double>& iv) {
            return iv.first <= s0 + slack && s1 <= iv.second + slack;
          }))
        continue;
      if (++done.rounds > kCoastRounds) s0 = 0, s1 = 1;
      done.flown.emplace_back(s0, s1);
      const Vec3 a = edge.a + s0 * (edge.b - edge.a), b = edge.a + s1 * (edge.b - edge.a);
      FlightSource src;
      src.face = fi;
      const std::vector<Vec3> sector = coast_sector(fi, edge);
      for (const Vec3& s : sector)
        for (const Vec3& q : {a, b}) {
          src.vertices.push_back(exact(Vec3(q + s)));
          if (lift_ > 0) src.vertices.push_back(exact(Vec3(q + s + lift_ * face.normal)));
        }
      for (int g : edge.faces) {
        src.keep_front = {reached_impl_.charts[g].plane};
        // A segment or point on the rim's own faces is the rim itself (the prism's points at the rim), not a
        // landing: coasting it would feed the rim a longer interval each round and creep along the edge. So
        // is a sliver along the rim's line (the segment rounded outward to the region grid: every vertex
        // within kRimLineRelativeTolerance of the line). A landing with area beyond it (the command turning
        // the robot back onto a face) is coasted.
        std::vector<FlightHit> rim, landings;
        for (FlightHit& h : fly(reached_impl_, src, cone_)) {
          const bool own = std::find(edge.faces.begin(), edge.faces.end(), h.face) != edge.faces.end();
          (own && on_edge_line(h, edge) ? rim : landings).push_back(std::move(h));
        }
        absorb(rim, edge.faces, sector);
        absorb(landings, {}, sector);
      }
    }
  }

  // Every point of the hit (its lower-dimensional points, and every vertex of its region's outer boundaries
  // and holes) lies on the edge's line, within kRimLineRelativeTolerance of the scene scale.
  bool on_edge_line(const FlightHit& h, const Edge& edge) const {
    const Vec3 d = (edge.b - edge.a).normalized();
    const auto near = [&](const Point2& p) {
      const Vec3 q = reached_impl_.charts[h.face].lift_double(p) - edge.a;
      return (q - q.dot(d) * d).norm() <= kRimLineRelativeTolerance * cspace_.scale();
    };
    if (!std::all_of(h.lower.begin(), h.lower.end(), near)) return false;
    for (const PolygonWithHoles2& p : h.region.polygons_with_holes()) {
      if (!std::all_of(p.outer_boundary().vertices_begin(), p.outer_boundary().vertices_end(), near))
        return false;
      for (auto hole = p.holes_begin(); hole != p.holes_end(); ++hole)
        if (!std::all_of(hole->vertices_begin(), hole->vertices_end(), near)) return false;
    }
    return true;
  }

  // The sweep wedge of face fi holds the tangential part of every cone velocity (so a face that is swept, not
  // must-stick, covers the landing coast of a flight that left from rest: its sweep moves every reached point
  // at least as far along each of those directions, clipped to the face alike).
  bool sweep_holds_cone(int fi) const {
    const Sweep& sw = sweeps_[fi];
    if (sw.whole) return true;
    if (sw.none) return false;
    const Vec3& n = cspace_.faces()[fi].normal;
    const Vec3 axis = (sw.b_plus + sw.b_minus).normalized();
    const double cos_alpha = sw.b_plus.dot(axis);
    for (const Vec3& ray : cone_.rays) {
      const Vec3 t = ray - ray.dot(n) * n;
      const double len = t.norm();
      if (len <= 1e-12 * ray.norm()) continue;  // normal to the face: no tangential part
      if (t.dot(axis) < (cos_alpha + 1e-9) * len) return false;
    }
    return true;
  }

  // The displacements tau u of the sliding velocities u on face fi that may carry it out over `edge`: the
  // sweep wedge (or the whole plane) within radius coast_. Returned as three points (each becomes a vertex of
  // the flight source, and a section costs the square of the source's generators). A wedge of half-angle
  // alpha < pi/2: the triangle 0, R b_minus, R b_plus with R = r / cos alpha holds its sector of radius r
  // (the chord of R b_minus, R b_plus lies at r along the axis, the sector's farthest reach). A whole sweep,
  // or a wedge wider than 2 pi / 3 (R > 2r): only velocities in the outward half-disk leave over the edge,
  // and it lies in the triangle -2r t, 2r t, 2r out (|x| + y <= 2r on it).
  std::vector<Vec3> coast_sector(int fi, const Edge& edge) const {
    const Face& face = cspace_.faces()[fi];
    const Sweep& sw = sweeps_[fi];
    const double r = coast_;
    const Vec3 axis = sw.whole ? Vec3::Zero() : Vec3((sw.b_plus + sw.b_minus).normalized());
    const double cos_alpha = sw.whole ? 0.0 : sw.b_plus.dot(axis);
    if (cos_alpha < 0.5) {
      const Vec3 t = (edge.b - edge.a).normalized();
      const Vec3 out = outward_across(face, edge);
      return {-2 * r * t, 2 * r * t, 2 * r * out};
    }
    return {Vec3::Zero(), (r / cos_alpha) * sw.b_minus, (r / cos_alpha) * sw.b_plus};
  }

  const CSpace& cspace_;
  Vec3 v_;
  double lift_;   // contact lift (task units)
  double coast_;  // servo coast tau V (task units), with kCoastRelativeSlack
  double kappa_;  // the stop rule's relative speed
  double theta_v_;
  ReachedSet reached_;
  ReachedSet::Impl& reached_impl_;
  DamperWorklist work_;
  int face_count_ = 0, edge_count_ = 0, vertex_count_ = 0;
  std::vector<StickClass> cls_;
  std::vector<bool> stops_;  // the atom may stop the motion: it may stick or slide slower than the stop rule
  std::vector<Sweep> sweeps_;
  std::map<int, int> lift_strips_;   // per edge: how often its lift strips were seeded
  std::map<int, int> coast_rounds_;  // per face: how many landing coasts grew it
  // Per (face, convex edge): the rim intervals the coast flights started from, and how often they were flown.
  struct RimCoast {
    std::vector<std::pair<double, double>> flown;  // edge parameter intervals
    int rounds = 0;
  };
  std::map<std::pair<int, int>, RimCoast> rim_coasts_;
  FlightCone cone_;
  std::vector<Vec3> cone_coast_;  // coast_ along each cone ray: the coast of a landing at a cone velocity
  std::vector<ChartRegion> whole_face_;  // per face: its polygon as a region
  std::vector<bool> sweep_holds_cone_;   // per face: swept, and the sweep covers a landing's coast
  int steps_ = 0;
};

}  // namespace

DamperProjection forward_project_damper(const LoadedTask& task, const AtomCones& cones,
                                        const ReachedSet& start, const Vec3& v, double stop_relative_speed,
                                        double contact_lift, double servo_coast) {
  return Projector(task, cones, start, v, stop_relative_speed, contact_lift, servo_coast).run();
}

}  // namespace cmt

// Free-space flight of the generalized damper (Buckley Alg 4.1 step 1; §4.3.2-4.3.4 compute the same sets by
// convex visibility, App. A). Design step D: reach(g) = g ∩ (conv(X) + cone(C)) minus, for every single
// occluding face h, g ∩ umbra_h(X) with umbra_h(X) = ∩_{x ∈ vertices(X)} Shadow_x(h).
//
// Section. With the cone truncated at length `far` (rays have v-component 1, so any displacement d of length
// <= scene scale is a combination of rays with coefficients summing to <= scale), Q = conv(X) ⊕ S with
// S = conv({0} ∪ far R) equals conv(X) + cone(C) inside the scene. The section of a polytope by a plane is
// the hull of the crossings of its edges, and every edge of a Minkowski sum is a vertex of one summand plus
// an edge of the other: (x_i, x_j) + s_k for every source pair and S vertex, x_i + (0, far r_k) and x_i +
// (far r_k, far r_k+1). Those crossings are computed in doubles with interval bounds on the signs
// (section_in_doubles); a section thinner than a thousand of its rounding pads is recomputed exactly (Epeck)
// from the edges that can cross, so a segment or point stays one (section_exact).
#include "verifier/internal/damper_flight.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "verifier/internal/frame.h"

namespace cmt::face_geometry {
namespace {

struct Box {
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  void add(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  bool meets(const Box& o, double pad) const {
    for (int k = 0; k < 3; ++k)
      if (lo[k] > o.hi[k] + pad || o.lo[k] > hi[k] + pad) return false;
    return true;
  }
};

FT value(const Plane3& p, const Point3& x) { return p.a() * x.x() + p.b() * x.y() + p.c() * x.z() + p.d(); }

// a u + b v + c >= 0 tightened by `margin` chart lengths (sqrt(a^2 + b^2) <= |a| + |b|, rounded up).
HalfPlane2 shrunk(const HalfPlane2& h, double margin) {
  const double norm = std::abs(CGAL::to_double(h.a)) + std::abs(CGAL::to_double(h.b));
  return {h.a, h.b, h.c - FT(margin * norm * (1 + 1e-6))};
}

bool same_plane(const Plane3& a, const Plane3& b) { return a == b || a == b.opposite(); }

using Inexact = CGAL::Exact_predicates_inexact_constructions_kernel;

// Plane a x + b y + c z + d in doubles, with a bound on the error of its value at a point computed in
// doubles.
struct PlaneDouble {
  double a, b, c, d;
  explicit PlaneDouble(const Plane3& p)
      : a(CGAL::to_double(p.a())),
        b(CGAL::to_double(p.b())),
        c(CGAL::to_double(p.c())),
        d(CGAL::to_double(p.d())) {}
  double value(const Vec3& x) const { return a * x.x() + b * x.y() + c * x.z() + d; }
  double error(const Vec3& x) const {
    return kFlightSectionRelativeError *
           (std::abs(a * x.x()) + std::abs(b * x.y()) + std::abs(c * x.z()) + std::abs(d));
  }
};

// Parameters t in [0, 1] at which (1 - t) D_p + t D_q can vanish for some D_p in [lo_p, hi_p], D_q in
// [lo_q, hi_q]: {t : (1 - t) lo_p + t lo_q <= 0 <= (1 - t) hi_p + t hi_q}. False when there are none.
bool crossing_interval(double lo_p, double hi_p, double lo_q, double hi_q, double* t0, double* t1) {
  double lo = 0, hi = 1;
  // f(t) = lo_p + t (lo_q - lo_p) <= 0 and g(t) = hi_p + t (hi_q - hi_p) >= 0, each a half-line in t.
  auto keep = [&](double at0, double slope, bool want_nonpositive) {
    const double sign = want_nonpositive ? 1 : -1;  // keep sign * (at0 + slope t) <= 0
    const double a0 = sign * at0, s = sign * slope;
    if (s == 0) {
      if (a0 > 0) hi = -1;
      return;
    }
    const double root = -a0 / s;
    if (s > 0)
      hi = std::min(hi, root);
    else
      lo = std::max(lo, root);
  };
  keep(lo_p, lo_q - lo_p, true);
  keep(hi_p, hi_q - hi_p, false);
  if (lo > hi) return false;
  *t0 = lo;
  *t1 = hi;
  return true;
}

}  // namespace

// The section of Q = conv(x_i) ⊕ conv(s_k) (s_0 = 0, s_k = far r_k on a ring) by `plane`, in the chart, from
// the crossings of Q's Minkowski edges. Each generator's plane value carries an error bound; for every edge
// the parameters where the true value can vanish form an interval [t0, t1], and both ends enter the hull (the
// true crossing projects between them: the chart projection is linear). The hull is grown by
// kFlightSectionRelativeError x the largest coordinate against rounding of the points. Returns false when no
// edge can cross; sets *thin when the hull is degenerate or narrower than kFlightThinSection of that size, or
// when that growth exceeds half a region cell: the caller then takes the exact section.
bool section_in_doubles(const std::vector<Vec3>& x, const std::vector<Vec3>& s, const FaceChart& chart,
                        Points2* out, bool* thin, std::vector<GeneratorEdge>* crossing) {
  const PlaneDouble plane(chart.plane);
  const std::size_t nx = x.size(), ns = s.size();
  std::vector<Vec3> gen(nx * ns);
  std::vector<double> lo(gen.size()), hi(gen.size());
  double big = 0;
  for (std::size_t i = 0; i < nx; ++i)
    for (std::size_t k = 0; k < ns; ++k) {
      const std::size_t at = i * ns + k;
      gen[at] = x[i] + s[k];
      const double v = plane.value(gen[at]), e = plane.error(gen[at]) + plane.error(x[i]) + plane.error(s[k]);
      lo[at] = v - e;
      hi[at] = v + e;
      big = std::max(big, gen[at].cwiseAbs().maxCoeff());
    }
  std::vector<Inexact::Point_2> pts;
  auto certain_sign = [&](std::size_t g) { return lo[g] > 0 ? 1 : (hi[g] < 0 ? -1 : 0); };
  auto can_cross = [&](std::size_t p, std::size_t q, double* t0, double* t1) {
    if ((lo[p] > 0 && lo[q] > 0) || (hi[p] < 0 && hi[q] < 0)) return false;
    return crossing_interval(lo[p], hi[p], lo[q], hi[q], t0, t1);
  };
  auto edge = [&](std::size_t p, std::size_t q) {
    double t0, t1;
    if (!can_cross(p, q, &t0, &t1)) return;
    if (crossing) crossing->push_back({p, q, certain_sign(p), certain_sign(q)});
    for (const double t : {t0, t1}) {
      const Vec3 y = gen[p] + t * (gen[q] - gen[p]);
      pts.emplace_back(y[chart.u], y[chart.v]);
    }
  };
  for (std::size_t k = 0; k < ns; ++k)
    for (std::size_t i = 0; i < nx; ++i)
      for (std::size_t j = i + 1; j < nx; ++j) edge(i * ns + k, j * ns + k);
  for (std::size_t i = 0; i < nx; ++i)
    for (std::size_t k = 1; k < ns; ++k) {
      edge(i * ns, i * ns + k);
      edge(i * ns + k, i * ns + (k + 1 < ns ? k + 1 : 1));
    }
  if (pts.empty()) return false;
  // The ring's corners are rounded, so in exact arithmetic they are not quite coplanar and their hull has
  // edges between non-adjacent corners too. The slab of the error bounds covers them in doubles (each corner
  // lies within 2^-52 of its size of the planar ring, far inside the bounds); the exact section also needs
  // them as edges.
  auto add_ring_chords = [&] {
    if (!crossing) return;
    double t0, t1;
    for (std::size_t i = 0; i < nx; ++i)
      for (std::size_t k = 1; k < ns; ++k)
        for (std::size_t l = k + 2; l < ns; ++l)
          if ((k != 1 || l + 1 != ns) && can_cross(i * ns + k, i * ns + l, &t0, &t1))
            crossing->push_back({i * ns + k, i * ns + l, certain_sign(i * ns + k), certain_sign(i * ns + l)});
  };
  const double pad = kFlightSectionRelativeError * (1 + big);
  if (pad > 0.5 * chart.cell) {
    *thin = true;
    add_ring_chords();
    return true;
  }
  std::vector<Inexact::Point_2> hull, grown;
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
  double area2 = 0, diameter2 = 0;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& p = hull[i];
    const auto& q = hull[(i + 1) % hull.size()];
    area2 += p.x() * q.y() - q.x() * p.y();
    for (const auto& r : hull) diameter2 = std::max(diameter2, CGAL::squared_distance(p, r));
  }
  *thin = hull.size() < 3 || area2 <= kFlightThinSection * pad * std::sqrt(diameter2);
  if (*thin) {
    add_ring_chords();
    return true;
  }
  for (const auto& h : hull)
    for (const double dx : {-pad, pad})
      for (const double dy : {-pad, pad}) grown.emplace_back(h.x() + dx, h.y() + dy);
  hull.clear();
  CGAL::convex_hull_2(grown.begin(), grown.end(), std::back_inserter(hull));
  out->clear();
  for (const auto& h : hull) out->emplace_back(h.x(), h.y());
  return true;
}

Points2 section_exact(const std::vector<Point3>& x, const std::vector<Vec3>& s,
                      const std::vector<GeneratorEdge>& edges, const FaceChart& chart) {
  const std::size_t ns = s.size();
  std::vector<std::optional<Point3>> gen(x.size() * ns);
  std::vector<std::optional<FT>> v(gen.size());
  auto point = [&](std::size_t g) -> const Point3& {
    if (!gen[g]) {
      const Vec3& d = s[g % ns];
      gen[g] = g % ns == 0 ? x[g / ns] : x[g / ns] + Vector3(d.x(), d.y(), d.z());
    }
    return *gen[g];
  };
  auto val = [&](std::size_t g) -> const FT& {
    if (!v[g]) v[g] = value(chart.plane, point(g));
    return *v[g];
  };
  // Exact values only where the error bounds leave the sign open, or for a crossing's position.
  auto sign = [&](std::size_t g, int certain) {
    return certain != 0 ? certain : static_cast<int>(CGAL::sign(val(g)));
  };
  Points2 pts;
  for (const GeneratorEdge& e : edges) {
    const int sp = sign(e.p, e.sign_p), sq = sign(e.q, e.sign_q);
    if (sp == 0) pts.push_back(chart.project(point(e.p)));
    if (sq == 0) pts.push_back(chart.project(point(e.q)));
    if (sp * sq < 0) {
      const Point2 a = chart.project(point(e.p));
      pts.push_back(a + (chart.project(point(e.q)) - a) * (val(e.p) / (val(e.p) - val(e.q))));
    }
  }
  return pts.empty() ? pts : convex_hull(pts);
}

FlightCone flight_cone(const Vec3& v_in, double theta_v, double scale) {
  FlightCone cone;
  const Vec3 v = v_in.normalized();
  Vec3 e1, e2;
  plane_frame(v, &e1, &e2);  // turns with the task: the fan of rays is the turned task's
  const double radius = std::tan(theta_v + kFlightAngleSlack) / std::cos(std::numbers::pi / kFlightConeRays);
  for (int k = 0; k < kFlightConeRays; ++k) {
    const double a = 2 * std::numbers::pi * k / kFlightConeRays;
    cone.rays.push_back(v + radius * (std::cos(a) * e1 + std::sin(a) * e2));
  }
  cone.far = 2 * scale;  // relative to the scene: the same cone in every unit
  return cone;
}

namespace {
// x lies strictly inside the concave edge between the source face and wall face h.
bool on_wall_edge(const FlightSource& source, int h, const Point3& x) {
  for (const FlightSource::Wall& w : source.walls) {
    if (w.face != h || !CGAL::collinear(w.a, w.b, x)) continue;
    if ((x - w.a) * (w.b - w.a) > 0 && (x - w.b) * (w.a - w.b) > 0) return true;
  }
  return false;
}
}  // namespace

std::vector<FlightHit> fly(const ReachedSet::Impl& g, const FlightSource& source, const FlightCone& cone) {
  const CSpace& c = *g.cspace;
  const double margin = kUmbraRelativeMargin * c.scale();
  std::vector<Vec3> src_vec, ring{Vec3::Zero()};
  for (const Vec3& r : cone.rays) ring.push_back(cone.far * r);
  Box src_box, gen_box;
  for (const Point3& x : source.vertices) {
    src_vec.push_back(to_vec(x));
    src_box.add(to_vec(x));
    gen_box.add(to_vec(x));
    for (const Vec3& d : ring) gen_box.add(to_vec(x) + d);
  }
  const double pad = 1e-9 * c.scale();
  std::vector<Box> face_box(c.faces().size());
  for (std::size_t i = 0; i < c.faces().size(); ++i)
    for (const Vec3& p : c.faces()[i].polygon) face_box[i].add(p);

  std::vector<FlightHit> hits;
  for (std::size_t gi = 0; gi < c.faces().size(); ++gi) {
    if (static_cast<int>(gi) == source.face || !face_box[gi].meets(gen_box, pad)) continue;
    const FaceChart& chart = g.charts[gi];
    bool front = false, all_on = true;
    for (const Point3& x : source.vertices) {
      const auto side = chart.plane.oriented_side(x);
      front = front || side == CGAL::ON_POSITIVE_SIDE;
      all_on = all_on && side == CGAL::ON_ORIENTED_BOUNDARY;
    }
    if (!front && !all_on) continue;  // behind g: reaching g would cross the obstacle behind it
    Points2 section;
    bool thin = false;
    std::vector<GeneratorEdge> crossing;
    if (!section_in_doubles(src_vec, ring, chart, &section, &thin, &crossing)) continue;
    if (thin) section = section_exact(source.vertices, ring, crossing, chart);
    if (section.empty()) continue;
    section = clip(section, g.face_polygon[gi]);
    for (const Plane3& keep : source.keep_front) section = clip(section, restrict_to_chart(keep, chart));
    if (section.empty()) continue;
    FlightHit hit;
    hit.face = static_cast<int>(gi);
    if (section.size() < 3) {
      hit.lower = section;
      hits.push_back(std::move(hit));
      continue;
    }
    hit.region = ChartRegion(to_polygon(section), chart.cell);
    // Occluders: faces meeting the hull of the source and g (where every segment from X to g lies).
    Box corridor = src_box;
    for (const Vec3& p : c.faces()[gi].polygon) corridor.add(p);
    for (std::size_t hi = 0; hi < c.faces().size(); ++hi) {
      if (hi == gi || !face_box[hi].meets(corridor, pad)) continue;
      const FaceChart& hc = g.charts[hi];
      if (same_plane(hc.plane, chart.plane)) continue;
      // Shadow_x(h) is empty for x in h's plane, except on a wall's concave edge (FlightSource::walls), where
      // it is all of h's back; skip h otherwise (sound).
      std::vector<const Point3*> front;
      bool occludes = true;
      for (const Point3& x : source.vertices) {
        if (hc.plane.has_on_positive_side(x))
          front.push_back(&x);
        else
          occludes = occludes && on_wall_edge(source, static_cast<int>(hi), x);
      }
      if (!occludes) continue;
      const auto& poly = c.faces()[hi].polygon;
      std::vector<Point3> corners;
      for (const Vec3& p : poly) corners.push_back(exact(p));
      const Point3 inside = CGAL::centroid(corners[0], corners[1], corners[2]);
      Points2 umbra = section;
      umbra = clip(umbra, shrunk(restrict_to_chart(hc.plane.opposite(), chart), margin));  // beyond h
      for (const Point3* xp : front) {
        const Point3& x = *xp;
        for (std::size_t k = 0; k < corners.size() && umbra.size() >= 3; ++k) {
          Plane3 side(x, corners[k], corners[(k + 1) % corners.size()]);
          if (side.oriented_side(inside) == CGAL::ON_NEGATIVE_SIDE) side = side.opposite();
          umbra = clip(umbra, shrunk(restrict_to_chart(side, chart), margin));
        }
        if (umbra.size() < 3) break;
      }
      if (umbra.size() >= 3) hit.region.difference(to_polygon(umbra));
    }
    if (!hit.region.is_empty()) hits.push_back(std::move(hit));
  }
  return hits;
}

}  // namespace cmt::face_geometry

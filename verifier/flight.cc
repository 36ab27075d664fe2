// Free-space flight of the generalized damper (Buckley Alg 4.1 step 1; §4.3.2-4.3.4 compute the same sets by
// convex visibility, App. A). Design step D: reach(g) = g ∩ (conv(X) + cone(C)) minus, for every single
// occluding face h, g ∩ umbra_h(X) with umbra_h(X) = ∩_{x ∈ vertices(X)} Shadow_x(h).
//
// Section. With the cone truncated at length `far` (rays have v-component 1, so any displacement d of length
// <= scene scale is a combination of rays with coefficients summing to <= scale), Q = conv(X ∪ {x + far r})
// equals conv(X) + cone(C) inside the scene. The section of a polytope by a plane is the hull of its
// generators on the plane and of the crossings of every generator pair on opposite sides: all exact (Epeck).
#include "verifier/internal/flight.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cmt::fp {
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

}  // namespace

FlightCone flight_cone(const Vec3& v_in, double theta_v, double scale) {
  FlightCone cone;
  const Vec3 v = v_in.normalized();
  const Vec3 e1 = (std::abs(v.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY()).cross(v).normalized();
  const Vec3 e2 = v.cross(e1);
  const double radius = std::tan(theta_v + kFlightAngleSlack) / std::cos(std::numbers::pi / kFlightConeRays);
  for (int k = 0; k < kFlightConeRays; ++k) {
    const double a = 2 * std::numbers::pi * k / kFlightConeRays;
    cone.rays.push_back(v + radius * (std::cos(a) * e1 + std::sin(a) * e2));
  }
  cone.far = 2 * scale + 1;
  return cone;
}

std::vector<FlightHit> fly(const ReachedSet::Impl& g, const FlightSource& source, const FlightCone& cone) {
  const CSpace& c = *g.cspace;
  const double margin = kUmbraRelativeMargin * c.scale();
  std::vector<Point3> gens = source.vertices;
  Box src_box, gen_box;
  for (const Point3& x : source.vertices) {
    src_box.add(to_vec(x));
    gen_box.add(to_vec(x));
    for (const Vec3& r : cone.rays) {
      const Vec3 d = cone.far * r;
      gens.push_back(x + Vector3(d.x(), d.y(), d.z()));
      gen_box.add(to_vec(x) + d);
    }
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
    std::vector<FT> s(gens.size());
    for (std::size_t i = 0; i < gens.size(); ++i) s[i] = value(chart.plane, gens[i]);
    Points2 pts;
    for (std::size_t i = 0; i < gens.size(); ++i) {
      if (s[i] == 0) pts.push_back(chart.project(gens[i]));
      if (s[i] <= 0) continue;
      const Point2 p2 = chart.project(gens[i]);
      for (std::size_t j = 0; j < gens.size(); ++j)
        if (s[j] < 0) pts.push_back(p2 + (chart.project(gens[j]) - p2) * (s[i] / (s[i] - s[j])));
    }
    if (pts.empty()) continue;
    Points2 section = clip(convex_hull(pts), g.face_polygon[gi]);
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
      bool all_front = true;
      for (const Point3& x : source.vertices) all_front = all_front && hc.plane.has_on_positive_side(x);
      if (!all_front) continue;  // Shadow_x(h) is empty for x in h's plane; skip h otherwise too (sound)
      const auto& poly = c.faces()[hi].polygon;
      std::vector<Point3> corners;
      for (const Vec3& p : poly) corners.push_back(exact(p));
      const Point3 inside = CGAL::centroid(corners[0], corners[1], corners[2]);
      Points2 umbra = section;
      umbra = clip(umbra, shrunk(restrict_to_chart(hc.plane.opposite(), chart), margin));  // beyond h
      for (const Point3& x : source.vertices) {
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

}  // namespace cmt::fp

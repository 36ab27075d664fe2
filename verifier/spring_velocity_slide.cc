// Sliding of the generalized spring on a face under the velocity-form error model
// (verifier/internal/spring_velocity.h; the proofs are in docs/verifier.md, "Velocity-form spring model").
//
// Sliding. In the plane the in-plane half-angle beta(d) replaces theta_v: the lateral deviation from
// seg[e, p*'] is at most L(d0) = max(zone, max_d d sin(min(Psi(d), pi/2))), Psi(d) = the integral of
// tan(beta(s)) / s from d to d0, and the wedge e + cone(p*' − e, beta(d_w)) holds the path until it enters
// the disk d <= d_w, which it never leaves (d_w > zone).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "verifier/internal/spring_flight.h"
#include "verifier/internal/spring_velocity.h"
#include "verifier/internal/spring_velocity_support.h"

namespace cmt::face_geometry {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSlack = kVelocitySlack;

// The plane of a slide on a face (docs/verifier.md "Velocity-form spring model", fact 3): p' (p projected on
// the plane), H >= |h*| (the depth of p* below it) and the zone radius H tan(theta_v) within which the
// in-plane direction is arbitrary; outside it the in-plane velocity lies within beta(d) of the direction to
// p*', sin beta(d) = sin(theta_v) sqrt(d^2 + H^2) / d (no bound where that reaches 1).
struct SlidePlane {
  Vec3 center;
  double H = 0, zone = 0, sin_v = 0;
  double sin_beta(double d) const { return sin_v * std::hypot(d, H) / d; }
};

SlidePlane slide_plane(const Face& face, const VelocitySpring& m) {
  const double h = face.offset - face.normal.dot(m.p);
  SlidePlane out;
  out.center = m.p + h * face.normal;
  out.H = std::abs(h) + m.u.eps_s;
  out.zone = out.H * std::tan(m.u.theta_v) * (1 + kSlack);
  out.sin_v = std::sin(m.u.theta_v);
  return out;
}

// Grid cells of the upper sums of Psi in lateral_deviation (any count is sound; more is tighter).
constexpr int kLateralCells = 400;
// The grid's least d lies this much (relative) above the zone, where tan(beta(d)) / d is finite.
constexpr double kAboveZone = 1e-9;
// The directional bounds (spiral regions, wedge) need every entry farther than eps_s from p' (relative
// margin): p*' lies within eps_s of p', so the direction from p*' to each entry is then defined.
constexpr double kEntryClearance = 1e-6;
// Floors d_f of the in-plane spiral regions: kSpiralFloors of them, from kFloorAboveZone (relative) above the
// zone to d0, denser near the zone (quadratic spacing), where beta changes fastest. Every floor gives a sound
// bound; more floors only tighten.
constexpr int kSpiralFloors = 8;
constexpr double kFloorAboveZone = 1e-3;
// The forward wedge's disk radius d_w = max(kWedgeDiskOfEntry x the entries' least distance, kWedgeDiskOfZone
// x zone): any d_w above the zone is sound (the disk is never left); a larger disk narrows the wedge's angle
// beta(d_w), a smaller one is a smaller disk.
constexpr double kWedgeDiskOfEntry = 0.5;
constexpr double kWedgeDiskOfZone = 1.5;

// The entry piece seen from p' in the face plane.
struct SlideEntries {
  std::vector<Vec3> lifted;    // the entry vertices (3-D)
  std::vector<Vec3> in_plane;  // each entry − p', projected on the plane
  Vec3 mean = Vec3::Zero();    // sum of the unit in-plane directions from p' (zero: no direction)
  double dmax = 0;             // max |e − p'| in the plane
  double dmin = 0;             // <= min |e − p'| over the (convex) piece
};

SlideEntries slide_entries(const FaceChart& chart, const Face& face, const Vec3& center,
                           const Points2& part) {
  SlideEntries e;
  for (const Point2& q : part) {
    const Vec3 v = chart.lift_double(q) - center;
    e.in_plane.push_back(v - face.normal.dot(v) * face.normal);
    e.dmax = std::max(e.dmax, e.in_plane.back().norm());
    if (e.in_plane.back().norm() > 0) e.mean += e.in_plane.back() / e.in_plane.back().norm();
  }
  for (const Point2& q : part) e.lifted.push_back(chart.lift_double(q));
  e.dmin = distance_in_plane(e.lifted, face.normal, center) * (1 - kSlack);
  return e;
}

// L(d0) (file comment) from upper sums of Psi on a grid: on each cell d sin Psi(d) <= d_hi sin(min(Psi(d_lo),
// pi/2)); at least the zone radius.
double lateral_deviation(const SlidePlane& plane, double d0) {
  const double zone = plane.zone;  // beta(d) = pi/2 for d <= h* tan(theta_v)
  // tan(beta(s)) / s, decreasing in s for s > zone.
  auto integrand = [&](double s) {
    const double sb = std::min(1.0, plane.sin_beta(s));
    return sb >= 1 ? std::numeric_limits<double>::infinity() : std::tan(std::asin(sb)) / s;
  };
  double lateral = zone;
  if (d0 <= zone) return lateral;
  double psi = 0, d_hi = d0;
  for (int j = 1; j <= kLateralCells; ++j) {
    const double d_lo = std::max(zone * (1 + kAboveZone), d0 - (d0 - zone) * j / kLateralCells);
    if (d_lo >= d_hi) break;
    psi += integrand(d_lo) * (d_hi - d_lo);
    if (psi * (1 + kSlack) >= kPi / 2) {
      lateral = std::max(lateral, d_hi);
      break;
    }
    lateral = std::max(lateral, d_hi * std::sin(psi * (1 + kSlack)));
    d_hi = d_lo;
  }
  return lateral;
}

// The tube: conv(part ∪ disk(p', eps)) ⊕ disk(L), within max(d0, zone) + eps of p', on the face and within
// the reach bound (outer polygon).
Points2 slide_tube(const ReachedSet::Impl& g, int fi, const Points2& part, const VelocitySpring& m,
                   const SlidePlane& plane, double d0, double lateral) {
  const Face& face = g.cspace->faces()[fi];
  const FaceChart& chart = g.charts[fi];
  const double eps = m.u.eps_s, margin = kSlack * g.cspace->scale();
  const Point2 c2 = chart.project(plane.center);
  Points2 pts = part;
  for (const Vector2& o : disk_offsets(chart, face.normal, eps * (1 + kSlack))) pts.push_back(c2 + o);
  Points2 tube =
      clip(minkowski_outward(pts, disk_offsets(chart, face.normal, lateral * (1 + kSlack) + margin)),
           g.face_polygon[fi]);
  const double reach = std::max(d0, plane.zone) * (1 + kSlack) + eps * (1 + kSlack) + margin;
  tube = clip(tube, minkowski_outward({c2}, disk_offsets(chart, face.normal, reach)));
  if (!tube.empty()) {
    const Points2 bound = velocity_reach_section(g, fi, m);
    tube = bound.empty() ? bound : clip(tube, bound);
  }
  return tube;
}

// The entries' mean in-plane direction from p' (`axis`, `perp` beside it in the plane), their angular spread
// about it, and `shift` >= the angle p*' − p' turns a direction from p' (asin(eps / dmin)).
struct SlideAxis {
  Vec3 axis, perp;
  double spread = 0, shift = 0;
};

SlideAxis slide_axis(const SlideEntries& e, const Vec3& normal, double eps) {
  SlideAxis a;
  a.axis = e.mean.normalized();
  a.perp = normal.cross(a.axis);
  for (const Vec3& w : e.in_plane)
    a.spread = std::max(a.spread, std::abs(std::atan2(w.dot(a.perp), w.dot(a.axis))));
  a.shift = std::asin(std::min(1.0, eps / e.dmin)) * (1 + kSlack) + kSlack;
  return a;
}

// In-plane spiral regions (docs/verifier.md "Spiral regions"): while d >= d_f > zone the in-plane angle is at
// most beta(d_f), so the path lies in the spiral region of angle beta(d_f) from its entry about p*', or
// within d_f of p*' once it gets there (d never grows back past d_f). Each floor d_f gives a convex bound;
// the region lies in all of them, so the least support is a bound. Intersects *out with the section of that
// bound; returns false (and fills *lower) when the section is a segment or point on the face: the whole
// slide.
bool clip_to_spiral_regions(const ReachedSet::Impl& g, int fi, const SlideEntries& e, const SlideAxis& ax,
                            const SlidePlane& plane, double eps, double d0, ChartRegion* out,
                            Points2* lower) {
  const double zone = plane.zone;
  const double axis_error = ax.spread * (1 + kSlack) + ax.shift;
  struct Floor {
    double d, beta;
  };
  std::vector<Floor> floors;
  for (int k = 0; k < kSpiralFloors; ++k) {
    const double t = static_cast<double>(k) / kSpiralFloors;
    const double d_f = zone * (1 + kFloorAboveZone) + (d0 - zone) * t * t;
    const double sb = plane.sin_beta(d_f);
    if (d_f <= 0 || sb >= std::sin(kPi / 2 - kVelocityPointedMargin)) continue;
    floors.push_back({d_f, std::asin(sb) * (1 + kSlack) + kSlack});
  }
  if (floors.empty()) return true;
  const Face& face = g.cspace->faces()[fi];
  const Vec3 n = face.normal;
  const double c_plane = face.offset;
  const Vec3 pc = plane.center;
  const Vec3 axis = ax.axis;
  const std::vector<Vec3>& lifted_part = e.lifted;
  const double r0 = d0 * (1 + kSlack);
  const double d_lo = std::max(0.0, e.dmin - eps);  // <= |e − p*'| for every entry e and p*'
  Support spiral = [lifted_part, n, c_plane, pc, axis, eps, r0, d_lo, axis_error, floors](const Vec3& w) {
    const Vec3 wt = w - w.dot(n) * n;
    const double norm = wt.norm();
    double tip = -std::numeric_limits<double>::infinity();
    for (const Vec3& x : lifted_part) tip = std::max(tip, x.dot(wt));
    if (norm == 0) return w.dot(n) * c_plane;
    const double gamma_a = angle_between(wt, axis);
    const double gamma = std::max(0.0, gamma_a - axis_error - kSlack);
    double best = std::numeric_limits<double>::infinity();
    const double gamma_hi = std::min(kPi, gamma_a + axis_error + kSlack);
    // d_e cos(gamma) over the entries (d_e in [d_lo, r0]) is at least this:
    const double cos_hi = std::cos(gamma_hi);
    const double min_proj = cos_hi >= 0 ? d_lo * cos_hi : r0 * cos_hi;
    for (const Floor& f : floors) {
      // Translated bound: the spiral or the floor's disk about p*'.
      double v = tip;
      if (gamma_hi > kPi / 2 - f.beta)
        v = std::max(v, pc.dot(wt) + norm * (eps * (1 + kSlack) +
                                             r0 * spiral_factor(gamma, f.beta) * (1 + kSlack) + kSlack));
      v = std::max(v, pc.dot(wt) + norm * ((eps + f.d) * (1 + kSlack) + kSlack));
      // Relative to the tips: the spiral's excess, or the disk's d_f − d_e cos(gamma).
      const double rel = std::max(r0 * spiral_excess(gamma, gamma_hi, f.beta), f.d - min_proj);
      v = std::min(v, tip + norm * (std::max(0.0, rel) * (1 + kSlack) + kSlack));
      best = std::min(best, v);
    }
    return best + w.dot(n) * c_plane;
  };
  const Points2 bound = support_section(g, fi, {spiral}, /*in_plane=*/true);
  if (bound.size() < 3) {  // a segment or point (on the face): the whole slide
    *lower = bound;
    return false;
  }
  ChartRegion tight = *out;
  tight.intersection(to_polygon(bound));
  if (!tight.is_empty()) *out = std::move(tight);  // else a lower-dimensional meet: keep the tube (sound)
  return true;
}

// The forward wedge part + cone(−axis, beta(d_w) + spread + shift) ∪ the disk d <= d_w about p*' (so within
// d_w + eps of p'): the path stays in the wedge until it enters the disk, which it never leaves (d_w > zone).
// Intersects *out with it (nothing when the wedge is not pointed).
void clip_to_forward_wedge(const ReachedSet::Impl& g, int fi, const Points2& part, const SlideEntries& e,
                           const SlideAxis& ax, const SlidePlane& plane, double eps, ChartRegion* out) {
  const Face& face = g.cspace->faces()[fi];
  const FaceChart& chart = g.charts[fi];
  const double scale = g.cspace->scale(), margin = kSlack * scale;
  const double d_w = std::max(kWedgeDiskOfEntry * e.dmin, kWedgeDiskOfZone * plane.zone);
  const double beta_w = std::asin(std::min(1.0, plane.sin_beta(d_w))) * (1 + kSlack) + kSlack;
  const double half = beta_w + ax.spread * (1 + kSlack) + ax.shift;
  if (half + kVelocityPointedMargin >= kPi / 2) return;
  // Rays with axis component 1 (as flight_cone's): the truncated wedge reaches `far` along the axis, past
  // every face point (all lie within `scale` of the part), whatever the half-angle.
  const double far = 2 * scale;
  Points2 wedge_pts;
  for (const Point2& q : part) {
    wedge_pts.push_back(q);
    for (const double sgn : {-1.0, 1.0}) {
      const Vec3 dir = -(ax.axis + sgn * std::tan(half) * ax.perp);
      wedge_pts.push_back(q + chart.project_direction(far * dir));
    }
  }
  ChartRegion allowed;
  const Points2 wedge = clip(convex_hull(wedge_pts), g.face_polygon[fi]);
  if (wedge.size() >= 3) allowed.join(to_polygon(wedge), g.charts[fi].cell);
  const Point2 c2 = chart.project(plane.center);
  const Points2 inner =
      clip(minkowski_outward({c2}, disk_offsets(chart, face.normal, (d_w + eps) * (1 + kSlack) + margin)),
           g.face_polygon[fi]);
  if (inner.size() >= 3) allowed.join(to_polygon(inner), g.charts[fi].cell);
  out->intersection(allowed);
}

// The slide from one entry piece (file comment), before the direction-cone rule (slide_piece): the tube, then
// (for entries clear of p') the spiral regions and the forward wedge.
ChartRegion slide_piece_bounds(const ReachedSet::Impl& g, int fi, const Points2& part,
                               const VelocitySpring& m, Points2* lower) {
  const Face& face = g.cspace->faces()[fi];
  const double eps = m.u.eps_s, margin = kSlack * g.cspace->scale();
  const SlidePlane plane = slide_plane(face, m);
  lower->clear();
  const SlideEntries entries = slide_entries(g.charts[fi], face, plane.center, part);
  const double d0 = entries.dmax + eps;  // >= |e − p*'|
  const Points2 tube = slide_tube(g, fi, part, m, plane, d0, lateral_deviation(plane, d0));
  if (tube.size() < 3) {
    *lower = tube;
    return ChartRegion();
  }
  ChartRegion out(to_polygon(tube), g.charts[fi].cell);
  if (entries.dmin <= eps * (1 + kEntryClearance) + margin || entries.mean.norm() == 0) return out;
  const SlideAxis axis = slide_axis(entries, face.normal, eps);
  if (!clip_to_spiral_regions(g, fi, entries, axis, plane, eps, d0, &out, lower)) return ChartRegion();
  clip_to_forward_wedge(g, fi, part, entries, axis, plane, eps, &out);
  return out;
}

// Direction cones of a slide (docs/verifier.md, "Direction cones of slides"). A path whose velocity always
// lies in a convex cone C stays in x0 + C. While the robot slides on face fi within a region K that bounds
// the slide (the other bounds), its in-plane velocity at x is within beta(|x − p*'|) of the direction to p*',
// so within angle(m, p' − x) + asin(eps_s / |x − p'|) + beta(|x − p'| − eps_s) of a unit in-plane direction m
// (beta decreasing in d, |p*' − p'| <= eps_s). Over K, cut into pieces of small angular and radial extent
// about p' (split_source), the largest such angle alpha(m) is bounded per piece (the angle to m is largest at
// a vertex: its sublevel sets are convex cones about p'); if alpha(m) < pi/2 the slide lies in part + cone(m,
// alpha(m)). Candidates m: the outward normals of the face's boundary edges (a robot that must cross an edge
// leaves the face there: from a source on that edge the cone meets the face only in the source) and the
// mean direction from the source toward p'.
ChartRegion direction_cone_bound(const ReachedSet::Impl& g, int fi, const Points2& part,
                                 const VelocitySpring& m, ChartRegion region, Points2* lower) {
  const CSpace& c = *g.cspace;
  const Face& face = c.faces()[fi];
  const FaceChart& chart = g.charts[fi];
  const double eps = m.u.eps_s, scale = c.scale();
  const SlidePlane plane = slide_plane(face, m);
  const Vec3& center = plane.center;  // p'
  // K: the hull of the region (3-D doubles).
  Points2 verts;
  {
    std::vector<PolygonWithHoles2> pwhs;
    region.polygons_with_holes(std::back_inserter(pwhs));
    for (const PolygonWithHoles2& pwh : pwhs)
      verts.insert(verts.end(), pwh.outer_boundary().vertices_begin(), pwh.outer_boundary().vertices_end());
  }
  const Points2 hull = convex_hull(verts);
  if (hull.size() < 3) return region;
  std::vector<Vec3> k3;
  for (const Point2& q : hull) k3.push_back(chart.lift_double(q));
  // Candidate directions (unit, in the plane).
  std::vector<Vec3> dirs;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& q : face.polygon) centroid += q / static_cast<double>(face.polygon.size());
  for (std::size_t i = 0; i < face.polygon.size(); ++i) {
    const Vec3 e = face.polygon[(i + 1) % face.polygon.size()] - face.polygon[i];
    Vec3 out = face.normal.cross(e);
    if (out.norm() == 0) continue;
    out.normalize();
    if (out.dot(centroid - face.polygon[i]) > 0) out = -out;
    dirs.push_back(out);
  }
  {
    Vec3 mean = Vec3::Zero();
    for (const Point2& q : part) {
      Vec3 v = center - chart.lift_double(q);
      v -= face.normal.dot(v) * face.normal;
      if (v.norm() > 0) mean += v.normalized();
    }
    if (mean.norm() > 1e-9) dirs.push_back(mean.normalized());
  }
  std::vector<double> alpha(dirs.size(), 0.0);
  auto beta = [&](double d) {
    if (d <= plane.zone) return kPi;
    const double sb = plane.sin_beta(d);
    return sb >= 1 ? kPi : std::asin(sb) * (1 + kSlack) + kSlack;
  };
  split_source(k3, center, eps, std::max(eps, 1e-3 * scale), kSlack * scale,
               [&](const std::vector<Vec3>& piece, double r_lower) {
                 const double d_lo = r_lower - eps;
                 const double add = r_lower <= eps
                                        ? kPi
                                        : beta(d_lo) + std::asin(std::min(1.0, eps / r_lower)) * (1 + kSlack);
                 for (std::size_t j = 0; j < dirs.size(); ++j) {
                   double worst = 0;
                   for (const Vec3& x : piece) {
                     Vec3 v = center - x;
                     v -= face.normal.dot(v) * face.normal;
                     worst = std::max(worst, v.norm() == 0 ? kPi : angle_between(dirs[j], v));
                   }
                   alpha[j] = std::max(alpha[j], worst * (1 + kSlack) + add);
                 }
               });
  const Vec3 n = face.normal;
  // Rays with component 1 along m: the truncated cone reaches `far` along m, past every face point (all lie
  // within `scale` of the part), whatever alpha(m) is.
  const double far = 2 * scale;
  bool cut_any = false;
  for (std::size_t j = 0; j < dirs.size(); ++j) {
    const double a = alpha[j] + kSlack;
    if (a + kVelocityPointedMargin >= kPi / 2) continue;
    const Vec3 side = n.cross(dirs[j]);
    Points2 cone_pts;
    for (const Point2& q : part) {
      cone_pts.push_back(q);
      for (const double sgn : {-1.0, 1.0})
        cone_pts.push_back(q + chart.project_direction(far * (dirs[j] + sgn * std::tan(a) * side)));
    }
    const Points2 cone = convex_hull(cone_pts);
    if (cone.size() < 3) continue;
    // Nothing to cut when the region's hull already lies in the (convex) cone: exact tests, no Boolean.
    bool inside = true;
    for (const Point2& q : hull) inside = inside && inside_closed(cone, q);
    if (inside) continue;
    region.intersection(to_polygon(cone));
    cut_any = true;
    if (region.is_empty()) break;
  }
  if (cut_any && region.is_empty()) *lower = part.size() < 3 ? part : Points2{};
  return region;
}

// The slide from one entry piece: the bounds of slide_piece_bounds, then the direction cones.
ChartRegion slide_piece(const ReachedSet::Impl& g, int fi, const Points2& part, const VelocitySpring& m,
                        Points2* lower) {
  ChartRegion out = slide_piece_bounds(g, fi, part, m, lower);
  if (out.is_empty()) return out;
  return direction_cone_bound(g, fi, part, m, std::move(out), lower);
}

}  // namespace

ChartRegion velocity_slide(const ReachedSet::Impl& g, int fi, const Points2& part, const VelocitySpring& m,
                           Points2* lower) {
  lower->clear();
  if (part.size() < 2) return slide_piece(g, fi, part, m, lower);  // segments are cut like polygons
  const Face& face = g.cspace->faces()[fi];
  const FaceChart& chart = g.charts[fi];
  const Vec3 center = m.p + (face.offset - face.normal.dot(m.p)) * face.normal;
  std::vector<Vec3> poly;
  double dmax = 0;
  for (const Point2& q : part) {
    poly.push_back(chart.lift_double(q));
    dmax = std::max(dmax, (poly.back() - center).norm());
  }
  // Radial extent: the lateral bound grows by about L(d0) / d0 per unit of d0 (at most tan of the in-plane
  // angle, which is >= theta_v); eps / 4 of growth per piece, as for flights.
  const double radial_limit =
      cutting_eps(m.u, g.cspace->scale()) / (4 * std::max(std::tan(m.u.theta_v), 1e-3));
  std::vector<Polygon2> polys;
  Points2 first_lower;
  // A source near p' (within 2 eps_s) cannot be cut into pieces whose directions from p' are defined (the
  // spiral bounds need them): first cut it by the four lines of the square of half-side 2 eps_s about p'
  // (face frame), so that every part but the central one stays 2 eps_s from p'.
  std::vector<std::vector<Vec3>> parts = {poly};
  const double rho = 2 * m.u.eps_s, cut_margin = kSlack * g.cspace->scale();
  if (m.u.eps_s > 0 && distance_in_plane(poly, face.normal, center) <= rho) {
    Vec3 e1, e2;
    plane_frame(face.normal, &e1, &e2);
    for (const Vec3& dir : {e1, e2}) {
      std::vector<std::vector<Vec3>> next;
      for (const std::vector<Vec3>& part : parts) {
        auto [below, rest] = cut(part, dir, dir.dot(center) - rho, cut_margin);
        auto [middle, above] = cut(rest, dir, dir.dot(center) + rho, cut_margin);
        for (auto* q : {&below, &middle, &above})
          if (!q->empty()) next.push_back(std::move(*q));
      }
      parts = std::move(next);
    }
  }
  for (const std::vector<Vec3>& part : parts)
    split_source(part, center, cutting_eps(m.u, g.cspace->scale()), radial_limit, kSlack * g.cspace->scale(),
                 [&](const std::vector<Vec3>& piece, double) {
                   Points2 pts;
                   for (const Vec3& x : piece) pts.push_back(chart.project(x));
                   // the chart image of the double piece, rounded outward (covers the cut's rounding)
                   if (pts.size() >= 3)
                     pts =
                         minkowski_outward(pts, disk_offsets(chart, face.normal, kSlack * g.cspace->scale()));
                   Points2 piece_lower;
                   ChartRegion region = slide_piece(g, fi, pts, m, &piece_lower);
                   if (!region.is_empty()) {
                     std::vector<PolygonWithHoles2> pwhs;
                     region.polygons_with_holes(std::back_inserter(pwhs));
                     for (const PolygonWithHoles2& pwh : pwhs) polys.push_back(pwh.outer_boundary());
                   } else if (!piece_lower.empty() && first_lower.empty()) {
                     first_lower = piece_lower;
                   }
                 });
  ChartRegion out = union_of(polys, g.charts[fi].cell);
  if (out.is_empty()) *lower = first_lower;
  return out;
}

}  // namespace cmt::face_geometry

// The generalized spring's free-space reach and sliding strip (verifier/internal/spring_flight.h).
//
// Free space (Fig 3.13): a trajectory from x commanded to p stays within eps_t of seg[x, p + eps_o u(x)]
// (the eps_t cylinder about the line toward p, overshooting p by at most eps_o). For a convex source X with
// vertices x_i, the overshoot points p + eps_o u with u in the cone of the u_i lie in conv(p, p + (eps_o / c)
// u_i) (|w| >= c for w in conv(u_i)), so V = conv(gens) ⊕ ball(eps_t) holds every trajectory from X.
//
// Section of V by a target plane H (unit normal n): y in H is in V iff some g in conv(gens) has |g − y| <=
// eps_t. With t = |(g − H) . n| in [t_k, t_{k+1}] (t_k = k eps_t / m), the in-plane distance from y to the
// orthogonal projection of g is <= sqrt(eps_t^2 − t_k^2). So V ∩ H ⊆ ∪_k proj_H(conv(gens) ∩ slab(t_{k+1}))
// ⊕ disk(sqrt(eps_t^2 − t_k^2)). conv(gens) ∩ slab is the hull of the generators inside and the crossings of
// generator pairs with the slab planes (exact); the projection is exact; the disks are circumscribed
// polygons.
#include "verifier/internal/spring_flight.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>

namespace cmt::face_geometry {
namespace {

constexpr double kPi = std::numbers::pi;

FT value(const Plane3& p, const Point3& x) { return p.a() * x.x() + p.b() * x.y() + p.c() * x.z() + p.d(); }

// Overshoot points p + (eps_o / c) u_i for unit directions u_i (doubles), or nothing when the cap bound
// fails.
std::vector<Vec3> overshoot_points(const std::vector<Vec3>& from, const Vec3& p, double eps_o, double scale) {
  std::vector<Vec3> dirs;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& x : from) {
    const Vec3 d = p - x;
    if (d.norm() <= 1e-9 * scale) return {};
    dirs.push_back(d.normalized());
    mean += dirs.back();
  }
  if (dirs.empty() || mean.norm() == 0) return {};
  mean.normalize();
  double c = 1;
  for (const Vec3& u : dirs) c = std::min(c, u.dot(mean));
  if (c < kSpringMinCapCosine) return {};
  const double reach = eps_o / c * (1 + kSpringRelativeSlack);
  std::vector<Vec3> out = {p};
  for (const Vec3& u : dirs) out.push_back(p + reach * u);
  return out;
}

using InexactPoint = CGAL::Exact_predicates_inexact_constructions_kernel::Point_2;

// Candidate vertices of the Minkowski sum of two counter-clockwise convex polygons a and b: the merge of
// their edges by polar angle from their lowest vertices (the sum's vertex sequence), each step also emitting
// both successors a_i+1 + b_j and a_i + b_j+1. A comparison of nearly parallel edges that rounding decides
// wrongly then still leaves every vertex of the exact sum among the points, or one within |edge| x 2^-52 of
// them; the caller's hull of the points is the sum (O(|a| + |b|) points instead of |a| |b|).
std::vector<InexactPoint> merged_sum_points(const std::vector<InexactPoint>& a,
                                            const std::vector<InexactPoint>& b) {
  auto lowest = [](const std::vector<InexactPoint>& p) {
    std::size_t k = 0;
    for (std::size_t i = 1; i < p.size(); ++i)
      if (p[i].y() < p[k].y() || (p[i].y() == p[k].y() && p[i].x() < p[k].x())) k = i;
    return k;
  };
  std::vector<InexactPoint> out;
  if (a.empty() || b.empty()) return out;
  const std::size_t na = a.size(), nb = b.size(), a0 = lowest(a), b0 = lowest(b);
  auto at_a = [&](std::size_t k) { return a[(a0 + k) % na]; };
  auto at_b = [&](std::size_t k) { return b[(b0 + k) % nb]; };
  auto sum = [&](std::size_t i, std::size_t j) {
    out.emplace_back(at_a(i).x() + at_b(j).x(), at_a(i).y() + at_b(j).y());
  };
  std::size_t i = 0, j = 0;
  while (i < na || j < nb) {
    sum(i, j);
    sum(i + 1, j);
    sum(i, j + 1);
    if (i == na) {
      ++j;
      continue;
    }
    if (j == nb) {
      ++i;
      continue;
    }
    const double ax = at_a(i + 1).x() - at_a(i).x(), ay = at_a(i + 1).y() - at_a(i).y();
    const double bx = at_b(j + 1).x() - at_b(j).x(), by = at_b(j + 1).y() - at_b(j).y();
    const double cross = ax * by - ay * bx;  // > 0: a's edge turns first
    if (cross >= 0) ++i;
    if (cross <= 0) ++j;
  }
  return out;
}

}  // namespace

// Chart offsets of a polygon circumscribing the disk of radius r in the plane with normal n.
std::vector<Vector2> disk_offsets(const FaceChart& chart, const Vec3& n, double r) {
  Vec3 u, w;
  plane_frame(n, &u, &w);
  const double R = r / std::cos(kPi / kSpringDiskSides) * (1 + kSpringRelativeSlack);
  std::vector<Vector2> out;
  for (int k = 0; k < kSpringDiskSides; ++k) {
    const double a = 2 * kPi * k / kSpringDiskSides;
    out.push_back(chart.project_direction(R * (std::cos(a) * u + std::sin(a) * w)));
  }
  return out;
}

// conv(points) ⊕ conv(offsets), rounded outward to double vertices: a superset of the exact sum whose points
// are plain doubles, so that later predicates on them never evaluate deep lazy-exact constructions (those
// took most of the spring projection's time: 40 % in the exact convex hulls of flight sections, 14 % in the
// exceptions of failed interval filters, hole `teach`). Each exact point lies in the box of its coordinates'
// interval enclosures (CGAL::to_interval); the boxes are grown by s = kSpringRoundingSlack (1 + the largest
// magnitude) and their corners summed with the offsets in doubles: each computed sum is within 2^-53 of its
// magnitude (far below s) of the exact sum of a box corner, so the hull (exact predicates on doubles, Epick)
// of the computed sums contains every exact point plus every offset. The offsets are exact doubles
// (disk_offsets). Only the sums that can be vertices are formed (merged_sum_points: the corners' hull and the
// offsets' hull merged by edge angle).
Points2 minkowski_outward(const Points2& points, const std::vector<Vector2>& offsets) {
  using Inexact = CGAL::Exact_predicates_inexact_constructions_kernel;
  double big = 0;
  std::vector<std::array<double, 4>> boxes;  // x lo, x hi, y lo, y hi
  for (const Point2& p : points) {
    const auto x = CGAL::to_interval(p.x()), y = CGAL::to_interval(p.y());
    boxes.push_back({x.first, x.second, y.first, y.second});
    big = std::max({big, std::abs(x.first), std::abs(x.second), std::abs(y.first), std::abs(y.second)});
  }
  std::vector<std::array<double, 2>> d;
  for (const Vector2& v : offsets) {
    d.push_back({CGAL::to_double(v.x()), CGAL::to_double(v.y())});
    big = std::max({big, std::abs(d.back()[0]), std::abs(d.back()[1])});
  }
  const double s = kSpringRoundingSlack * (1 + 2 * big);
  std::vector<Inexact::Point_2> corners, hull, ring;
  for (const auto& b : boxes)
    for (const double x : {b[0] - s, b[1] + s})
      for (const double y : {b[2] - s, b[3] + s}) corners.emplace_back(x, y);
  CGAL::convex_hull_2(corners.begin(), corners.end(), std::back_inserter(hull));
  corners.clear();
  for (const auto& v : d) corners.emplace_back(v[0], v[1]);
  CGAL::convex_hull_2(corners.begin(), corners.end(), std::back_inserter(ring));
  std::vector<Inexact::Point_2> sums = merged_sum_points(hull, ring);
  hull.clear();
  CGAL::convex_hull_2(sums.begin(), sums.end(), std::back_inserter(hull));
  Points2 out;
  for (const Inexact::Point_2& h : hull) out.emplace_back(h.x(), h.y());
  return out;
}

std::vector<Point3> spring_generators(const std::vector<Point3>& source, const Vec3& p, double eps_o) {
  std::vector<Vec3> from;
  Vec3 lo = p, hi = p;
  for (const Point3& x : source) {
    from.push_back(to_vec(x));
    lo = lo.cwiseMin(from.back());
    hi = hi.cwiseMax(from.back());
  }
  std::vector<Point3> gens = source;
  std::vector<Vec3> extra = overshoot_points(from, p, eps_o, std::max(1.0, (hi - lo).norm()));
  if (extra.empty()) {
    const double h = eps_o * (1 + kSpringRelativeSlack);
    for (int k = 0; k < 8; ++k) extra.push_back(p + Vec3(k & 1 ? h : -h, k & 2 ? h : -h, k & 4 ? h : -h));
  }
  for (const Vec3& q : extra) gens.push_back(exact(q));
  return gens;
}

std::vector<FlightHit> spring_fly(const ReachedSet::Impl& g, const std::vector<Point3>& gens, int source_face,
                                  double eps_t) {
  const CSpace& c = *g.cspace;
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Point3& x : gens) {
    lo = lo.cwiseMin(to_vec(x));
    hi = hi.cwiseMax(to_vec(x));
  }
  const double pad = eps_t * 2 + 1e-9 * c.scale();
  std::vector<FlightHit> hits;
  for (std::size_t gi = 0; gi < c.faces().size(); ++gi) {
    if (static_cast<int>(gi) == source_face) continue;
    const Face& face = c.faces()[gi];
    Vec3 flo = Vec3::Constant(1e300), fhi = Vec3::Constant(-1e300);
    for (const Vec3& q : face.polygon) {
      flo = flo.cwiseMin(q);
      fhi = fhi.cwiseMax(q);
    }
    bool meets = true;
    for (int k = 0; k < 3; ++k) meets = meets && flo[k] <= hi[k] + pad && lo[k] <= fhi[k] + pad;
    if (!meets) continue;
    // Cheap rejection: every generator farther than eps_t from the plane on one side (doubles, with margin).
    double dmin = 1e300, dmax = -1e300;
    for (const Point3& x : gens) {
      const double dist = face.normal.dot(to_vec(x)) - face.offset;
      dmin = std::min(dmin, dist);
      dmax = std::max(dmax, dist);
    }
    const double band = eps_t * (1 + 1e-6) + 1e-9 * c.scale();
    if (dmin > band || dmax < -band) continue;
    const FaceChart& chart = g.charts[gi];
    const Plane3& H = chart.plane;
    const FT nn = H.a() * H.a() + H.b() * H.b() + H.c() * H.c();
    const double norm_up = std::sqrt(CGAL::to_double(nn)) * (1 + kSpringRelativeSlack);
    std::vector<FT> s(gens.size());
    for (std::size_t i = 0; i < gens.size(); ++i) s[i] = value(H, gens[i]);
    auto project = [&](const Point3& q) {
      const FT k = value(H, q) / nn;
      return chart.project(Point3(q.x() - k * H.a(), q.y() - k * H.b(), q.z() - k * H.c()));
    };
    std::vector<Polygon2> layer_polygons;  // united below (union_of)
    Points2 lower;
    const int layers = eps_t > 0 ? kSpringSlabLayers : 1;
    for (int k = 0; k < layers; ++k) {
      const FT T = FT(eps_t * (k + 1) / layers * norm_up);
      Points2 pts;
      for (std::size_t i = 0; i < gens.size(); ++i) {
        if (CGAL::abs(s[i]) <= T) pts.push_back(project(gens[i]));
        for (std::size_t j = 0; j < gens.size(); ++j)
          for (const FT& level : {T, FT(-T)}) {
            if (s[i] > level && s[j] < level) {
              const FT f = (s[i] - level) / (s[i] - s[j]);
              pts.push_back(project(gens[i] + (gens[j] - gens[i]) * f));
            }
          }
      }
      if (pts.empty()) continue;
      const double t_k = eps_t * k / layers;
      const double radius = std::sqrt(std::max(0.0, eps_t * eps_t - t_k * t_k));
      Points2 grown;
      if (radius > 0) {
        grown = minkowski_outward(pts, disk_offsets(chart, face.normal, radius));
      } else {
        grown = convex_hull(pts);
        if (grown.empty()) grown = {pts[0]};
      }
      grown = clip(grown, g.face_polygon[gi]);
      if (grown.size() >= 3)
        layer_polygons.push_back(to_polygon(grown));
      else if (!grown.empty() && lower.empty())
        lower = grown;
    }
    const ChartRegion region = union_of(layer_polygons, chart.cell);
    if (region.is_empty() && lower.empty()) continue;
    FlightHit hit;
    hit.face = static_cast<int>(gi);
    hit.region = std::move(region);
    if (hit.region.is_empty()) hit.lower = std::move(lower);
    hits.push_back(std::move(hit));
  }
  return hits;
}

Points2 chart_disk(const ReachedSet::Impl& g, int fi, const Vec3& center, double r, bool outer) {
  const FaceChart& chart = g.charts[fi];
  const Face& face = g.cspace->faces()[fi];
  if (outer) return minkowski_outward({chart.project(center)}, disk_offsets(chart, face.normal, r));
  Vec3 u, w;
  plane_frame(face.normal, &u, &w);
  // Inscribed, pulled in by the slack: the chart image of a polygon inside the disk.
  const double R = r * (1 - 1e3 * kSpringRelativeSlack);
  Points2 pts;
  for (int k = 0; k < kSpringDiskSides; ++k) {
    const double a = 2 * kPi * k / kSpringDiskSides;
    pts.push_back(chart.project(center) + chart.project_direction(R * (std::cos(a) * u + std::sin(a) * w)));
  }
  return convex_hull(pts);
}

Points2 spring_strip(const ReachedSet::Impl& g, int fi, const Points2& part, const Vec3& p_proj, double eps_t,
                     double eps_o) {
  const FaceChart& chart = g.charts[fi];
  std::vector<Vec3> from;
  for (const Point2& q : part) from.push_back(chart.lift_double(q));
  Points2 pts = part;
  const std::vector<Vec3> extra = overshoot_points(from, p_proj, eps_o, g.cspace->scale());
  if (extra.empty()) {
    for (const Point2& q : chart_disk(g, fi, p_proj, eps_o, /*outer=*/true)) pts.push_back(q);
  } else {
    for (const Vec3& q : extra) pts.push_back(chart.project(q));
  }
  if (eps_t > 0)
    return clip(minkowski_outward(pts, disk_offsets(chart, g.cspace->faces()[fi].normal, eps_t)),
                g.face_polygon[fi]);
  Points2 hull = convex_hull(pts);
  if (hull.empty()) hull = {pts[0]};
  return clip(hull, g.face_polygon[fi]);
}

double edge_either_way_halfwidth(const Edge& e, const Vec3& p, const Uncertainty& u, double overshoot) {
  const Vec3 d = e.b - e.a;
  const Vec3 q = e.a + (p - e.a).dot(d) / d.squaredNorm() * d;
  const double perp = (p - q).norm(), sv = std::sin(u.theta_v);
  if (sv >= 1) return std::numeric_limits<double>::infinity();
  auto f = [&](double s) { return s - u.eps_s - sv * (std::hypot(perp, s) + u.eps_s); };
  double lo = 0, hi = 1;
  while (f(hi) <= 0) hi *= 2;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) <= 0 ? lo : hi) = mid;
  }
  return std::max(hi, overshoot) * (1 + kSpringRelativeSlack);
}

double edge_must_leave_halfwidth(const CSpace& cspace, const Edge& e, double tp, const Vec3& p,
                                 const Uncertainty& u, double margin) {
  if (e.shape == EdgeShape::kNonManifold) return 0;
  const double sv = std::sin(u.theta_v);
  double radius = 0;
  for (int f : e.faces) {
    const Face& face = cspace.faces()[f];
    const double pull_away = -(face.offset - face.normal.dot(p)) - u.eps_s - margin;
    double r_f;
    if (pull_away <= 0)
      r_f = 0;
    else if (sv <= 0)
      r_f = std::numeric_limits<double>::infinity();
    else
      r_f = std::max(0.0, pull_away / sv - u.eps_s);
    radius = std::max(radius, r_f);
  }
  if (std::isinf(radius)) return radius;
  const double perp = (p - (e.a + tp * (e.b - e.a))).norm();
  if (radius <= perp) return 0;
  return std::sqrt(radius * radius - perp * perp) / (e.b - e.a).norm() - kEdgeParamSlack;
}

}  // namespace cmt::face_geometry

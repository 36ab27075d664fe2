// The generalized spring under the velocity-form error model (verifier/internal/spring_velocity.h; the proofs
// are in docs/verifier.md, "Velocity-form spring model").
//
// Flight. For a source point x and a fixed p* every reached y lies within delta |x − p*| of seg[x, p*] and in
// the cone x + cone(p* − x, theta_v), and |y − p*| <= |x − p*|. Over a convex source piece X and every p* in
// B(p, eps): y ∈ conv(X ∪ B(p, eps)) ⊕ ball(delta (R + eps)) (seg[x, p*] lies in conv(x, B(p, eps))), y ∈ X +
// cone(−a, theta_v + sigma + asin(eps / R_min)) (p* − x is within asin(eps / |x − p|) of p − x, which is
// within sigma of −a), and |y − p| <= R + 2 eps. All three are convex; their sections by a face plane are
// computed from support functions (support_section), so a piece's reach on a face is a convex polygon.
// Sources are cut into pieces so that sigma and the spread of R stay small (the bounds are per piece).
//
// Sliding. In the plane the in-plane half-angle beta(d) replaces theta_v: the lateral deviation from
// seg[e, p*'] is at most L(d0) = max(zone, max_d d sin(min(Psi(d), pi/2))), Psi(d) = the integral of
// tan(beta(s)) / s from d to d0, and the wedge e + cone(p*' − e, beta(d_w)) holds the path until it enters
// the disk d <= d_w, which it never leaves (d_w > zone).
#include "verifier/internal/spring_velocity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <utility>

#include "models/polygon_distance.h"
#include "verifier/internal/spring_flight.h"

namespace cmt::fp {

double angle_between(const Vec3& a, const Vec3& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

std::vector<Vec3> clip_halfspace(const std::vector<Vec3>& poly, const Vec3& n, double c) {
  std::vector<Vec3> out;
  const std::size_t k = poly.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3& a = poly[i];
    const Vec3& b = poly[(i + 1) % k];
    const double sa = n.dot(a) - c, sb = n.dot(b) - c;
    if (sa <= 0) out.push_back(a);
    if ((sa < 0 && sb > 0) || (sa > 0 && sb < 0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
  }
  return out;
}

// The support bound's search over lambda (any lambda is sound, so these only set how tight the bound is):
// within [−kLambdaRange, kLambdaRange], to a bracket of kLambdaResolution (the width 60 golden-section steps
// leave of the whole range), starting from a bracket of half-width kLambdaWarmWidth x (1 + |guess|) about the
// previous direction's minimiser.
constexpr double kLambdaRange = 1e3;
constexpr double kLambdaResolution = 2 * kLambdaRange * 3.1e-13;
constexpr double kLambdaWarmWidth = 1e-2;

// The least value found of f on [−kLambdaRange, kLambdaRange], searched to a bracket of kLambdaResolution;
// *guess: where to start, and on return the minimiser found. A bracket [lo, hi] about the guess is widened
// (doubling) until f(mid) <= f(lo), f(hi) or it reaches the range's end, so that it holds a minimiser when f
// is convex; golden-section steps then shrink it. A support bound that is the minimum of two bounds (the
// spiral's) is not convex everywhere, and then this finds a local minimum. Every value is an f(lambda), so
// the result is as sound as any single evaluation; the search only sets how tight it is.
double minimize_over_lambda(const std::function<double(double)>& f, double* guess) {
  const double width = kLambdaWarmWidth * (1 + std::abs(*guess));
  double mid = std::clamp(*guess, -kLambdaRange, kLambdaRange);
  double lo = std::max(-kLambdaRange, mid - width), hi = std::min(kLambdaRange, mid + width);
  double f_lo = f(lo), f_mid = f(mid), f_hi = f(hi);
  while (f_lo < f_mid && lo > -kLambdaRange) {  // the minimum lies to the left
    hi = mid, f_hi = f_mid, mid = lo, f_mid = f_lo;
    lo = std::max(-kLambdaRange, mid - 2 * (hi - mid));
    f_lo = f(lo);
  }
  while (f_hi < f_mid && hi < kLambdaRange) {  // to the right
    lo = mid, f_lo = f_mid, mid = hi, f_mid = f_hi;
    hi = std::min(kLambdaRange, mid + 2 * (mid - lo));
    f_hi = f(hi);
  }
  double best = std::min({f_lo, f_mid, f_hi});
  *guess = best == f_mid ? mid : (best == f_lo ? lo : hi);
  const double r = (std::sqrt(5.0) - 1) / 2;
  double a = lo, b = hi;
  double x1 = b - r * (b - a), x2 = a + r * (b - a), f1 = f(x1), f2 = f(x2);
  while (b - a > kLambdaResolution) {
    if (f1 <= f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - r * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + r * (b - a), f2 = f(x2);
    }
  }
  for (const auto& [x, fx] : {std::pair{x1, f1}, std::pair{x2, f2}})
    if (fx < best) best = fx, *guess = x;
  return best;
}

namespace {

constexpr double kPi = std::numbers::pi;
// Relative slack on angles, radii and bounds computed in floating point (all rounded toward "more").
constexpr double kSlack = 1e-9;
// Grid of snap_outward, x scene scale.
constexpr double kVelocitySnap = 1e-7;
// Angular margin (rad) by which a face normal must lie inside a piece's tip cone for touches_only_at_tips.
constexpr double kVelocityTipMargin = 1e-6;

// The support function w -> max { y . w : y in the set } of a convex set (w need not be a unit vector).
using Support = std::function<double(const Vec3&)>;

// A convex chart polygon grown by kVelocitySnap x scale and its vertices rounded to the grid of that
// spacing, then hulled: it contains the polygon (each vertex moves by at most spacing / sqrt 2 < the growth),
// and nearly equal polygons (the same bound computed from slightly different pieces) become equal, so the
// fixpoint does not chase rounding-level slivers.
Points2 snap_outward(const Points2& poly, const FaceChart& chart, const Vec3& n, double scale) {
  if (poly.size() < 3) return poly;
  const double grid = kVelocitySnap * scale;
  const Points2 grown = minkowski_outward(poly, disk_offsets(chart, n, grid));
  Points2 snapped;
  for (const Point2& q : grown) {
    const double x = CGAL::to_double(q.x()), y = CGAL::to_double(q.y());
    snapped.emplace_back(std::round(x / grid) * grid, std::round(y / grid) * grid);
  }
  return convex_hull(snapped);
}

// Clips the double polygon `poly` (frame coordinates) to cs x + sn y <= bound.
void clip_poly(std::vector<std::array<double, 2>>& poly, double cs, double sn, double bound) {
  std::vector<std::array<double, 2>> out;
  const std::size_t k = poly.size();
  for (std::size_t i = 0; i < k; ++i) {
    const auto& P = poly[i];
    const auto& Q = poly[(i + 1) % k];
    const double sp = cs * P[0] + sn * P[1] - bound, sq = cs * Q[0] + sn * Q[1] - bound;
    if (sp <= 0) out.push_back(P);
    if ((sp < 0 && sq > 0) || (sp > 0 && sq < 0)) {
      const double t = sp / (sp - sq);
      out.push_back({P[0] + t * (Q[0] - P[0]), P[1] + t * (Q[1] - P[1])});
    }
  }
  poly = std::move(out);
}

// Outer polygon (chart coordinates, clipped to the face) of the section of the intersection of convex sets
// by face fi's plane n . y = c. For a unit in-plane direction v and any lambda, v . y = (v + lambda n) . y −
// lambda c <= h(v + lambda n) − lambda c on the section, so every lambda gives a sound bound; a
// search over lambda (minimize_over_lambda) makes it tight. The polygon is the intersection of
// kVelocitySupportDirections such half-planes per set, each bound raised by a margin for the rounding of
// doubles. `in_plane`: every set's support is of the form g(v) + (w . n)
// c for w = v + lambda n (a set given by its in-plane section), so lambda = 0 is as tight as any: no search.
//
// `cuts`: half-spaces that hold the whole motion (velocity_invariant_half_spaces); the polygon is also
// clipped to their lines in the plane (exact lines in doubles, rounded outward with the rest).
Points2 support_section(const ReachedSet::Impl& g, int fi, const std::vector<Support>& sets,
                        bool in_plane = false, const std::vector<HalfSpace>* cuts = nullptr) {
  const Face& face = g.cspace->faces()[fi];
  const Vec3& n = face.normal;
  const double c = face.offset, scale = g.cspace->scale();
  const double margin = kSlack * scale;
  for (const Support& h : sets)
    if (h(n) < c - margin || -h(-n) > c + margin) return {};  // a set lies on one side of the plane
  Vec3 e1, e2;
  face_frame(n, &e1, &e2);
  const Vec3 origin = c * n;
  // The starting square holds the whole face (the section is clipped to the face at the end): centred on the
  // face's vertex centroid, half-size above the scene's diameter (every face point lies within `scale` of
  // it). Relative to the face, not to the world origin, so the section does not depend on where the task
  // sits in the world or on its units.
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& q : face.polygon) centroid += q / static_cast<double>(face.polygon.size());
  const double cx = (centroid - origin).dot(e1), cy = (centroid - origin).dot(e2);
  const double big = 2 * scale;
  std::vector<std::array<double, 2>> poly = {
      {cx - big, cy - big}, {cx + big, cy - big}, {cx + big, cy + big}, {cx - big, cy + big}};
  for (const Support& h : sets) {
    double guess = 0;  // the minimiser moves little between neighbouring directions
    for (int j = 0; j < kVelocitySupportDirections && !poly.empty(); ++j) {
      const double th = 2 * kPi * j / kVelocitySupportDirections;
      const double cs = std::cos(th), sn = std::sin(th);
      const Vec3 v = cs * e1 + sn * e2;
      auto f = [&](double lambda) { return h(v + lambda * n) - lambda * c; };
      if (in_plane) {  // h(v + lambda n) − lambda c does not depend on lambda: no search
        clip_poly(poly, cs, sn, f(0) + margin * (1 + std::abs(f(0))));
        continue;
      }
      const double best = minimize_over_lambda(f, &guess);
      clip_poly(poly, cs, sn, best + margin * (1 + std::abs(best)));
    }
  }
  if (cuts)
    for (const HalfSpace& hs : *cuts) {
      if (poly.empty()) break;
      // w . (origin + x e1 + y e2) <= c in the plane's frame
      const double a = hs.normal.dot(e1), b = hs.normal.dot(e2), rhs = hs.offset - hs.normal.dot(origin);
      const double len = std::hypot(a, b);
      if (len <= 1e-12) {  // w along n: the whole plane lies on one side
        if (rhs < -margin) return {};
        continue;
      }
      clip_poly(poly, a / len, b / len, rhs / len + margin);
    }
  if (poly.empty()) return {};
  const FaceChart& chart = g.charts[fi];
  Points2 pts;
  for (const auto& q : poly) pts.push_back(chart.project(Vec3(origin + q[0] * e1 + q[1] * e2)));
  // The chart image of the double polygon, rounded outward by the margin (which also covers the rounding of
  // the double clipping above), on the face.
  return clip(snap_outward(minkowski_outward(pts, disk_offsets(chart, n, margin)), chart, n, scale),
              g.face_polygon[fi]);
}

Support ball_support(const Vec3& center, double radius) {
  return [center, radius](const Vec3& w) { return center.dot(w) + radius * w.norm(); };
}

// The spiral region of one start x0 and one p* (docs/verifier.md "Spiral regions"): every point y of a path
// whose velocity stays within theta of p* − x has angle(y − p*, x0 − p*) <= tan(theta) ln(r0 / |y − p*|), r0
// = |x0 − p*|: the solid of revolution about the axis u = (x0 − p*) / r0 bounded by the logarithmic spiral
// r = r0 e^(−psi / tan theta), psi in [0, pi] (with the ball r <= r0 e^(−pi / tan theta) about p*). Its
// support in a unit direction w at angle gamma from u is the max over psi of p* . w + r0 e^(−psi / tan theta)
// cos(psi − gamma), whose derivative in psi has the sign of −cos(psi − gamma − theta): for gamma <= knee =
// pi/2 − theta the max is at psi = 0, the tip x0 (x0 . w, whatever p* is); beyond the knee at psi = gamma −
// knee, where it is p* . w + r0 e^(−(gamma − knee) / tan theta) sin(theta), decreasing in gamma.
double spiral_factor(double gamma, double theta) {
  const double knee = kPi / 2 - theta;
  return std::max(std::exp(-std::max(0.0, gamma - knee) / std::tan(theta)) * std::sin(theta),
                  std::exp(-kPi / std::tan(theta)));
}

// The same support relative to the tip: (support − x0 . w) / r0 = G(gamma) − cos(gamma), G = the factor
// above with cos(gamma) below the knee. It is 0 up to the knee and increasing on [knee, pi − knee] (its
// derivative sin(gamma) − cos(theta) e^(−(gamma − knee) / tan theta) is >= 0 there, as sin(gamma) >=
// sin(knee) = cos(theta)). Returns an upper bound of its max over gamma in [lo, hi] (the translation of p*
// cancels: only r0 and the angle matter).
double spiral_excess(double lo, double hi, double theta) {
  const double knee = kPi / 2 - theta, top = kPi - knee, T = std::tan(theta);
  lo = std::clamp(lo, 0.0, kPi);
  hi = std::clamp(hi, 0.0, kPi);
  if (hi <= knee) return 0;
  auto excess = [&](double g) { return std::exp(-(g - knee) / T) * std::sin(theta) - std::cos(g); };
  double best = excess(std::min(hi, top));  // the increasing part's largest value
  if (hi > top)                             // beyond top: each term bounded on its own
    best = std::max(best, std::exp(-(std::max(lo, top) - knee) / T) * std::sin(theta) - std::cos(hi));
  best = std::max(best, std::exp(-kPi / T) - std::cos(hi));  // the ball r <= r0 e^(−pi / tan theta)
  return std::max(0.0, best);
}
// A convex source piece (polygon, segment or point, 3-D doubles) cut by the plane n . x = c: the parts on
// either side, each grown across the plane by `margin` (their union covers the piece).
std::pair<std::vector<Vec3>, std::vector<Vec3>> cut(const std::vector<Vec3>& piece, const Vec3& n, double c,
                                                    double margin) {
  if (piece.size() >= 3)
    return {clip_halfspace(piece, n, c + margin), clip_halfspace(piece, -n, -c + margin)};
  if (piece.size() == 2) {
    const double s0 = n.dot(piece[0]) - c, s1 = n.dot(piece[1]) - c;
    if (s0 == s1) return {piece, {}};
    const double t = std::clamp(-s0 / (s1 - s0), 0.0, 1.0);
    const double len = (piece[1] - piece[0]).norm();
    const double dt = len > 0 ? margin / len : 0;
    const Vec3 lo = piece[0] + std::max(0.0, t - dt) * (piece[1] - piece[0]);
    const Vec3 hi = piece[0] + std::min(1.0, t + dt) * (piece[1] - piece[0]);
    return {{piece[0], hi}, {lo, piece[1]}};
  }
  return {piece, {}};
}

// Distance from q (in the plane) to the convex planar polygon `poly` with plane normal n, whatever the
// polygon's orientation about n: 0 inside.
double distance_in_plane(const std::vector<Vec3>& poly, const Vec3& n, const Vec3& q) {
  if (poly.size() < 3) return distance_to_convex_polygon(q, poly, n);
  Vec3 area = Vec3::Zero();  // Newell: robust to collinear vertices
  for (std::size_t i = 0; i < poly.size(); ++i) area += poly[i].cross(poly[(i + 1) % poly.size()]);
  const double turn = n.dot(area);
  return distance_to_convex_polygon(q, poly, turn < 0 ? Vec3(-n) : n);
}

// Where the spiral bound of a piece is its tips alone: directions w with angle(w, a) + axis_error below the
// knee pi/2 − theta (spiral_factor).
struct TipCone {
  bool active = false;
  Vec3 a = Vec3::UnitZ();
  double axis_error = 0, theta = 0;
};

// The flight region of a piece meets face f's plane only in the piece's own points there: the piece lies
// on the closed back side of the plane (n . x <= c) and n is strictly inside the tip cone, so the spiral
// bound's support is the piece's own near n (by continuity) and the region's exposed face in direction n is
// the piece's (its points on the plane, where the robot already is: the edges and vertices they lie on are
// reached and seed their faces, may_enter). No landing on f.
bool touches_only_at_tips(const Face& f, const std::vector<Vec3>& piece, const TipCone& tips) {
  if (!tips.active) return false;
  if (angle_between(f.normal, tips.a) + tips.axis_error + kVelocityTipMargin > kPi / 2 - tips.theta)
    return false;
  for (const Vec3& x : piece)
    if (f.normal.dot(x) > f.offset) return false;
  return true;
}

// One piece's reach (see the file comment) into `regions` / `lowers`.
void fly_piece(const ReachedSet::Impl& g, const std::vector<Vec3>& piece, int source_face,
               const VelocitySpring& m, double r_lower, std::map<int, std::vector<Polygon2>>* regions,
               std::map<int, Points2>* lowers) {
  const double scale = g.cspace->scale();
  const double eps = m.u.eps_s;
  const Vec3& p = m.p;
  double rmax = 0;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& x : piece) {
    const double r = (x - p).norm();
    rmax = std::max(rmax, r);
    if (r > 0) mean += (x - p) / r;
  }
  const double ball = std::min(rmax + 2 * eps, m.reach) * (1 + kSlack) + kSlack * scale;
  std::vector<Support> bounds = {ball_support(p, ball)};
  std::vector<int> skip_faces;
  TipCone tips;
  if (r_lower > eps * (1 + 1e-6) + kSlack * scale && mean.norm() > 1e-9 * static_cast<double>(piece.size())) {
    // Tube: conv(piece ∪ B(p, eps)) ⊕ ball(rho).
    const double rho = spring_spiral_deviation(m.u.theta_v) * (rmax + eps) * (1 + kSlack) + kSlack * scale;
    bounds.push_back([piece, p, eps, rho](const Vec3& w) {
      double best = p.dot(w) + eps * (1 + kSlack) * w.norm();
      for (const Vec3& x : piece) best = std::max(best, x.dot(w));
      return best + rho * w.norm();
    });
    // Forward cone: piece + cone(−a, angle), truncated beyond the scene.
    const Vec3 a = mean.normalized();
    double sigma = 0;
    for (const Vec3& x : piece) sigma = std::max(sigma, angle_between(a, x - p));
    const double axis_error = sigma * (1 + kSlack) + std::asin(std::min(1.0, eps / r_lower)) * (1 + kSlack);
    const double angle = m.u.theta_v + axis_error + 2 * kSlack;
    // Spiral regions over the piece and B(p, eps): x0 − p* is within axis_error of a (x0 − p is within sigma
    // of a, and p* − p turns it by at most asin(eps / |x0 − p|)), so gamma lies within axis_error of
    // angle(w, a). Where gamma may pass the knee, the spiral part is bounded with p* . w <= p . w + eps |w|,
    // r0 <= R + eps and the least gamma; otherwise only the tips count (the piece's own support).
    if (m.u.theta_v > 0) {
      tips = {true, a, axis_error, m.u.theta_v};
      const double theta = m.u.theta_v, r0 = (rmax + eps) * (1 + kSlack);
      bounds.push_back([piece, p, a, eps, theta, r0, axis_error](const Vec3& w) {
        const double norm = w.norm();
        double tip = -std::numeric_limits<double>::infinity();
        for (const Vec3& x : piece) tip = std::max(tip, x.dot(w));
        if (norm == 0) return tip;
        const double gamma_a = angle_between(w, a), knee = kPi / 2 - theta;
        if (gamma_a + axis_error + kSlack <= knee) return tip;
        const double gamma = std::max(0.0, gamma_a - axis_error - kSlack);
        // Two bounds of the union's support, both sound; the lesser: translated by the p* error, or relative
        // to the tips (spiral_excess over the gamma range).
        const double spiral =
            p.dot(w) + norm * (eps * (1 + kSlack) + r0 * spiral_factor(gamma, theta) * (1 + kSlack) + kSlack);
        const double relative =
            tip +
            norm * (r0 * spiral_excess(gamma, gamma_a + axis_error + kSlack, theta) * (1 + kSlack) + kSlack);
        return std::min(std::max(tip, spiral), relative);
      });
    }
    if (angle + kVelocityPointedMargin < kPi / 2) {
      const FlightCone cone = flight_cone(-a, angle, scale);
      // A face whose plane holds the piece while every ray of the cone points strictly to one side of it
      // meets the flight only in the piece itself, where the robot already is (edges and vertices seed
      // their faces themselves, may_enter): not a landing.
      for (std::size_t fi = 0; fi < g.cspace->faces().size(); ++fi) {
        const Face& face = g.cspace->faces()[fi];
        bool on_plane = true;
        for (const Vec3& x : piece)
          on_plane = on_plane && std::abs(face.normal.dot(x) - face.offset) <= 1e-9 * scale;
        if (!on_plane) continue;
        int above = 0, below = 0;
        for (const Vec3& r : cone.rays) {
          const double s = face.normal.dot(r) / r.norm();
          above += s > 1e-9 ? 1 : 0;
          below += s < -1e-9 ? 1 : 0;
        }
        if (above == static_cast<int>(cone.rays.size()) || below == static_cast<int>(cone.rays.size()))
          skip_faces.push_back(static_cast<int>(fi));
      }
      bounds.push_back([piece, cone](const Vec3& w) {
        double best = -std::numeric_limits<double>::infinity(), ray = 0;
        for (const Vec3& x : piece) best = std::max(best, x.dot(w));
        for (const Vec3& r : cone.rays) ray = std::max(ray, cone.far * r.dot(w));
        return best + ray;
      });
    }
  }
  const int nf = static_cast<int>(g.cspace->faces().size());
  for (int fi = 0; fi < nf; ++fi) {
    if (fi == source_face || std::find(skip_faces.begin(), skip_faces.end(), fi) != skip_faces.end())
      continue;
    if (touches_only_at_tips(g.cspace->faces()[fi], piece, tips)) continue;
    const Points2 section = support_section(g, fi, bounds, false, &m.bounds);
    if (section.size() < 3 && !section.empty()) {
      // A segment or point on the plane of a piece lying in that plane is the piece itself (the robot leaving
      // it is already there; edges and vertices seed their faces themselves, may_enter).
      const Face& face = g.cspace->faces()[fi];
      bool on_plane = true;
      for (const Vec3& x : piece)
        on_plane = on_plane && std::abs(face.normal.dot(x) - face.offset) <= 1e-9 * scale;
      if (on_plane) continue;
    }
    if (section.size() >= 3)
      (*regions)[fi].push_back(to_polygon(section));
    else if (!section.empty() && !lowers->count(fi))
      (*lowers)[fi] = section;
  }
}

// Cuts the convex source `poly` (3-D doubles) into pieces of angular radius <= kVelocityMaxSpread about their
// mean direction from `center` and of radial extent R_max − R_lower <= radial_limit, where R_lower = the
// least a . (x − center) over the piece's vertices (a lower bound of |x − center| on the piece: a . (x −
// center) is linear), and calls fly(piece, R_lower) for each; at most kVelocityMaxPieces pieces (past the
// budget the rest is taken as it is: sound, looser). Pieces overlap by `margin` across every cut.
void split_source(const std::vector<Vec3>& poly, const Vec3& center, double eps, double radial_limit,
                  double margin, const std::function<void(const std::vector<Vec3>&, double)>& fly) {
  std::vector<std::vector<Vec3>> work = {poly};
  int pieces = 0;
  while (!work.empty()) {
    std::vector<Vec3> piece = std::move(work.back());
    work.pop_back();
    if (piece.empty()) continue;
    Vec3 mean = Vec3::Zero();
    double rmax = 0;
    for (const Vec3& x : piece) {
      const double r = (x - center).norm();
      rmax = std::max(rmax, r);
      if (r > 0) mean += (x - center) / r;
    }
    const Vec3 a = mean.norm() > 0 ? Vec3(mean.normalized()) : Vec3::UnitZ();
    double smin = std::numeric_limits<double>::infinity(), smax = -smin, sigma = 0;
    std::size_t widest = 0;
    for (std::size_t i = 0; i < piece.size(); ++i) {
      smin = std::min(smin, a.dot(piece[i] - center));
      smax = std::max(smax, a.dot(piece[i] - center));
      const double ang = angle_between(a, piece[i] - center);
      if (ang > sigma) {
        sigma = ang;
        widest = i;
      }
    }
    const bool budget = pieces + static_cast<int>(work.size()) + 2 <= kVelocityMaxPieces;
    if (budget && piece.size() >= 2 && smin > eps) {
      Vec3 b = (piece[widest] - center) - a.dot(piece[widest] - center) * a;
      if (sigma > kVelocityMaxSpread && b.norm() > 0) {  // cut through the center along a, across the widest
        b.normalize();
        auto [l, r] = cut(piece, b, b.dot(center), margin);
        if (!l.empty() && !r.empty()) {
          work.push_back(std::move(l));
          work.push_back(std::move(r));
          continue;
        }
      }
      if (rmax - smin > radial_limit) {  // cut across a at the middle level
        auto [l, r] = cut(piece, a, a.dot(center) + 0.5 * (smin + smax), margin);
        if (!l.empty() && !r.empty()) {
          work.push_back(std::move(l));
          work.push_back(std::move(r));
          continue;
        }
      }
    }
    ++pieces;
    fly(piece, std::max(0.0, smin) * (1 - kSlack));
  }
}

}  // namespace

std::vector<FlightHit> velocity_fly(const ReachedSet::Impl& g, const std::vector<Point3>& src,
                                    int source_face, const VelocitySpring& m) {
  const double scale = g.cspace->scale();
  const double delta = spring_spiral_deviation(m.u.theta_v);
  const double margin = kSlack * scale;
  const Vec3& p = m.p;
  std::map<int, std::vector<Polygon2>> regions;
  std::map<int, Points2> lowers;
  // Cut until each piece has angular radius <= kVelocityMaxSpread about its mean direction from p and a
  // tube growth delta (R_max − R_lower) <= eps / 4.
  std::vector<Vec3> poly;
  for (const Point3& x : src) poly.push_back(to_vec(x));
  const double cut_eps = cutting_eps(m.u, scale);
  const double radial_limit = delta > 0 ? cut_eps / (4 * delta) : std::numeric_limits<double>::infinity();
  split_source(poly, p, cut_eps, radial_limit, margin, [&](const std::vector<Vec3>& piece, double r_lower) {
    fly_piece(g, piece, source_face, m, r_lower, &regions, &lowers);
  });
  std::vector<FlightHit> out;
  for (auto& [face, polys] : regions) {
    FlightHit hit;
    hit.face = face;
    hit.region = union_of(polys, g.charts[face].cell);
    out.push_back(std::move(hit));
  }
  for (auto& [face, lower] : lowers) {
    if (regions.count(face)) continue;
    FlightHit hit;
    hit.face = face;
    hit.lower = std::move(lower);
    out.push_back(std::move(hit));
  }
  return out;
}

namespace {

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

// The slide from one entry piece (file comment), before the direction-cone rule (slide_piece).
ChartRegion slide_piece_bounds(const ReachedSet::Impl& g, int fi, const Points2& part,
                               const VelocitySpring& m, Points2* lower) {
  const CSpace& c = *g.cspace;
  const Face& face = c.faces()[fi];
  const FaceChart& chart = g.charts[fi];
  const double eps = m.u.eps_s, scale = c.scale();
  const double margin = kSlack * scale;
  const SlidePlane plane = slide_plane(face, m);
  const Vec3& center = plane.center;  // p'
  const double zone = plane.zone;     // beta(d) = pi/2 for d <= h* tan(theta_v)
  lower->clear();
  std::vector<Vec3> in_plane;  // entries − p', in the plane
  double dmax = 0;
  Vec3 mean = Vec3::Zero();
  for (const Point2& q : part) {
    const Vec3 v = chart.lift_double(q) - center;
    in_plane.push_back(v - face.normal.dot(v) * face.normal);
    dmax = std::max(dmax, in_plane.back().norm());
    if (in_plane.back().norm() > 0) mean += in_plane.back() / in_plane.back().norm();
  }
  std::vector<Vec3> lifted_part;
  for (const Point2& q : part) lifted_part.push_back(chart.lift_double(q));
  const double dmin = distance_in_plane(lifted_part, face.normal, center) * (1 - kSlack);
  const double d0 = dmax + eps;  // >= |e − p*'|
  // tan(beta(s)) / s, decreasing in s for s > zone.
  auto integrand = [&](double s) {
    const double sb = std::min(1.0, plane.sin_beta(s));
    return sb >= 1 ? std::numeric_limits<double>::infinity() : std::tan(std::asin(sb)) / s;
  };
  // L(d0) from upper sums of Psi on a grid: on each cell d sin Psi(d) <= d_hi sin(min(Psi(d_lo), pi/2)).
  double lateral = zone;
  if (d0 > zone) {
    constexpr int kCells = 400;
    double psi = 0, d_hi = d0;
    for (int j = 1; j <= kCells; ++j) {
      const double d_lo = std::max(zone * (1 + 1e-9), d0 - (d0 - zone) * j / kCells);
      if (d_lo >= d_hi) break;
      psi += integrand(d_lo) * (d_hi - d_lo);
      if (psi * (1 + kSlack) >= kPi / 2) {
        lateral = std::max(lateral, d_hi);
        break;
      }
      lateral = std::max(lateral, d_hi * std::sin(psi * (1 + kSlack)));
      d_hi = d_lo;
    }
  }
  const Point2 c2 = chart.project(center);
  // Tube: conv(part ∪ disk(p', eps)) ⊕ disk(L), within max(d0, zone) + eps of p' and within the reach bound.
  Points2 pts = part;
  for (const Vector2& o : disk_offsets(chart, face.normal, eps * (1 + kSlack))) pts.push_back(c2 + o);
  Points2 tube =
      clip(minkowski_outward(pts, disk_offsets(chart, face.normal, lateral * (1 + kSlack) + margin)),
           g.face_polygon[fi]);
  const double reach = std::max(d0, zone) * (1 + kSlack) + eps * (1 + kSlack) + margin;
  tube = clip(tube, minkowski_outward({c2}, disk_offsets(chart, face.normal, reach)));
  if (!tube.empty()) {
    const Points2 bound = velocity_reach_section(g, fi, m);
    tube = bound.empty() ? bound : clip(tube, bound);
  }
  if (tube.size() < 3) {
    *lower = tube;
    return ChartRegion();
  }
  ChartRegion out(to_polygon(tube), g.charts[fi].cell);
  if (dmin <= eps * (1 + 1e-6) + margin || mean.norm() == 0) return out;
  const Vec3 axis = mean.normalized();
  const Vec3 axis_perp = face.normal.cross(axis);
  double spread = 0;
  for (const Vec3& w : in_plane)
    spread = std::max(spread, std::abs(std::atan2(w.dot(axis_perp), w.dot(axis))));
  const double shift = std::asin(std::min(1.0, eps / dmin)) * (1 + kSlack) + kSlack;
  // In-plane spiral regions (docs/verifier.md "Spiral regions"): while d >= d_f > zone the in-plane angle is
  // at most beta(d_f), so the path lies in the spiral region of angle beta(d_f) from its entry about p*', or
  // within d_f of p*' once it gets there (d never grows back past d_f). Each floor d_f gives a convex bound;
  // the region lies in all of them, so the least support is a bound.
  {
    const double axis_error = spread * (1 + kSlack) + shift;
    struct Floor {
      double d, beta;
    };
    std::vector<Floor> floors;
    constexpr int kFloors = 8;
    for (int k = 0; k < kFloors; ++k) {
      const double t = static_cast<double>(k) / kFloors;
      const double d_f = zone * (1 + 1e-3) + (d0 - zone) * t * t;
      const double sb = plane.sin_beta(d_f);
      if (d_f <= 0 || sb >= std::sin(kPi / 2 - kVelocityPointedMargin)) continue;
      floors.push_back({d_f, std::asin(sb) * (1 + kSlack) + kSlack});
    }
    if (!floors.empty()) {
      const Vec3 n = face.normal;
      const double c_plane = face.offset;
      const Vec3 pc = center;
      const double r0 = d0 * (1 + kSlack);
      const double d_lo = std::max(0.0, dmin - eps);  // <= |e − p*'| for every entry e and p*'
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
        return ChartRegion();
      }
      ChartRegion tight = out;
      tight.intersection(to_polygon(bound));
      if (!tight.is_empty()) out = std::move(tight);  // else a lower-dimensional meet: keep the tube (sound)
    }
  }
  // Forward wedge ∪ the disk d <= d_w (about p*', so within d_w + eps of p').
  const double d_w = std::max(0.5 * dmin, 1.5 * zone);
  const double beta_w = std::asin(std::min(1.0, plane.sin_beta(d_w))) * (1 + kSlack) + kSlack;
  const double half = beta_w + spread * (1 + kSlack) + shift;
  if (half + kVelocityPointedMargin >= kPi / 2) return out;
  // Rays with axis component 1 (as flight_cone's): the truncated wedge reaches `far` along the axis, past
  // every face point (all lie within `scale` of the part), whatever the half-angle.
  const double far = 2 * scale;
  Points2 wedge_pts;
  for (const Point2& q : part) {
    wedge_pts.push_back(q);
    for (const double sgn : {-1.0, 1.0}) {
      const Vec3 dir = -(axis + sgn * std::tan(half) * axis_perp);
      wedge_pts.push_back(q + chart.project_direction(far * dir));
    }
  }
  ChartRegion allowed;
  const Points2 wedge = clip(convex_hull(wedge_pts), g.face_polygon[fi]);
  if (wedge.size() >= 3) allowed.join(to_polygon(wedge), g.charts[fi].cell);
  const Points2 inner =
      clip(minkowski_outward({c2}, disk_offsets(chart, face.normal, (d_w + eps) * (1 + kSlack) + margin)),
           g.face_polygon[fi]);
  if (inner.size() >= 3) allowed.join(to_polygon(inner), g.charts[fi].cell);
  out.intersection(allowed);
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

Points2 velocity_reach_section(const ReachedSet::Impl& g, int fi, const VelocitySpring& m) {
  return support_section(g, fi, {ball_support(m.p, m.reach)}, false, &m.bounds);
}

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
    face_frame(face.normal, &e1, &e2);
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

}  // namespace cmt::fp

namespace cmt {

double spring_spiral_deviation(double theta_v) {
  if (theta_v <= 0) return 0;
  const double T = std::tan(theta_v);
  return std::max(std::exp(-theta_v / T) * std::sin(theta_v), std::exp(-fp::kPi / (2 * T)));
}

double velocity_reach_bound(const CSpace& c, const ReachedSet& start, const Vec3& p, const Uncertainty& u) {
  const double eps = u.eps_s, T = std::tan(u.theta_v), cos_v = std::cos(u.theta_v);
  double v = 0;  // >= |x − p*| for every point of the motion so far
  for (const ReachedPiece& piece : start.pieces())
    for (const Vec3& q : piece.polygon) v = std::max(v, (q - p).norm() + eps);
  // A zone can raise the bound only on an atom the robot can reach at all, i.e. one with a point within v of
  // p*; iterate until no zone raises it (each round takes in at least one more atom, or stops).
  const std::size_t nf = c.faces().size(), ne = c.edges().size();
  std::vector<char> used(nf + ne, 0);
  for (bool grew = true; grew;) {
    grew = false;
    for (std::size_t i = 0; i < nf; ++i) {
      if (used[i]) continue;
      const Face& f = c.faces()[i];
      const double depth = f.offset - f.normal.dot(p);
      const Vec3 center = p + depth * f.normal;
      const double inplane = fp::distance_in_plane(f.polygon, f.normal, center);
      const double h = std::abs(depth) + eps;
      if (std::hypot(depth, inplane) > v + eps) continue;  // not reachable within the bound
      if (inplane > h * T + eps) continue;                 // the zone about p*' misses the face
      used[i] = 1;
      if (h / cos_v > v) {
        v = h / cos_v;
        grew = true;
      }
    }
    for (std::size_t i = 0; i < ne; ++i) {
      if (used[nf + i]) continue;
      const Edge& e = c.edges()[i];
      const Vec3 d = e.b - e.a;
      const double len = d.norm();
      const double t = (p - e.a).dot(d) / (len * len);
      const double perp = (p - (e.a + t * d)).norm();
      const double gap = std::max({0.0, -t * len, (t - 1) * len});  // from the projection to the segment
      if (std::hypot(perp, gap) > v + eps) continue;
      if (gap > (perp + eps) * T + eps) continue;
      used[nf + i] = 1;
      if ((perp + eps) / cos_v > v) {
        v = (perp + eps) / cos_v;
        grew = true;
      }
    }
  }
  return (v + eps) * (1 + fp::kSlack) + fp::kSlack * c.scale();
}

}  // namespace cmt

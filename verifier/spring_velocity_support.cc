// Convex-geometry tools of the velocity-form spring model (verifier/internal/spring_velocity_support.h).
#include "verifier/internal/spring_velocity_support.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <utility>

#include "models/polygon_distance.h"
#include "verifier/internal/spring_flight.h"

namespace cmt::face_geometry {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSlack = kVelocitySlack;
// Grid of snap_outward, x scene scale.
constexpr double kVelocitySnap = 1e-7;
// Relative error bound of a support bound h(w) − lambda c evaluated in doubles, against the size of its
// terms: the supports sum a few dot products of scene points with w (each within a few units in the last
// place of |x| |w|, u = 1.1e-16), so 1e-12 (about 9,000 u) holds with a wide margin. The position-dependent
// part of a section's margin: a task far from the world origin has larger terms, not larger sets.
constexpr double kSupportRoundingRelative = 1e-12;

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

}  // namespace

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
// A lower bound of the minimum over [a, b] of a convex f sampled at a < x1 < x2 < b: beyond each sample the
// chords through its neighbours, extended, lie below f (on [a, x1] and [x2, b] the chord x1 x2; on [x1, x2]
// the greater of the chords a x1 and x2 b, least where they cross or at an end).
double convexity_lower_bound(double a, double fa, double x1, double f1, double x2, double f2, double b,
                             double fb) {
  const double s12 = (f2 - f1) / (x2 - x1);
  const double outer = std::min({f1 - s12 * (x1 - a), f2 + s12 * (b - x2), f1, f2});
  const double sl = x1 > a ? (f1 - fa) / (x1 - a) : 0, sr = b > x2 ? (fb - f2) / (b - x2) : 0;
  const auto left = [&](double x) { return f1 + sl * (x - x1); };   // chord a x1, extended right
  const auto right = [&](double x) { return f2 + sr * (x - x2); };  // chord x2 b, extended left
  double inner = std::min(std::max(left(x1), right(x1)), std::max(left(x2), right(x2)));
  if (sl != sr) {
    const double x = (f2 - sr * x2 - f1 + sl * x1) / (sl - sr);
    if (x > x1 && x < x2) inner = std::min(inner, left(x));
  }
  return std::min(outer, inner);
}

double minimize_over_lambda(const std::function<double(double)>& f, double* guess, double value_tolerance) {
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
  double a = lo, b = hi, fa = f_lo, fb = f_hi;
  double x1 = b - r * (b - a), x2 = a + r * (b - a), f1 = f(x1), f2 = f(x2);
  while (b - a > kLambdaResolution) {
    if (value_tolerance > 0 &&
        std::min({best, f1, f2}) - convexity_lower_bound(a, fa, x1, f1, x2, f2, b, fb) <= value_tolerance)
      break;
    if (f1 <= f2) {
      b = x2, fb = f2, x2 = x1, f2 = f1, x1 = b - r * (b - a), f1 = f(x1);
    } else {
      a = x1, fa = f1, x1 = x2, f1 = f2, x2 = a + r * (b - a), f2 = f(x2);
    }
  }
  for (const auto& [x, fx] : {std::pair{x1, f1}, std::pair{x2, f2}})
    if (fx < best) best = fx, *guess = x;
  return best;
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
Points2 support_section(const ReachedSet::Impl& g, int fi, const std::vector<Support>& sets, bool in_plane,
                        const std::vector<HalfSpace>* cuts) {
  const Face& face = g.cspace->faces()[fi];
  const Vec3& n = face.normal;
  const double c = face.offset, scale = g.cspace->scale();
  const double margin = kSlack * scale;
  // Every point the sets' supports take (sources on the scene's atoms, their cones and disks, within a few
  // scales of every face point) has norm at most `reach`.
  double face_reach = 0;
  for (const Vec3& q : face.polygon) face_reach = std::max(face_reach, q.norm());
  const double reach = face_reach + 4 * scale;
  // The margin of a bound at lambda: the supports' own slack (relative to the scene) and the rounding of
  // terms of size reach |v + lambda n| + |lambda c| (relative to their size, so far from the origin).
  auto bound_margin = [&](double lambda) {
    const double l = std::abs(lambda);
    return margin + kSupportRoundingRelative * (reach * (1 + l) + l * std::abs(c));
  };
  for (const Support& h : sets)
    if (h(n) < c - bound_margin(1) || -h(-n) > c + bound_margin(1)) return {};  // a set lies on one side
  Vec3 e1, e2;
  plane_frame(n, &e1, &e2);
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
        clip_poly(poly, cs, sn, f(0) + bound_margin(0));
        continue;
      }
      // Any lambda gives a sound bound: the least found, at lambda = guess, within a margin of the least.
      const double best = minimize_over_lambda(f, &guess, margin);
      clip_poly(poly, cs, sn, best + bound_margin(guess));
    }
  }
  if (cuts)
    for (const HalfSpace& hs : *cuts) {
      if (poly.empty()) break;
      // w . (origin + x e1 + y e2) <= c in the plane's frame
      const double a = hs.normal.dot(e1), b = hs.normal.dot(e2), rhs = hs.offset - hs.normal.dot(origin);
      const double len = std::hypot(a, b);
      const double rounding = kSupportRoundingRelative * (reach + std::abs(hs.offset));
      if (len <= 1e-12) {  // w along n: the whole plane lies on one side
        if (rhs < -margin - rounding) return {};
        continue;
      }
      clip_poly(poly, a / len, b / len, (rhs + rounding) / len + margin);
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

// Cuts the convex source `poly` (3-D doubles) into pieces of angular radius <= kVelocityMaxSpread about their
// mean direction from `center` and of radial extent R_max − R_lower <= radial_limit, where R_lower = the
// least a . (x − center) over the piece's vertices (a lower bound of |x − center| on the piece: a . (x −
// center) is linear), and calls take(piece, R_lower) for each; at most kVelocityMaxPieces pieces (past the
// budget the rest is taken as it is: sound, looser). Pieces overlap by `margin` across every cut.
void split_source(const std::vector<Vec3>& poly, const Vec3& center, double eps, double radial_limit,
                  double margin, const std::function<void(const std::vector<Vec3>&, double)>& take) {
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
    take(piece, std::max(0.0, smin) * (1 - kSlack));
  }
}

}  // namespace cmt::face_geometry

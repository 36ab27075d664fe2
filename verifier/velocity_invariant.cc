// Invariant half-spaces of a velocity-model spring motion (docs/verifier.md, "Invariant half-spaces").
//
// Lemma. Let w be a unit vector and c0 a level with w . x0 <= c0 for every start point. If every admissible
// motion direction v at every point x with c0 <= w . x <= c0 + h (h > 0) has w . v <= 0, no path of the
// motion ever has w . x > c0: let t1 be a time with w . x(t1) > c0 and t0 the last time before it with w . x
// = c0; just after t0 the path lies in the slab, where w . x does not grow (almost everywhere), a
// contradiction. The same holds with the slab replaced by the whole region w . x >= c0 (used for the search
// below, where that region shrinks as c0 grows, so the test is monotone).
//
// The motion directions of the velocity model (internal/spring_velocity.h): in free space the velocity F
// lies within theta_v of p* − x (|p* − p| <= eps_s); sliding on a face with normal n it is the tangential
// part F − (F . n) n of such an F, so w . v = F . (w − (w . n) n); along an edge with unit direction e it is
// ± e with the sign of F . e, so w . v = (F . e) (w . e) = F . ((w . e) e); at rest it is 0. Each case is
// "F . u <= 0 for every F within theta_v of p* − x" for a vector u (u = 0: nothing to test), i.e. angle(u, x
// − p*) <= pi/2 − theta_v, which holds when angle(u, x − p) + asin(eps_s / |x − p|) <= pi/2 − theta_v. Over a
// convex set of points x the angle to u is largest at a vertex (its sublevel sets {x: angle(u, x − p) <=
// alpha}, alpha < pi/2, are convex cones about p), and |x − p| >= w . (x − p) >= c0 − w . p on the region.
// Free points of the region lie in the reach ball, where angle(w, x − p) <= acos((c0 − w . p) / reach).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "verifier/internal/spring_velocity.h"
#include "verifier/spring_projection.h"

namespace cmt {
namespace {

constexpr double kPi = std::numbers::pi;
// Angular margin (rad) by which every sign test must hold (covers the rounding of the doubles).
constexpr double kInvariantAngleMargin = 1e-6;
// Slab thickness h of the lemma, x scene scale.
constexpr double kInvariantSlab = 1e-6;
// Relative slack on levels computed in floating point.
constexpr double kInvariantSlack = 1e-9;

struct Test {
  const CSpace& c;
  Vec3 p;
  double theta = 0, eps = 0, reach = 0;

  // angle(u, x − p) + asin(eps / d_min) <= pi/2 − theta − margin at every point of `pts` (u != 0).
  bool never_along(const Vec3& u, const std::vector<Vec3>& pts, double d_min) const {
    const double limit = kPi / 2 - theta - std::asin(std::min(1.0, eps / d_min)) - kInvariantAngleMargin;
    for (const Vec3& x : pts)
      if (face_geometry::angle_between(u, x - p) > limit) return false;
    return true;
  }

  // The hypothesis of the lemma on the region lo <= w . x <= hi (hi may be +inf).
  bool holds(const Vec3& w, double lo, double hi) const {
    const double a0 = (lo - w.dot(p)) * (1 - kInvariantSlack) - kInvariantSlack * c.scale();
    if (a0 <= eps) return false;  // p* may lie in the region: the pull may point anywhere
    if (std::acos(std::min(1.0, a0 / reach)) + theta + std::asin(std::min(1.0, eps / a0)) >
        kPi / 2 - kInvariantAngleMargin)
      return false;  // free points
    const double tol = kInvariantSlack * c.scale();
    for (const Face& f : c.faces()) {
      const Vec3 u = w - w.dot(f.normal) * f.normal;
      if (u.norm() <= 1e-12) continue;  // sliding on f does not move along w
      std::vector<Vec3> q = face_geometry::clip_halfspace(f.polygon, -w, -lo + tol);
      if (std::isfinite(hi)) q = face_geometry::clip_halfspace(q, w, hi + tol);
      if (!q.empty() && !never_along(u, q, a0)) return false;
    }
    for (const Edge& e : c.edges()) {
      const Vec3 d = (e.b - e.a).normalized();
      const Vec3 u = w.dot(d) * d;
      if (u.norm() <= 1e-12) continue;
      // the segment's part in the region
      const double sa = w.dot(e.a), sb = w.dot(e.b);
      double t0 = 0, t1 = 1;
      if (sa != sb) {
        const double ta = (lo - tol - sa) / (sb - sa),
                     tb = ((std::isfinite(hi) ? hi + tol : 1e300) - sa) / (sb - sa);
        t0 = std::max(0.0, std::min(ta, tb));
        t1 = std::min(1.0, std::max(ta, tb));
      } else if (sa < lo - tol || sa > hi + tol) {
        continue;
      }
      if (t0 > t1) continue;
      if (!never_along(u, {e.a + t0 * (e.b - e.a), e.a + t1 * (e.b - e.a)}, a0)) return false;
    }
    return true;
  }
};

}  // namespace

std::vector<HalfSpace> velocity_invariant_half_spaces(const CSpace& c, const ReachedSet& start, const Vec3& p,
                                                      const Uncertainty& u, double reach) {
  std::vector<HalfSpace> out;
  if (u.theta_v >= kPi / 2) return out;
  const Test test{c, p, u.theta_v, u.eps_s, reach};
  std::vector<Vec3> dirs;
  for (int i = 0; i < 3; ++i)
    for (const double s : {1.0, -1.0}) dirs.push_back(s * Vec3::Unit(i));
  for (const double sx : {1.0, -1.0})
    for (const double sy : {1.0, -1.0})
      for (const double sz : {1.0, -1.0}) dirs.push_back(Vec3(sx, sy, sz).normalized());
  const std::vector<ReachedPiece> pieces = start.pieces();
  const double h = kInvariantSlab * c.scale();
  for (const Vec3& w : dirs) {
    double s0 = -std::numeric_limits<double>::infinity();
    for (const ReachedPiece& piece : pieces)
      for (const Vec3& x : piece.polygon) s0 = std::max(s0, w.dot(x));
    if (!std::isfinite(s0)) continue;
    const double top = w.dot(p) + reach;  // the reach ball's extent along w: no bound beyond it
    double level = std::numeric_limits<double>::infinity();
    if (test.holds(w, s0, s0 + h)) {
      level = s0;
    } else if (test.holds(w, top, std::numeric_limits<double>::infinity())) {
      // the least level >= s0 whose whole upper region satisfies the hypothesis (monotone: bisection)
      double lo = s0, hi = top;
      if (test.holds(w, s0, std::numeric_limits<double>::infinity())) hi = s0;
      for (int it = 0; it < 50 && hi - lo > 1e-9 * c.scale(); ++it) {
        const double mid = 0.5 * (lo + hi);
        (test.holds(w, mid, std::numeric_limits<double>::infinity()) ? hi : lo) = mid;
      }
      level = hi;
    }
    level += kInvariantSlack * (c.scale() + std::abs(level));
    if (level < top - 1e-6 * c.scale()) out.push_back({w, level});
  }
  return out;
}

}  // namespace cmt

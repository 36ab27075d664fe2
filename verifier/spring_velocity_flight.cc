// Free flight of the generalized spring under the velocity-form error model
// (verifier/internal/spring_velocity.h; the proofs are in docs/verifier.md, "Velocity-form spring model").
//
// Flight. For a source point x and a fixed p* every reached y lies within delta |x − p*| of seg[x, p*] and in
// the cone x + cone(p* − x, theta_v), and |y − p*| <= |x − p*|. Over a convex source piece X and every p* in
// B(p, eps): y ∈ conv(X ∪ B(p, eps)) ⊕ ball(delta (R + eps)) (seg[x, p*] lies in conv(x, B(p, eps))), y ∈ X +
// cone(−a, theta_v + sigma + asin(eps / R_min)) (p* − x is within asin(eps / |x − p|) of p − x, which is
// within sigma of −a), and |y − p| <= R + 2 eps. All three are convex; their sections by a face plane are
// computed from support functions (support_section), so a piece's reach on a face is a convex polygon.
// Sources are cut into pieces so that sigma and the spread of R stay small (the bounds are per piece).
//
// Servo coast (docs/verifier.md "Servo coast of springs"): a robot that leaves at a sliding velocity u keeps
// it for about the servo's time constant tau; free of contact its position is x0 + a u + (a first-order
// displacement), a in [0, tau] (the rollouts' servo, as for dampers). With `departure` the coast
// displacements tau u of that piece's points (S = conv(0, departure(piece)): a piece's own wedge is
// narrower than the whole source's), each piece's region is grown to region + S: every support
// and every invariant half-space by the support of S. Which faces a flight cannot land on is decided for
// the piece itself, as without the coast.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <vector>

#include "verifier/internal/spring_velocity.h"
#include "verifier/internal/spring_velocity_support.h"

namespace cmt::face_geometry {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kSlack = kVelocitySlack;
// Angular margin (rad) by which a face normal must lie inside a piece's tip cone for touches_only_at_tips.
constexpr double kVelocityTipMargin = 1e-6;
// The directional bounds (tube, forward cone, spiral regions) need the piece farther than eps_s from p
// (relative margin): p* lies within eps_s of p, so the direction from p* to each source point is then
// defined.
constexpr double kSourceClearance = 1e-6;

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
               const VelocitySpring& m, double r_lower, const CoastDeparture& coast,
               std::map<int, std::vector<Polygon2>>* regions, std::map<int, Points2>* lowers) {
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
  if (r_lower > eps * (1 + kSourceClearance) + kSlack * scale &&
      mean.norm() > 1e-9 * static_cast<double>(piece.size())) {
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
  // Servo coast: the region + conv(0, departure) (the file comment).
  const std::vector<Vec3> departure = coast ? coast(piece) : std::vector<Vec3>{};
  std::vector<HalfSpace> clip = m.bounds;
  if (!departure.empty()) {
    auto coast_support = [departure](const Vec3& w) {
      double best = 0;
      for (const Vec3& d : departure) best = std::max(best, d.dot(w));
      return best * (1 + kSlack);
    };
    for (Support& b : bounds) b = [b, coast_support](const Vec3& w) { return b(w) + coast_support(w); };
    for (HalfSpace& h : clip) h.offset += coast_support(h.normal);
  }
  const int nf = static_cast<int>(g.cspace->faces().size());
  for (int fi = 0; fi < nf; ++fi) {
    if (fi == source_face || std::find(skip_faces.begin(), skip_faces.end(), fi) != skip_faces.end())
      continue;
    if (touches_only_at_tips(g.cspace->faces()[fi], piece, tips)) continue;
    const Points2 section = support_section(g, fi, bounds, false, &clip);
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

}  // namespace

std::vector<FlightHit> velocity_fly(const ReachedSet::Impl& g, const std::vector<Point3>& src,
                                    int source_face, const VelocitySpring& m,
                                    const CoastDeparture& departure) {
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
    fly_piece(g, piece, source_face, m, r_lower, departure, &regions, &lowers);
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

}  // namespace cmt::face_geometry

namespace cmt {

double spring_spiral_deviation(double theta_v) {
  if (theta_v <= 0) return 0;
  const double T = std::tan(theta_v);
  return std::max(std::exp(-theta_v / T) * std::sin(theta_v), std::exp(-face_geometry::kPi / (2 * T)));
}

}  // namespace cmt

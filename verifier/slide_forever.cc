// Sliding forever (slide_forever.h; docs/verifier.md "Termination: sliding forever").
#include "verifier/slide_forever.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace cmt {
namespace {

constexpr double kPi = std::numbers::pi;
// Relative slack on zone radii and angles, on the sound side (a zone is only ever widened by it).
constexpr double kZoneSlack = 1e-9;

// A non-progressive slide of this speed bound (> 0; < 0: none) may reach the stop threshold.
bool fast(double speed_per_unit, double ratio, double kappa) {
  return speed_per_unit > 0 && speed_per_unit * ratio >= kappa * (1 - kZoneSlack);
}

double angle_between_unit(const Vec3& a, const Vec3& b) { return std::acos(std::clamp(a.dot(b), -1.0, 1.0)); }

// gamma = asin(|u . e|): the angle between unit u and the plane normal to the unit edge direction e.
double edge_gamma(const Vec3& u, const Vec3& e) { return std::asin(std::min(1.0, std::abs(u.dot(e)))); }

// Unit vectors where the linear function g . v may peak on K = {unit v : v . u >= cos(theta_v), a_i . v <=
// 0}: one candidate per set of active constraints (none; the cap's rim; a plane a_i . v = 0; the rim and a
// plane; both planes, whose great circles meet in +-e).
std::vector<Vec3> peak_candidates(const Vec3& g, const Vec3& u, double theta_v, const Vec3 a[2],
                                  const Vec3& e) {
  std::vector<Vec3> c = {e, -e};
  if (g.norm() > 0) c.push_back(g.normalized());
  Vec3 t = g - g.dot(u) * u;  // toward g on the rim
  if (t.norm() < 1e-12) t = u.unitOrthogonal();
  c.push_back(std::cos(theta_v) * u + std::sin(theta_v) * t.normalized());
  for (int i = 0; i < 2; ++i) {
    if (a[i].norm() == 0) continue;
    const Vec3 n = a[i].normalized();
    const Vec3 g_p = g - g.dot(n) * n, u_p = u - u.dot(n) * n;
    if (g_p.norm() > 0) c.push_back(g_p.normalized());
    const double r = u_p.norm();
    if (r <= 0 || r < std::cos(theta_v)) continue;
    const double eta = std::acos(std::min(1.0, std::cos(theta_v) / r));
    const Vec3 m = u_p / r, side = n.cross(m);
    c.push_back(std::cos(eta) * m + std::sin(eta) * side);
    c.push_back(std::cos(eta) * m - std::sin(eta) * side);
  }
  return c;
}

}  // namespace

double edge_slide_speed(const Vec3& u, double theta_v, const Vec3& n1, double mu1, const Vec3& n2, double mu2,
                        const Vec3& e) {
  // N = G^-1 (−n_j . v) with G the Gram matrix of n1, n2: N_i = −a_i . v.
  const double c = n1.dot(n2), det = 1 - c * c;
  if (det < 1e-9) return edge_nonprogressive_speed(edge_gamma(u, e), theta_v, std::min(mu1, mu2));
  const Vec3 a[2] = {(n1 - c * n2) / det, (n2 - c * n1) / det};
  const double cos_v = std::cos(theta_v), tol = kZoneSlack;
  double best = -std::numeric_limits<double>::infinity();
  for (const double s : {1.0, -1.0}) {
    if (s * u.dot(e) > tol) continue;  // sliding this way raises Phi = x . u: progressive
    const Vec3 g = s * e + mu1 * a[0] + mu2 * a[1];
    for (const Vec3& v : peak_candidates(g, u, theta_v, a, e))
      if (v.dot(u) >= cos_v - tol && a[0].dot(v) <= tol && a[1].dot(v) <= tol)
        best = std::max(best, g.dot(v));
  }
  if (best == -std::numeric_limits<double>::infinity()) return -1;  // v_a never holds the robot on the edge
  best += kZoneSlack;
  return best > 0 ? best : -1;
}

double face_nonprogressive_speed(double beta, double theta_v, double mu) {
  if (beta > theta_v * (1 + kZoneSlack) + kZoneSlack) return -1;
  const double psi = std::acos(std::clamp(std::cos(theta_v) / std::cos(std::min(beta, theta_v)), -1.0, 1.0));
  const double phi = std::atan(mu);
  if (psi * (1 + kZoneSlack) <= phi) return -1;  // every non-progressive velocity sticks
  return std::sin(psi * (1 + kZoneSlack) - phi) / std::cos(phi);
}

double edge_nonprogressive_speed(double gamma, double theta_v, double mu_min) {
  if (gamma > theta_v * (1 + kZoneSlack) + kZoneSlack) return -1;
  const double phi = std::atan(mu_min);
  if (theta_v * (1 + kZoneSlack) - gamma <= phi) return -1;
  return std::sin(theta_v * (1 + kZoneSlack) - gamma - phi) / std::cos(phi);
}

double edge_min_friction(const CSpace& cspace, int edge_atom) {
  const Edge& e = cspace.edges()[static_cast<std::size_t>(cspace.atom_index(edge_atom))];
  if (e.faces.empty()) return 0;
  double mu = std::numeric_limits<double>::infinity();
  for (int f : e.faces)
    mu = std::min(mu, cspace.faces()[static_cast<std::size_t>(cspace.atom_index(f))].friction);
  return mu;
}

double edge_slide_speed(const CSpace& cspace, const Edge& edge, const Vec3& u, double theta_v) {
  const Vec3 dir = (edge.b - edge.a).normalized();
  if (edge.faces.size() != 2)
    return edge_nonprogressive_speed(edge_gamma(u, dir), theta_v, edge_min_friction(cspace, edge.id));
  const Face& f1 = cspace.faces()[static_cast<std::size_t>(cspace.atom_index(edge.faces[0]))];
  const Face& f2 = cspace.faces()[static_cast<std::size_t>(cspace.atom_index(edge.faces[1]))];
  return edge_slide_speed(u, theta_v, f1.normal, f1.friction, f2.normal, f2.friction, dir);
}

std::vector<int> damper_slide_forever_atoms(const CSpace& cspace, const ReachedSet& reached, const Vec3& v,
                                            double theta_v, double kappa,
                                            const std::vector<bool>& must_stick) {
  std::vector<int> out;
  const Vec3 u = v.normalized();
  for (const Face& f : cspace.faces()) {
    if (!reached.contains_atom(f.id) || must_stick[static_cast<std::size_t>(f.id)]) continue;
    const double beta = angle_between_unit(u, -f.normal);
    if (fast(face_nonprogressive_speed(beta, theta_v, f.friction), 1, kappa)) out.push_back(f.id);
  }
  for (const Edge& e : cspace.edges()) {
    if (!reached.contains_atom(e.id) || must_stick[static_cast<std::size_t>(e.id)]) continue;
    if (fast(edge_slide_speed(cspace, e, u, theta_v), 1, kappa)) out.push_back(e.id);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<int> spring_slide_forever_atoms(const CSpace& cspace, const ReachedSet& reached,
                                            const ReachedSet& start, const Vec3& p, const Uncertainty& u,
                                            double kappa, const std::vector<bool>& strong_atom) {
  std::vector<int> out;
  const double eps = u.eps_s, scale = cspace.scale();
  const double tan_v = u.theta_v >= kPi / 2 ? std::numeric_limits<double>::infinity() : std::tan(u.theta_v);
  // |p* − x0| over the start: a lower bound (0 when p* may be on the start).
  const double d0 = std::max(0.0, start.distance(p) - eps);
  auto ratio = [&](double w_max) {
    if (d0 <= 0) return std::numeric_limits<double>::infinity();
    return std::max(1.0, w_max / d0);
  };
  for (const Face& f : cspace.faces()) {
    if (!reached.contains_atom(f.id)) continue;
    const double h = f.offset - f.normal.dot(p);  // depth of p behind the plane
    if (h + eps <= 0) continue;                   // every p* is in front: the pull leaves the face
    const double speed = face_nonprogressive_speed(0, u.theta_v, f.friction);  // beta >= 0: the largest
    const double radius = (std::max(0.0, h) + eps) * tan_v + eps;
    const double w_max = std::hypot(h, radius) + eps;
    if (!fast(speed, ratio(w_max), kappa)) continue;
    std::vector<bool> keep(static_cast<std::size_t>(cspace.atom_count()), false);
    keep[static_cast<std::size_t>(f.id)] = true;
    const Vec3 foot = p + h * f.normal;
    if (reached.restricted(keep).distance(foot) <= radius * (1 + kZoneSlack) + kZoneSlack * scale)
      out.push_back(f.id);
  }
  for (const Edge& e : cspace.edges()) {
    if (!reached.contains_atom(e.id) || strong_atom[static_cast<std::size_t>(e.id)]) continue;
    const Vec3 d = e.b - e.a;
    const double len = d.norm();
    if (len == 0) continue;
    const Vec3 dir = d / len;
    const double s_p = (p - e.a).dot(dir);
    const double rho = (p - e.a - s_p * dir).norm();
    const double half = (rho + eps) * tan_v + eps;
    const double speed = edge_nonprogressive_speed(0, u.theta_v, edge_min_friction(cspace, e.id));
    if (!fast(speed, ratio(std::hypot(rho, half) + eps), kappa)) continue;
    const double lo = (s_p - half) / len - kZoneSlack, hi = (s_p + half) / len + kZoneSlack;
    for (const EdgeInterval& iv : reached.edge_intervals(e.id))
      if (iv.t1 >= lo && iv.t0 <= hi) {
        out.push_back(e.id);
        break;
      }
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string atom_list(const CSpace& cspace, const std::vector<int>& atoms) {
  std::string s;
  for (int id : atoms) {
    if (!s.empty()) s += ' ';
    s += cspace.atom_name(id);
  }
  return s;
}

}  // namespace cmt

#include "verifier/polyhedron.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cmt {

bool Polyhedron::contains(const Vec3& p) const {
  switch (kind) {
    case Kind::kEmpty:
      return false;
    case Kind::kEverything:
      return true;
    case Kind::kConvex:
    case Kind::kComplement: {
      bool inside = true;
      for (const HalfSpace& h : halfspaces)
        if (h.normal.dot(p) > h.offset) {
          inside = false;
          break;
        }
      return kind == Kind::kConvex ? inside : !inside;
    }
  }
  return false;
}

Polyhedron Polyhedron::offset(double delta) const {
  Polyhedron out = *this;
  if (kind == Kind::kComplement) delta = -delta;  // growing a complement shrinks the convex part
  for (HalfSpace& h : out.halfspaces) h.offset += delta;
  return out;
}

Polyhedron hull_plus_cone(const std::vector<Vec3>& points, const std::vector<Vec3>& rays) {
  std::vector<Vec3> dirs;
  for (const Vec3& r : rays)
    if (r.norm() > 0) dirs.push_back(r.normalized());
  const std::size_t nrays = dirs.size();
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = i + 1; j < points.size(); ++j)
      if ((points[j] - points[i]).norm() > 0) dirs.push_back((points[j] - points[i]).normalized());
  Polyhedron out;
  out.kind = Polyhedron::Kind::kConvex;
  auto valid = [&](const Vec3& u) {
    for (std::size_t k = 0; k < nrays; ++k)
      if (u.dot(dirs[k]) > kPolarSlack) return false;
    return true;
  };
  auto add = [&](const Vec3& u) {
    double h = -std::numeric_limits<double>::infinity();
    for (const Vec3& x : points) h = std::max(h, u.dot(x));
    for (const HalfSpace& e : out.halfspaces)
      if (e.normal.dot(u) > 1 - 1e-15 && std::abs(e.offset - h) < 1e-15) return;  // duplicate
    out.halfspaces.push_back({u, h});
  };
  for (std::size_t i = 0; i < dirs.size(); ++i)
    for (std::size_t j = i + 1; j < dirs.size(); ++j) {
      const Vec3 c = dirs[i].cross(dirs[j]);
      const double len = c.norm();
      if (len < 1e-12) continue;
      for (const Vec3& u : {Vec3(c / len), Vec3(-c / len)})
        if (valid(u)) add(u);
    }
  // A segment or a point with no rays, or rays spanning less than 3-D, may also be bounded by planes
  // perpendicular to single directions; add those (valid ones only).
  for (const Vec3& d : dirs)
    for (const Vec3& u : {d, Vec3(-d)})
      if (valid(u)) add(u);
  if (out.halfspaces.empty()) return Polyhedron::everything();
  return out;
}

}  // namespace cmt

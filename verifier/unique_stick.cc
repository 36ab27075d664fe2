#include "verifier/unique_stick.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cmt {
namespace {

// Two unit normals are perpendicular (box geometry); decided with a tolerance far below any physical angle.
constexpr double kPerpendicularTolerance = 1e-9;
constexpr double kHalfPi = 1.5707963267948966;

double angle(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0));
}

// Angle from unit u to the plane through 0 spanned by a and b.
double plane_angle(const Vec3& u, const Vec3& a, const Vec3& b) {
  const Vec3 n = a.cross(b).normalized();
  return std::asin(std::clamp(std::abs(n.dot(u)), 0.0, 1.0));
}

}  // namespace

UniqueStick UniqueStick::face(const Vec3& normal, double mu) { return intersection({normal}, {mu}); }

UniqueStick UniqueStick::intersection(const std::vector<Vec3>& normals, const std::vector<double>& mus) {
  UniqueStick u;
  u.kind_ = Kind::kIntersection;
  for (std::size_t i = 0; i < normals.size(); ++i) {
    u.normals_.push_back(normals[i].normalized());
    u.mus_.push_back(mus[i]);
  }
  return u;
}

UniqueStick UniqueStick::concave_edge(const Vec3& n1, double mu1, const Vec3& n2, double mu2) {
  UniqueStick u;
  u.kind_ = Kind::kConcaveEdge;
  u.normals_ = {n1.normalized(), n2.normalized()};
  u.mus_ = {mu1, mu2};
  u.e_ = u.normals_[0].cross(u.normals_[1]).normalized();
  return u;
}

UniqueStick UniqueStick::corner(const Vec3& n1, const Vec3& n2, const Vec3& n3, std::vector<double> mus) {
  UniqueStick u;
  u.kind_ = Kind::kCorner;
  u.normals_ = {n1.normalized(), n2.normalized(), n3.normalized()};
  u.mus_ = std::move(mus);
  return u;
}

UniqueStick UniqueStick::for_atom(const CSpace& c, int atom_id) {
  std::vector<Vec3> normals;
  std::vector<double> mus;
  auto add_face = [&](int f) {
    const Face& face = c.faces()[f];
    for (std::size_t i = 0; i < normals.size(); ++i)
      if ((normals[i] - face.normal).norm() < kPerpendicularTolerance) {
        mus[i] =
            std::min(mus[i], face.friction);  // coplanar pieces: the smaller coefficient (sound for must)
        return;
      }
    normals.push_back(face.normal);
    mus.push_back(face.friction);
  };
  auto perpendicular = [](const Vec3& a, const Vec3& b) {
    return std::abs(a.dot(b)) < kPerpendicularTolerance;
  };
  switch (c.atom_kind(atom_id)) {
    case AtomKind::kFace: {
      const Face& f = c.faces()[atom_id];
      return face(f.normal, f.friction);
    }
    case AtomKind::kEdge: {
      const Edge& e = c.edges()[c.atom_index(atom_id)];
      for (int f : e.faces) add_face(f);
      if (e.shape == EdgeShape::kConcave && normals.size() == 2 && perpendicular(normals[0], normals[1]))
        return concave_edge(normals[0], mus[0], normals[1], mus[1]);
      return intersection(normals, mus);
    }
    case AtomKind::kVertex: {
      const Vertex& v = c.vertices()[c.atom_index(atom_id)];
      for (int f : v.faces) add_face(f);
      if (normals.size() == 3 && perpendicular(normals[0], normals[1]) &&
          perpendicular(normals[1], normals[2]) && perpendicular(normals[0], normals[2])) {
        // A concave corner: the vertex point is on the free side of none of the faces' extensions, i.e. every
        // face's polygon lies on the free side of the other faces' planes.
        bool concave = true;
        for (int f : v.faces)
          for (int g : v.faces) {
            if (f == g) continue;
            const Face& F = c.faces()[f];
            const Face& G = c.faces()[g];
            for (const Vec3& p : F.polygon)
              concave = concave && G.normal.dot(p) - G.offset >= -1e-12 * c.scale();
          }
        if (concave) return corner(normals[0], normals[1], normals[2], mus);
      }
      return intersection(normals, mus);
    }
  }
  return intersection(normals, mus);
}

std::vector<std::vector<CircularCone>> UniqueStick::must_cones(double angle) const {
  std::vector<std::vector<CircularCone>> out;
  // cone(axis, half) narrowed by `angle`; false when nothing is left.
  auto narrowed = [angle](const Vec3& axis, double half, std::vector<CircularCone>* set) {
    if (half - angle <= 0) return false;
    set->push_back({axis.normalized(), std::min(half - angle, kHalfPi)});
    return true;
  };
  // Two cones whose axes are further apart than their half-angles add up meet only at the apex: the
  // alternative holds no direction and is left out.
  auto add = [&out](std::vector<CircularCone> set, bool ok) {
    ok = ok && !set.empty();  // no cone would be every direction: never an alternative
    for (std::size_t i = 0; ok && i < set.size(); ++i)
      for (std::size_t j = i + 1; ok && j < set.size(); ++j)
        ok = std::acos(std::clamp(set[i].axis.dot(set[j].axis), -1.0, 1.0)) <
             set[i].half_angle + set[j].half_angle;
    if (ok) out.push_back(std::move(set));
  };
  auto face_alternatives = [&] {  // each face's own narrowed cone
    for (std::size_t i = 0; i < normals_.size() && i < mus_.size(); ++i) {
      std::vector<CircularCone> set;
      const bool ok = narrowed(-normals_[i], std::atan(mus_[i]), &set);
      add(set, ok);
    }
  };
  switch (kind_) {
    case Kind::kIntersection: {
      std::vector<CircularCone> set;
      bool ok = true;
      for (std::size_t i = 0; i < normals_.size(); ++i)
        ok = ok && narrowed(-normals_[i], std::atan(mus_[i]), &set);
      add(set, ok);
      break;
    }
    case Kind::kCorner: {
      // Pressing into every face: f . n_k <= 0, each plane narrowed to cone(−n_k, pi/2 − angle).
      std::vector<CircularCone> set;
      bool ok = true;
      for (const Vec3& n : normals_) ok = ok && narrowed(-n, kHalfPi, &set);
      add(set, ok);
      face_alternatives();
      break;
    }
    case Kind::kConcaveEdge: {  // N1, N2 >= 0 and |t| <= mu1 N1 + mu2 N2: four planes f . w <= 0
      const Vec3 &n1 = normals_[0], &n2 = normals_[1];
      const Vec3 side = mus_[0] * n1 + mus_[1] * n2;
      std::vector<CircularCone> set;
      bool ok = true;
      for (const Vec3& w : {n1, n2, Vec3(e_ + side), Vec3(side - e_)}) ok = ok && narrowed(-w, kHalfPi, &set);
      add(set, ok);
      face_alternatives();
      break;
    }
  }
  return out;
}

double UniqueStick::margin(const Vec3& force) const {
  const Vec3 f = force.normalized();
  switch (kind_) {
    case Kind::kIntersection: {
      double m = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < normals_.size(); ++i)
        m = std::min(m, std::atan(mus_[i]) - angle(f, -normals_[i]));
      return m;
    }
    case Kind::kCorner: {
      for (const Vec3& n : normals_)
        if (f.dot(n) > 0) return 0;  // pulls away from a face
      double m = std::numeric_limits<double>::infinity();
      for (int k = 0; k < 3; ++k)
        m = std::min(m, plane_angle(f, normals_[(k + 1) % 3], normals_[(k + 2) % 3]));
      return m;
    }
    case Kind::kConcaveEdge: {
      const Vec3 &n1 = normals_[0], &n2 = normals_[1];
      const double N1 = -f.dot(n1), N2 = -f.dot(n2), t = f.dot(e_);
      const double mu1 = mus_[0], mu2 = mus_[1], phi1 = std::atan(mu1), phi2 = std::atan(mu2);
      const bool in_kinetic = N1 >= 0 && N2 >= 0 && std::abs(t) <= mu1 * N1 + mu2 * N2;
      const bool on_face1 = N2 <= 0 && angle(f, -n1) <= phi1;
      const bool on_face2 = N1 <= 0 && angle(f, -n2) <= phi2;
      if (!in_kinetic && !on_face1 && !on_face2) return 0;
      // Boundary pieces: the kinetic cone's two facets toward ±e, and the two faces' rim circles.
      double m = std::abs(angle(f, -n1) - phi1);
      m = std::min(m, std::abs(angle(f, -n2) - phi2));
      for (double s : {1.0, -1.0}) m = std::min(m, plane_angle(f, -n1 + s * mu1 * e_, -n2 + s * mu2 * e_));
      return m;
    }
  }
  return 0;
}

}  // namespace cmt

// Lookups shared by the verifier tests.
#pragma once

#include "models/cspace.h"

namespace cmt::test {

// The face whose outward normal is `normal` and whose closure contains p, or -1.
inline int face_at(const CSpace& c, const Vec3& normal, const Vec3& p) {
  for (const Face& f : c.faces())
    if (f.normal.dot(normal) > 1 - 1e-12 && c.distance_to_atom(p, f.id) < 1e-9) return f.id;
  return -1;
}

// The edge between the points a and b (either direction, endpoints within 1e-9), or -1.
inline int edge_between(const CSpace& c, const Vec3& a, const Vec3& b) {
  for (const Edge& e : c.edges())
    if (((e.a - a).norm() < 1e-9 && (e.b - b).norm() < 1e-9) ||
        ((e.a - b).norm() < 1e-9 && (e.b - a).norm() < 1e-9))
      return e.id;
  return -1;
}

// The vertex at p (within 1e-9), or -1.
inline int vertex_at(const CSpace& c, const Vec3& p) {
  for (const Vertex& v : c.vertices())
    if ((v.point - p).norm() < 1e-9) return v.id;
  return -1;
}

}  // namespace cmt::test

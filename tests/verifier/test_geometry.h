// Lookups shared by the verifier tests.
#pragma once

#include "models/cspace.h"

namespace cmt::test {

// The rollouts' stop rule (controllers/termination.h kStopRelativeSpeed, which the verifier's tests do not
// link): a robot sliding slower than 1 % of its reference speed counts as stopped. With it a verdict is the
// one `cmt verify` gives; with kappa 0 (Coulomb sticking only) a motion whose velocity error may keep it
// sliding slowly without progress is not proved to terminate (docs/verifier.md "Termination: sliding
// forever").
inline constexpr double kRolloutStopRelativeSpeed = 0.01;

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

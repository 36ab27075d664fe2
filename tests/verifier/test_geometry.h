// Lookups shared by the verifier tests.
#pragma once

#include <memory>
#include <string>

#include "models/cspace.h"
#include "models/loaded_task.h"
#include "models/task_loader.h"

namespace cmt::test {

// An empty room [-4,4] x [-4,4] x [0,4] in C-space (the robot is a point), mu .25, with the given C-space
// obstacles (a YAML list): without them the floor z = 0 is one 8 x 8 face. Scene scale 12 (the diagonal).
inline std::shared_ptr<const LoadedTask> room(const std::string& obstacles = "[]") {
  return load_task_from_string(
      "name: t\nunits: in\nfriction: 0.25\nuncertainty: {eps_s: 0.1, eps_p: 0.1, theta_v: 0.1, theta_f: "
      "0.1}\n"
      "cspace: " +
          obstacles +
          "\nbounds: {min: [-4, -4, 0], max: [4, 4, 4]}\n"
          "start: {point: [0, 0, 4]}\ngoal: {point: [0, 0, 4]}\nmotions:\n  m: {damper: [0, 0, -1]}\n"
          "strategies:\n  s: [m]\n",
      "test");
}

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

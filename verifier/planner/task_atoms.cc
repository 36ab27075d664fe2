// Start and goal atoms (task_atoms.h).
#include "verifier/planner/task_atoms.h"

#include <algorithm>

#include "models/polygon_distance.h"
#include "verifier/atom_cone.h"
#include "verifier/planner/simulation.h"

namespace cmt::planner {

bool in_region(const Region& region, const Vec3& p, double tol) {
  const auto& q = region.points;
  switch (region.kind) {
    case Region::Kind::kPoint:
      return (p - q[0]).norm() <= tol;
    case Region::Kind::kSegment:
      return distance_to_segment(p, q[0], q[1]) <= tol;
    case Region::Kind::kPolygon: {
      Vec3 n = Vec3::Zero();
      for (std::size_t i = 0; i < q.size(); ++i) n += q[i].cross(q[(i + 1) % q.size()]);
      n.normalize();
      if (std::abs(n.dot(p - q[0])) > tol) return false;
      for (std::size_t i = 0; i < q.size(); ++i) {
        const Vec3 edge = q[(i + 1) % q.size()] - q[i];
        const Vec3 inward = n.cross(edge).normalized();  // counter-clockwise about n
        if (inward.dot(p - q[i]) < -tol) return false;
      }
      return true;
    }
  }
  return false;
}

Vec3 region_centroid(const Region& region) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : region.points) c += p;
  return region.points.empty() ? c : Vec3(c / static_cast<double>(region.points.size()));
}

std::vector<int> start_atoms(const LoadedTask& task) {
  std::vector<int> atoms;
  for (const Vec3& p : region_samples(task.task.start)) {
    const int a = task.cspace.nearest_atom(p, task.surface_tolerance());
    if (a >= 0 && std::find(atoms.begin(), atoms.end(), a) == atoms.end()) atoms.push_back(a);
  }
  std::sort(atoms.begin(), atoms.end());
  std::vector<int> out;
  for (int a : atoms) {
    const bool bounds_another = std::any_of(atoms.begin(), atoms.end(), [&](int b) {
      return b != a && atoms_connected(task.cspace, a, b) &&
             static_cast<int>(task.cspace.atom_kind(b)) < static_cast<int>(task.cspace.atom_kind(a));
    });
    if (!bounds_another) out.push_back(a);
  }
  return out;
}

std::vector<bool> goal_atoms(const LoadedTask& task) {
  const double tol = task.surface_tolerance();
  std::vector<bool> out(static_cast<std::size_t>(task.cspace.atom_count()), false);
  for (int atom = 0; atom < task.cspace.atom_count(); ++atom) {
    const std::vector<Vec3> points = atom_points(task.cspace, atom);
    out[static_cast<std::size_t>(atom)] =
        std::any_of(task.task.goal.begin(), task.task.goal.end(), [&](const Region& g) {
          return std::all_of(points.begin(), points.end(),
                             [&](const Vec3& p) { return in_region(g, p, tol); });
        });
  }
  return out;
}

}  // namespace cmt::planner

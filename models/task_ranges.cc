#include "models/task_ranges.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/convex_hull_2.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "models/task_error.h"

namespace cmt {
namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

std::string format(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

struct SceneBox {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool empty() const { return !(min.x() <= max.x()); }
};

SceneBox bounding_box(const std::vector<ConvexPart>& parts) {
  SceneBox b;
  for (const ConvexPart& part : parts)
    for (const Vec3& v : part.vertices) b.add(v);
  return b;
}

// The scene box of task_scene_size, with planar tasks' y collapsed to 0.
SceneBox scene_box(const Task& task) {
  SceneBox box;
  if (task.bounds) {
    box.add(task.bounds->min);
    box.add(task.bounds->max);
  } else if (task.physical()) {
    // O ⊕ (−R) lies in [min O − max R, max O − min R].
    const SceneBox o = bounding_box(task.environment), r = bounding_box(task.robot);
    if (!o.empty()) {
      box.add(o.min - r.max);
      box.add(o.max - r.min);
    }
  } else {
    box = bounding_box(task.cspace);
  }
  for (const Vec3& p : task.start.points) box.add(p);
  for (const Region& g : task.goal)
    for (const Vec3& p : g.points) box.add(p);
  if (task.dimension == 2) box.min.y() = box.max.y() = 0;
  return box;
}

// The width of a convex polytope is the minimum over its hull's facet planes of the largest distance of a
// point from that plane (a minimum-width slab has a facet on one of its planes); in 2-D, over the hull's
// edges.
double width_3d(const std::vector<Vec3>& points) {
  std::vector<Kernel::Point_3> pts;
  for (const Vec3& p : points) pts.emplace_back(p.x(), p.y(), p.z());
  CGAL::Polyhedron_3<Kernel> hull;
  CGAL::convex_hull_3(pts.begin(), pts.end(), hull);
  if (hull.size_of_facets() < 4) return 0;  // fewer than 4 facets: not a solid
  double width = std::numeric_limits<double>::infinity();
  for (auto f = hull.facets_begin(); f != hull.facets_end(); ++f) {
    const auto h = f->halfedge();
    const Vec3 a(h->vertex()->point().x(), h->vertex()->point().y(), h->vertex()->point().z());
    const auto& pb = h->next()->vertex()->point();
    const auto& pc = h->next()->next()->vertex()->point();
    const Vec3 n = (Vec3(pb.x(), pb.y(), pb.z()) - a).cross(Vec3(pc.x(), pc.y(), pc.z()) - a);
    if (!(n.norm() > 0)) return 0;
    double farthest = 0;
    for (const Vec3& p : points) farthest = std::max(farthest, std::abs(n.dot(p - a)) / n.norm());
    width = std::min(width, farthest);
  }
  return width;
}

double width_2d(const std::vector<Vec3>& points) {
  std::vector<Kernel::Point_2> pts, hull;
  for (const Vec3& p : points) pts.emplace_back(p.x(), p.z());
  CGAL::convex_hull_2(pts.begin(), pts.end(), std::back_inserter(hull));
  if (hull.size() < 3) return 0;
  double width = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const auto& a = hull[i];
    const auto& b = hull[(i + 1) % hull.size()];
    const double ex = b.x() - a.x(), ez = b.y() - a.y(), len = std::hypot(ex, ez);
    if (!(len > 0)) return 0;
    double farthest = 0;
    for (const auto& p : hull)
      farthest = std::max(farthest, std::abs(ex * (p.y() - a.y()) - ez * (p.x() - a.x())) / len);
    width = std::min(width, farthest);
  }
  return width;
}

void check_parts(const Task& task, const std::vector<ConvexPart>& parts, double scene) {
  const double min_width = kMinPartWidthRelative * scene;
  for (const ConvexPart& part : parts) {
    const double w = part_width(part, task.dimension);
    if (!(w >= min_width))
      throw TaskError(task.source_file, part.key,
                      "the part is " + format(w) + " thick, below the smallest accepted width " +
                          format(min_width) + " (" + format(kMinPartWidthRelative) + " of the scene size " +
                          format(scene) + ")");
  }
}

void check_errors(const Task& task, double scene) {
  const Uncertainty& u = task.uncertainty;
  const double max_error = kMaxErrorRelative * scene;
  const auto at_most = [&](double v, const char* key, const char* what) {
    if (v > max_error)
      throw TaskError(task.source_file, std::string("uncertainty.") + key,
                      std::string(what) + " " + format(v) + " exceeds the scene size " + format(scene) +
                          " (the largest accepted value)");
  };
  at_most(u.eps_s, "eps_s", "the position-sensing error bound");
  at_most(u.eps_p, "eps_p", "the positioning error bound");
  at_most(u.step, "step", "the spring interpolation step");
  const double min_step = kMinStepRelative * scene;
  if (u.step < min_step)
    throw TaskError(task.source_file, "uncertainty.step",
                    "the spring interpolation step " + format(u.step) + " is below " + format(min_step) +
                        " (" + format(kMinStepRelative) + " of the scene size " + format(scene) + ")");
}

double distance_to_box(const Vec3& p, const SceneBox& b) {
  return (p - p.cwiseMax(b.min).cwiseMin(b.max)).norm();
}

void check_springs(const Task& task, const SceneBox& box, double scene) {
  const double reach = kMaxSpringReachRelative * scene;
  for (const Motion& m : task.motions) {
    if (m.kind != Motion::Kind::kSpring) continue;
    Vec3 target = m.target;
    if (task.dimension == 2) target.y() = 0;
    const double d = distance_to_box(target, box);
    if (d > reach)
      throw TaskError(task.source_file, "motions." + m.name + ".spring",
                      "the commanded position is " + format(d) + " from the scene, farther than " +
                          format(kMaxSpringReachRelative) + " scene sizes (" + format(reach) +
                          "); a damper toward it is the same motion");
  }
}

}  // namespace

double part_width(const ConvexPart& part, int dimension) {
  if (part.shape == ConvexPart::Shape::kBox) {
    const Vec3 extent = part.box.max - part.box.min;
    return dimension == 2 ? std::min(extent.x(), extent.z()) : extent.minCoeff();
  }
  return dimension == 2 ? width_2d(part.vertices) : width_3d(part.vertices);
}

void apply_scene_defaults(Task& task) {
  Uncertainty& u = task.uncertainty;
  if (u.step > 0) return;
  const double scene = task_scene_size(task);
  u.step = u.eps_p >= kMinStepRelative * scene ? u.eps_p : kDefaultStepRelative * scene;
}

std::string theta_v_range_reason(double theta_v) {
  return "must be < pi/2 (1.5708) radians, got " + format(theta_v);
}

double task_scene_size(const Task& task) {
  const SceneBox box = scene_box(task);
  return box.empty() ? 0 : (box.max - box.min).norm();
}

void check_task_ranges(const Task& task) {
  const SceneBox box = scene_box(task);
  const double scene = box.empty() ? 0 : (box.max - box.min).norm();
  const std::string where = task.bounds ? "bounds" : (task.physical() ? "environment" : "cspace");
  if (!(scene >= kMinSceneSize))
    throw TaskError(task.source_file, where,
                    "the scene is " + format(scene) + " across, below the smallest accepted size " +
                        format(kMinSceneSize) + " task units (use smaller units)");
  const double offset = std::max(box.min.cwiseAbs().maxCoeff(), box.max.cwiseAbs().maxCoeff());
  if (offset > kMaxSceneOffset * scene)
    throw TaskError(task.source_file, where,
                    "the scene is " + format(scene) + " across but lies " + format(offset) +
                        " from the origin, more than " + format(kMaxSceneOffset) +
                        " scene sizes (move it toward the origin)");
  check_parts(task, task.robot, scene);
  check_parts(task, task.environment, scene);
  check_parts(task, task.cspace, scene);
  check_errors(task, scene);
  check_springs(task, box, scene);
}

}  // namespace cmt

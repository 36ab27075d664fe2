// Goal stops on partial goal faces and the sensed positions of a goal (goal_stops.h).
#include "verifier/planner/goal_stops.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <optional>

#include "verifier/atom_cone.h"
#include "verifier/convex_polygon.h"
#include "verifier/planner/task_atoms.h"

namespace cmt::planner {
namespace {

// Bisection steps for the scale of a goal's sensed rectangle (2^-40 of the polygon's bounding rectangle).
constexpr int kRectangleBisections = 40;
// Type 3 tries every subset of a goal polygon's sides as the ones P_s may reach (2^sides boxes); a polygon
// of more sides gets the type 2 box.
constexpr std::size_t kMaxSidesForSubsets = 8;
// A goal polygon's normal within this (1 - |n_k|) of a coordinate axis lies on an axis-aligned plane.
constexpr double kAxisAligned = 1e-12;

std::vector<Vec3> clip_to_box(std::vector<Vec3> points, const AxisBox& box) {
  for (int k = 0; k < 3 && !points.empty(); ++k) {
    points = clip_to_halfspace(points, Vec3::Unit(k), box.max[k]);
    if (!points.empty()) points = clip_to_halfspace(points, -Vec3::Unit(k), -box.min[k]);
  }
  return points;
}

AxisBox grown(const AxisBox& box, double r) {
  AxisBox out = box;
  out.min.array() -= r;
  out.max.array() += r;
  return out;
}

Vec3 centroid(const std::vector<Vec3>& points) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : points) c += p;
  return c / static_cast<double>(points.size());
}

// A polygon's sides as half-spaces m . x <= c with m in the plane of normal n, pointing out of the polygon.
std::vector<HalfSpace> polygon_sides(const std::vector<Vec3>& polygon, const Vec3& n) {
  const Vec3 c = centroid(polygon);
  std::vector<HalfSpace> sides;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec3& a = polygon[i];
    const Vec3& b = polygon[(i + 1) % polygon.size()];
    Vec3 m = (b - a).cross(n);
    if (m.norm() == 0) continue;
    m.normalize();
    if (m.dot(c - a) > 0) m = -m;
    sides.push_back({m, m.dot(a)});
  }
  return sides;
}

Vec3 polygon_normal(const std::vector<Vec3>& q) {
  Vec3 n = Vec3::Zero();
  for (std::size_t i = 0; i < q.size(); ++i) n += q[i].cross(q[(i + 1) % q.size()]);
  return n.normalized();
}

// The axis rectangle (in the plane's two other axes) of a goal polygon on the plane x_k = level, centred in
// the polygon shrunk side by side, whose axis box grown by insets[i] stays `margin` inside side i, m . x <=
// c, of polygon_sides() (a side moves in by inset |m|_1 + margin: the support of that cube along m), as a box
// 2 half_thickness thick; nothing when too small.
std::optional<AxisBox> inscribed_box(const std::vector<Vec3>& polygon, int k,
                                     const std::vector<double>& insets, double half_thickness,
                                     double margin) {
  const Vec3 n = Vec3::Unit(k);
  std::vector<HalfSpace> sides = polygon_sides(polygon, n);
  std::vector<Vec3> shrunk = polygon;  // the polygon with every side moved in: the rectangle is centred in it
  for (std::size_t i = 0; i < sides.size(); ++i) {
    sides[i].offset -= insets[i] * sides[i].normal.lpNorm<1>() + margin;
    if (!shrunk.empty()) shrunk = clip_to_halfspace(shrunk, sides[i].normal, sides[i].offset);
  }
  if (shrunk.size() < 3) return std::nullopt;
  AxisBox bound{shrunk[0], shrunk[0]};
  for (const Vec3& q : shrunk) bound.min = bound.min.cwiseMin(q), bound.max = bound.max.cwiseMax(q);
  const Vec3 c = centroid(shrunk);
  const auto fits = [&](double s) {
    for (int corner = 0; corner < 4; ++corner) {
      Vec3 q = c;
      int bit = 0;
      for (int axis = 0; axis < 3; ++axis) {
        if (axis == k) continue;
        const double end = (corner >> bit++) & 1 ? bound.max[axis] : bound.min[axis];
        q[axis] = c[axis] + s * (end - c[axis]);
      }
      for (const HalfSpace& h : sides)
        if (h.normal.dot(q) > h.offset) return false;
    }
    return true;
  };
  if (!fits(0)) return std::nullopt;
  double lo = 0, hi = 1;
  if (fits(1)) lo = 1;
  for (int i = 0; i < kRectangleBisections && lo < 1; ++i) (fits((lo + hi) / 2) ? lo : hi) = (lo + hi) / 2;
  AxisBox box;
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == k) {
      box.min[axis] = c[axis] - half_thickness;
      box.max[axis] = c[axis] + half_thickness;
    } else {
      box.min[axis] = c[axis] + lo * (bound.min[axis] - c[axis]);
      box.max[axis] = c[axis] + lo * (bound.max[axis] - c[axis]);
      if (box.max[axis] - box.min[axis] <= margin) return std::nullopt;
    }
  }
  return box;
}

// Per atom: whether its friction cone widened by theta_f may meet a cone of F_s (all atoms without F_s).
// may_intersect_cone's false is certain, so an atom marked false never passes the force test (Def 4.1).
std::vector<bool> may_sense_forces(const LoadedTask& task, const std::vector<ForceCone>& forces) {
  const CSpace& c = task.cspace;
  std::vector<bool> out(static_cast<std::size_t>(c.atom_count()), forces.empty());
  if (forces.empty()) return out;
  const AtomCones cones(c);
  for (int atom = 0; atom < c.atom_count(); ++atom) {
    const FrictionCone sensed = cones[atom].widened(task.task.uncertainty.theta_f);
    for (const ForceCone& f : forces)
      if (sensed.may_intersect_cone(CircularCone{f.direction, f.angle}))
        out[static_cast<std::size_t>(atom)] = true;
  }
  return out;
}

// Whether goal polygon g lies on face f (in its plane within `tol`) and overlaps it with positive area.
bool lies_on_face(const Region& g, const Face& f, double tol) {
  if (std::any_of(g.points.begin(), g.points.end(),
                  [&](const Vec3& q) { return std::abs(f.normal.dot(q) - f.offset) > tol; }))
    return false;
  std::vector<Vec3> overlap = g.points;
  for (const HalfSpace& h : polygon_sides(f.polygon, f.normal))
    if (!overlap.empty()) overlap = clip_to_halfspace(overlap, h.normal, h.offset);
  return overlap.size() >= 3 && std::abs(polygon_area(overlap, f.normal)) > tol * tol;
}

// A box's extent across the plane x_k = level.
double area(const AxisBox& box, int k) {
  double a = 1;
  for (int axis = 0; axis < 3; ++axis)
    if (axis != k) a *= box.max[axis] - box.min[axis];
  return a;
}

// Whether every contact point within r of the box that may pass the force test (`force_sensed`) lies in the
// goal: on a goal atom, or (the clipped part of an atom, convex) inside one goal region.
bool senses_goal_only(const LoadedTask& task, const std::vector<bool>& goal_atom,
                      const std::vector<bool>& force_sensed, const AxisBox& box, double r) {
  const CSpace& c = task.cspace;
  const double tol = task.surface_tolerance();
  const AxisBox near = grown(box, r);
  for (int atom = 0; atom < c.atom_count(); ++atom) {
    if (goal_atom[static_cast<std::size_t>(atom)] || !force_sensed[static_cast<std::size_t>(atom)]) continue;
    const std::vector<Vec3> part = clip_to_box(atom_points(c, atom), near);
    if (part.empty()) continue;
    const bool inside = std::any_of(task.task.goal.begin(), task.task.goal.end(), [&](const Region& g) {
      return std::all_of(part.begin(), part.end(), [&](const Vec3& p) { return in_region(g, p, tol); });
    });
    if (!inside) return false;
  }
  return true;
}

}  // namespace

std::vector<PartialGoalFace> partial_goal_faces(const LoadedTask& task, const std::vector<bool>& goal_atom) {
  const CSpace& c = task.cspace;
  const double tol = task.surface_tolerance();
  std::vector<PartialGoalFace> out;
  for (const Region& g : task.task.goal) {
    if (g.kind != Region::Kind::kPolygon) continue;
    for (const Face& f : c.faces()) {
      if (goal_atom[static_cast<std::size_t>(f.id)] || !lies_on_face(g, f, tol)) continue;
      out.push_back({f.id, polygon_sides(g.points, f.normal)});
    }
  }
  return out;
}

std::vector<AxisBox> goal_sensed_positions(const LoadedTask& task, const std::vector<ForceCone>& forces) {
  const double eps_s = task.task.uncertainty.eps_s;
  const double margin = kSensedSetRelativeMargin * task.cspace.scale();
  const std::vector<bool> goal_atom = goal_atoms(task);
  const std::vector<bool> force_sensed = may_sense_forces(task, forces);
  std::vector<AxisBox> out;
  for (const Region& g : task.task.goal) {
    if (g.kind != Region::Kind::kPolygon) continue;
    const Vec3 n = polygon_normal(g.points);
    int k = 0;
    n.cwiseAbs().maxCoeff(&k);
    if (1 - std::abs(n[k]) > kAxisAligned) continue;
    const double thickness = eps_s > 0 ? eps_s : margin;
    const std::size_t sides = polygon_sides(g.points, Vec3::Unit(k)).size();
    // Type 2: every side inset. Type 3: each subset of the sides inset (the rest not), the largest box that
    // senses the goal only.
    const std::uint32_t subsets = forces.empty() || sides > kMaxSidesForSubsets ? 1 : 1u << sides;
    std::optional<AxisBox> best;
    for (std::uint32_t open = 0; open < subsets; ++open) {
      std::vector<double> insets(sides, eps_s + margin);
      for (std::size_t i = 0; i < sides; ++i)
        if ((open >> i) & 1u) insets[i] = 0;
      const std::optional<AxisBox> box = inscribed_box(g.points, k, insets, thickness, margin);
      if (box && (!best || area(*box, k) > area(*best, k)) &&
          senses_goal_only(task, goal_atom, force_sensed, *box, eps_s + margin))
        best = box;
    }
    if (best) out.push_back(*best);
  }
  return out;
}

std::vector<ForceCone> goal_sensed_forces(const LoadedTask& task) {
  const CSpace& c = task.cspace;
  const double tol = task.surface_tolerance();
  const AtomCones cones(c);
  std::vector<ForceCone> out;
  for (const Region& g : task.task.goal) {
    if (g.kind != Region::Kind::kPolygon) continue;
    for (const Face& f : c.faces()) {
      if (!lies_on_face(g, f, tol) || !cones[f.id].circular())
        continue;  // the task format's cones are circular, at most pi/2 wide
      const CircularCone& cone = cones[f.id].generators()[0];
      const ForceCone sensed{cone.axis.normalized(),
                             cone.half_angle + task.task.uncertainty.theta_f + kSensedForceMargin};
      if (sensed.angle > std::numbers::pi / 2) continue;
      const bool known = std::any_of(out.begin(), out.end(), [&](const ForceCone& o) {
        return (o.direction - sensed.direction).norm() <= kAxisAligned && o.angle >= sensed.angle;
      });
      if (!known) out.push_back(sensed);
    }
  }
  return out;
}

std::vector<bool> sensing_atoms(const LoadedTask& task, const std::vector<AxisBox>& boxes,
                                const std::vector<ForceCone>& forces) {
  const CSpace& cspace = task.cspace;
  const double r = task.task.uncertainty.eps_s + kSensedSetRelativeMargin * cspace.scale();
  const std::vector<bool> force_sensed = may_sense_forces(task, forces);
  std::vector<bool> out(static_cast<std::size_t>(cspace.atom_count()), false);
  for (int atom = 0; atom < cspace.atom_count(); ++atom)
    for (const AxisBox& box : boxes)
      if (force_sensed[static_cast<std::size_t>(atom)] &&
          !clip_to_box(atom_points(cspace, atom), grown(box, r)).empty())
        out[static_cast<std::size_t>(atom)] = true;
  return out;
}

}  // namespace cmt::planner

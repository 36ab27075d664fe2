// Weakly consistent reached points of a motion's termination sets (Buckley §4.5, Def 4.1).
#include "verifier/sensing_termination.h"

#include <algorithm>
#include <cmath>

#include "models/task_loader.h"

namespace cmt {

ReachedSet sensing_termination(const LoadedTask& task, const AtomCones& cones, const Motion& m,
                               const ReachedSet& reached) {
  return weakly_consistent(task, cones, m.terminate, reached);
}

ReachedSet weakly_consistent(const LoadedTask& task, const AtomCones& cones, const MotionTermination& t,
                             const ReachedSet& reached) {
  const CSpace& c = task.cspace;
  if (!t.any()) return ReachedSet(c);

  // Def 4.1, position part: x within eps_s of P_s. The ball is over-approximated by the box grown by eps_s on
  // every axis (the ball lies in that cube), plus kSensingBoxRelativeSlack x scale.
  ReachedSet out = reached;
  if (!t.position.empty()) {
    const double grow = task.task.uncertainty.eps_s + kSensingBoxRelativeSlack * c.scale();
    ReachedSet inside(c);
    for (const AxisBox& b : t.position) {
      AxisBox g = b;
      g.min.array() -= grow;
      g.max.array() += grow;
      inside.unite(reached.within_box(g));
    }
    out = std::move(inside);
  }

  // Def 4.1, force part: some vector of the atom's friction cone within theta_f of F_s. The reaction force
  // on the robot lies in its atom's cone (an edge's or vertex's sum holds every face's), and the sensed one
  // is turned by at most theta_f, so an atom whose widened cone cannot meet any cone of F_s never fires
  // type 3 (may_intersect_cone: false is certain).
  if (!t.force.empty()) {
    std::vector<bool> keep(static_cast<std::size_t>(c.atom_count()), false);
    for (int id : out.atoms()) {
      const FrictionCone sensed = cones[id].widened(task.task.uncertainty.theta_f);
      for (const ForceCone& f : t.force)
        if (sensed.may_intersect_cone(CircularCone{f.direction, f.angle})) keep[id] = true;
    }
    out = out.restricted(keep);
  }
  return out;
}

ReachedSet without_strongly_consistent(const LoadedTask& task, const AtomCones& cones,
                                       const MotionTermination& t, const ReachedSet& set) {
  const CSpace& c = task.cspace;
  if (!t.any()) return set;
  // Which atoms surely pass the force part (all of them when there is none).
  std::vector<bool> force_sure(static_cast<std::size_t>(c.atom_count()), t.force.empty());
  if (!t.force.empty()) {
    for (int id : set.atoms()) {
      if (c.atom_kind(id) != AtomKind::kFace || !cones[id].circular()) continue;
      const CircularCone& g = cones[id].generators()[0];
      for (const ForceCone& f : t.force) {
        const double between = std::acos(std::clamp(g.axis.normalized().dot(f.direction), -1.0, 1.0));
        if (between + g.half_angle + task.task.uncertainty.theta_f + kForceContainmentMargin <= f.angle)
          force_sure[static_cast<std::size_t>(id)] = true;
      }
    }
  }
  std::vector<bool> other(force_sure.size());
  for (std::size_t i = 0; i < other.size(); ++i) other[i] = !force_sure[i];
  ReachedSet kept = set.restricted(other);  // no point here surely passes
  ReachedSet sure = set.restricted(force_sure);
  if (t.position.empty()) return kept;  // the force part alone decides: every reading passes on those faces
  const double shrink = task.task.uncertainty.eps_s + kSensingBoxRelativeSlack * c.scale();
  for (const AxisBox& b : t.position) {
    AxisBox inner = b;
    inner.min.array() += shrink;
    inner.max.array() -= shrink;
    if (task.task.dimension == 2) {
      // Planar: the sensing error lies in the x-z plane and the robot stays in the clip slab, which a planar
      // box spans in y (the loader's reading), so every reading passes in y: the box takes twice the slab,
      // which holds the whole C-space (its bounds span the slab) with room for the grid's rounding.
      inner.min.y() = -2 * kPlanarClipHalfDepth;
      inner.max.y() = 2 * kPlanarClipHalfDepth;
    }
    if ((inner.min.array() > inner.max.array()).any()) continue;  // the ball fits nowhere in this box
    sure = sure.without_box(inner);
  }
  kept.unite(sure);
  return kept;
}

}  // namespace cmt

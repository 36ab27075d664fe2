// Weakly consistent reached points of a motion's termination sets (Buckley §4.5, Def 4.1).
#include "verifier/sensing_termination.h"

namespace cmt {

ReachedSet sensing_termination(const LoadedTask& lt, const AtomCones& cones, const Motion& m,
                               const ReachedSet& reached) {
  const MotionTermination& t = m.terminate;
  const CSpace& c = lt.cspace;
  if (!t.any()) return ReachedSet(c);

  // Def 4.1, position part: x within eps_s of P_s. The ball is over-approximated by the box grown by eps_s on
  // every axis (the ball lies in that cube), plus kSensingBoxRelativeSlack x scale.
  ReachedSet out = reached;
  if (!t.position.empty()) {
    const double grow = lt.task.uncertainty.eps_s + kSensingBoxRelativeSlack * c.scale();
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
      const FrictionCone sensed = cones[id].widened(lt.task.uncertainty.theta_f);
      for (const ForceCone& f : t.force)
        if (sensed.may_intersect_cone(CircularCone{f.direction, f.angle})) keep[id] = true;
    }
    out = out.restricted(keep);
  }
  return out;
}

}  // namespace cmt

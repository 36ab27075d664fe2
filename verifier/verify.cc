// Strategy verification (Buckley §4.2, Fig 4.2; Alg 4.1 / 4.4 per motion, §4.5 sensing termination).
#include "verifier/verify.h"

#include <algorithm>

#include "models/task_error.h"
#include "verifier/atom_cone.h"
#include "verifier/damper_projection.h"
#include "verifier/sensing_termination.h"
#include "verifier/slide_forever.h"
#include "verifier/spring_projection.h"

namespace cmt {
namespace {

// One motion's termination set from `start` (damper Alg 4.1, spring Alg 4.4, plus §4.5 sensing).
VerifyStep simulate(const LoadedTask& task, const AtomCones& cones, const Motion& motion,
                    const ReachedSet& start, const VerifyOptions& options) {
  VerifyStep step{motion.name, ReachedSet(task.cspace)};
  if (motion.kind == Motion::Kind::kSpring) {
    SpringProjection p = forward_project_spring(
        task, start, motion.target, options.spring_model, options.stop_relative_speed, options.contact_lift,
        options.spring_coast ? options.servo_coast : 0.0, options.spring_lag);
    step.termination = std::move(p.termination);
    step.may_not_terminate = p.may_not_terminate;
    step.slide_forever = std::move(p.slide_forever);
    step.fallback = p.fallback;
    step.fixpoint_steps = p.steps;
    step.widened_atoms = p.widened;
    step.reached_area = p.reached.area();
    step.free_termination = p.free_termination;
    step.free_center = p.free_center;
    step.free_radius = p.free_radius;
    step.reached = std::make_shared<const ReachedSet>(std::move(p.reached));
  } else {
    DamperProjection p =
        forward_project_damper(task, cones, start, motion.target, options.stop_relative_speed,
                               options.contact_lift, options.servo_coast);
    step.termination = std::move(p.termination);
    step.may_not_terminate = p.may_not_terminate;
    step.slide_forever = std::move(p.slide_forever);
    step.fallback = p.fallback;
    step.fixpoint_steps = p.steps;
    step.reached_area = p.reached.area();
    step.reached = std::make_shared<const ReachedSet>(std::move(p.reached));
  }
  if (motion.terminate.any()) {
    // §4.5: the weakly consistent reached points join the weak sticking points (Alg 4.1 step 4). A motion
    // that can stop by sensing somewhere may terminate even where nothing sticks.
    auto sensed = std::make_shared<const ReachedSet>(sensing_termination(task, cones, motion, *step.reached));
    step.termination.unite(*sensed);
    step.may_not_terminate = step.may_not_terminate && sensed->empty();
    step.sensing = std::move(sensed);
  }
  return step;
}

class StrategyVerifier {
 public:
  StrategyVerifier(const LoadedTask& task, const Strategy& strategy, const VerifyOptions& options)
      : task_(task), strategy_(strategy), options_(options), cones_(task.cspace) {
    out_.node_step.assign(strategy.nodes.size(), -1);
    out_.spring_model = options.spring_model;
    out_.stop_relative_speed = options.stop_relative_speed;
    out_.contact_lift = options.contact_lift;
    out_.servo_coast = options.servo_coast;
  }

  VerifyResult run(const ReachedSet& start) {
    if (strategy_.nodes.empty()) {
      out_.failure = "empty strategy";
      return std::move(out_);
    }
    simulate_node(0, start, -1, -1);
    out_.reliable = out_.failed_step < 0;
    return std::move(out_);
  }

 private:
  void fail(int step, std::string why, std::vector<ReachedPiece> pieces = {}) {
    if (out_.failed_step >= 0) return;  // the first failure is reported
    out_.failed_step = step;
    out_.failure = std::move(why);
    out_.outside_goal = std::move(pieces);
  }

  // A final set (the last motion of a path, or a branch that stops) must lie in the goal.
  void check_goal(int step, const ReachedSet& final_set, const std::string& what) {
    std::vector<ReachedPiece> outside = pieces_outside_goal(task_, final_set);
    if (!outside.empty()) fail(step, what + " is not inside the goal", std::move(outside));
  }

  void simulate_node(int node_id, const ReachedSet& start, int parent_step, int branch) {
    const StrategyNode& node = strategy_.nodes[static_cast<std::size_t>(node_id)];
    const Motion* motion = task_.task.find_motion(node.motion);
    if (!motion) throw TaskError(task_.task.source_file, "motions", "no motion named '" + node.motion + "'");
    VerifyStep step = simulate(task_, cones_, *motion, start, options_);
    step.node = node_id;
    step.parent = parent_step;
    step.branch = branch;
    const int index = static_cast<int>(out_.steps.size());
    out_.node_step[static_cast<std::size_t>(node_id)] = index;
    out_.steps.push_back(std::move(step));
    const VerifyStep& s = out_.steps.back();
    if (s.may_not_terminate) {
      fail(index,
           "motion '" + motion->name + "' may never terminate: no reached atom can stick" +
               (motion->terminate.any() ? " and no reached point is consistent with its termination sets"
                                        : ""));
      return;
    }
    if (!s.slide_forever.empty()) {
      fail(index, "motion '" + motion->name + "' may slide forever on " +
                      atom_list(task_.cspace, s.slide_forever) +
                      ": its velocity error can keep it sliding without progress, faster than the stop rule");
      // Where it stops when it does is still predicted: the later steps are simulated for the report.
    }
    if (s.free_termination) {
      // Goals are contact regions, and a motion from a free-space rest is not simulated: a failure either
      // way.
      fail(index, "motion '" + motion->name + "' may come to rest in free space near its commanded position");
      return;
    }
    const ReachedSet termination = s.termination;  // `s` moves when steps grow
    if (node.next >= 0)
      simulate_node(node.next, termination, index, -1);
    else if (!node.branches.empty())
      decide(index, node, termination);
    else
      check_goal(index, termination, "termination of motion '" + motion->name + "'");
  }

  // Buckley §4.2 conditional test after step `index` with termination set r.
  void decide(int index, const StrategyNode& node, const ReachedSet& r) {
    ReachedSet remaining = r;  // points no earlier test surely takes
    bool has_else = false;
    for (std::size_t i = 0; i < node.branches.size(); ++i) {
      const StrategyBranch& b = node.branches[i];
      ReachedSet start = b.otherwise ? remaining : weakly_consistent(task_, cones_, b.when, remaining);
      if (b.otherwise) {
        has_else = true;
        remaining = ReachedSet(task_.cspace);
      } else {
        remaining = without_strongly_consistent(task_, cones_, b.when, remaining);
      }
      auto shared = std::make_shared<const ReachedSet>(std::move(start));
      out_.steps[static_cast<std::size_t>(index)].branches.push_back({shared, -1});
      if (shared->empty()) continue;  // this branch cannot be taken
      const std::string label =
          "branch " + std::to_string(i) + " (" + b.key + ") after motion '" + node.motion + "'";
      if (b.first < 0) {
        check_goal(index, *shared, "the start of " + label + ", which stops there,");
        continue;
      }
      out_.steps[static_cast<std::size_t>(index)].branches[i].step = static_cast<int>(out_.steps.size());
      simulate_node(b.first, *shared, index, static_cast<int>(i));
    }
    if (!has_else) {
      auto unmatched = std::make_shared<const ReachedSet>(std::move(remaining));
      out_.steps[static_cast<std::size_t>(index)].unmatched = unmatched;
      if (!unmatched->empty())
        fail(index, "a termination point of motion '" + node.motion + "' may pass no branch test (no 'else')",
             unmatched->pieces());
    }
  }

  const LoadedTask& task_;
  const Strategy& strategy_;
  const VerifyOptions options_;
  const AtomCones cones_;
  VerifyResult out_;
};

}  // namespace

std::vector<ReachedPiece> pieces_outside_goal(const LoadedTask& task, const ReachedSet& final_set) {
  return final_set.pieces_outside(ReachedSet::from_regions(task, task.task.goal, /*partial=*/true),
                                  kGoalRelativeTolerance * task.cspace.scale());
}

VerifyResult verify_motions(const LoadedTask& task, const std::vector<std::string>& names,
                            const VerifyOptions& options) {
  // unknown names: TaskError from simulate_node
  return verify_strategy(task, Strategy::sequence("", names), options);
}

ReachedSet start_set(const LoadedTask& task, const VerifyOptions& options) {
  ReachedSet start = ReachedSet::from_region(task, task.task.start);
  if (options.contact_lift <= 0 || task.task.start.kind != Region::Kind::kPoint) return start;
  const CSpace& c = task.cspace;
  const Vec3& p = task.task.start.points.front();
  const int nf = static_cast<int>(c.faces().size()), ne = static_cast<int>(c.edges().size());
  for (int ei = 0; ei < ne; ++ei) {
    const Edge& e = c.edges()[ei];
    if (c.distance_to_atom(p, nf + ei) > options.contact_lift) continue;
    const Vec3 d = e.b - e.a;
    const double t = std::clamp((p - e.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    start.add_edge_interval(nf + ei, t, t);
  }
  for (std::size_t vi = 0; vi < c.vertices().size(); ++vi)
    if ((c.vertices()[vi].point - p).norm() <= options.contact_lift)
      start.add_vertex(nf + ne + static_cast<int>(vi));
  return start;
}

VerifyResult verify_strategy(const LoadedTask& task, const Strategy& strategy, const VerifyOptions& options) {
  return StrategyVerifier(task, strategy, options).run(start_set(task, options));
}

VerifyResult verify_strategy_from(const LoadedTask& task, const Strategy& strategy, const ReachedSet& start,
                                  const VerifyOptions& options) {
  return StrategyVerifier(task, strategy, options).run(start);
}

}  // namespace cmt

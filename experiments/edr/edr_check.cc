// Rollouts of an EDR strategy in worlds drawn over the model parameters (edr_check.h).
#include "experiments/edr/edr_check.h"

#include <cmath>
#include <random>

#include "experiments/common/point_json.h"
#include "experiments/validation/verifier_model.h"
#include "sim/rollout.h"
#include "verifier/atom_cone.h"

namespace cmt {
namespace {

constexpr std::size_t kListed = 50;  // forbidden and missed outcomes listed in full

// The verifier's terminations in the goal over all slices, each with its atom's friction cone.
struct GoalPiece {
  ReachedPiece piece;
  FrictionCone cone;
};

std::vector<GoalPiece> goal_terminations(const EdrResult& verdict) {
  std::vector<GoalPiece> out;
  for (const EdrSlice& s : verdict.slices) {
    if (!s.success) continue;
    for (ReachedPiece& p : s.success->pieces())
      out.push_back({p, atom_friction_cone(s.task->cspace, p.atom)});
  }
  return out;
}

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  Vec3 v(g(rng), g(rng), g(rng));
  while (v.norm() < 1e-12) v = Vec3(g(rng), g(rng), g(rng));
  return v.normalized();
}

// One sensor reading at the end: the position offset (within eps_s; on the sphere in extreme mode) and the
// force direction turned by up to theta_f (exactly theta_f in extreme mode) about a random axis.
struct Reading {
  Vec3 position = Vec3::Zero();
  Vec3 force_direction = Vec3::Zero();  // zero: no contact force to sense
};

Reading read_sensors(const Vec3& end, const Vec3& force, const Uncertainty& u, SampleMode mode,
                     std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  Reading r;
  const double radius = mode == SampleMode::kExtreme ? u.eps_s : u.eps_s * std::cbrt(unit(rng));
  r.position = end + radius * random_unit(rng);
  if (force.norm() <= 1e-9) return r;
  const Vec3 f = force.normalized();
  const Vec3 axis = f.cross(random_unit(rng)).normalized();
  const double angle = mode == SampleMode::kExtreme ? u.theta_f : u.theta_f * unit(rng);
  r.force_direction = Eigen::AngleAxisd(angle, axis) * f;
  return r;
}

// The EDR termination predicate (edr_check.h).
bool signals_success(const Reading& r, const std::vector<GoalPiece>& goal, const Uncertainty& u,
                     double margin) {
  if (r.force_direction.isZero()) return false;
  ReachedPiece at;
  at.polygon = {r.position};
  for (const GoalPiece& g : goal)
    if (piece_distance_lower_bound(at, g.piece) <= u.eps_s + margin &&
        g.cone.angle_lower_bound(r.force_direction) <= u.theta_f)
      return true;
  return false;
}

std::vector<double> draw_world(const Task& task, std::mt19937_64& rng) {
  std::vector<double> values;
  for (const ModelParameter& p : task.model_error)
    values.push_back(std::uniform_real_distribution<double>(p.min, p.max)(rng));
  return values;
}

}  // namespace

EdrCheck check_edr(const Task& task, const std::vector<std::string>& motions, const EdrResult& verdict,
                   const EdrCheckOptions& options) {
  EdrCheck out;
  const std::vector<GoalPiece> goal = goal_terminations(verdict);
  double scale = 0;
  for (const EdrSlice& s : verdict.slices) scale = std::max(scale, s.task->cspace.scale());
  const double margin = kEdrPositionRelativeMargin * scale;
  const Strategy strategy = Strategy::sequence("edr", motions);
  std::mt19937_64 worlds_rng(options.seed);
  for (int w = 0; w < options.worlds; ++w) {
    const std::vector<double> values = draw_world(task, worlds_rng);
    const auto world = load_task_slice(task, values);
    const bool guaranteed = verify_motions(*world, motions, rollout_verify_options(*world)).reliable;
    SimOptions sim;
    sim.form = ControllerForm::kImpedance;
    sim.mode = options.mode;
    const auto scene = RolloutScene::build(world, sim);
    const std::vector<RolloutOutcome> rollouts =
        run_rollouts(scene, strategy, options.rollouts_per_world,
                     options.seed + static_cast<std::uint64_t>(w), options.threads);
    nlohmann::json counts = {{"success", 0},       {"failure_signalled", 0}, {"false_success", 0},
                             {"false_failure", 0}, {"missed_success", 0},    {"timeout", 0},
                             {"unstable", 0}};
    for (const RolloutOutcome& o : rollouts) {
      std::string outcome;
      bool timed_out = false;
      for (const MotionOutcome& m : o.motions) timed_out = timed_out || m.termination == Termination::kNone;
      if (o.unstable) {
        outcome = "unstable";
      } else if (timed_out || o.motions.size() < motions.size()) {
        outcome = "timeout";
      } else {
        std::seed_seq stream{options.seed, static_cast<std::uint64_t>(w), static_cast<std::uint64_t>(o.index),
                             std::uint64_t{0xED2}};
        std::mt19937_64 rng(stream);
        const Reading r =
            read_sensors(o.end, o.motions.back().contact_force, task.uncertainty, options.mode, rng);
        const bool in_goal = scene->goal_distance(o.end) <= scene->atom_tolerance();
        const bool reported = signals_success(r, goal, task.uncertainty, margin);
        outcome = reported ? (in_goal ? "success" : "false_success")
                           : (!in_goal     ? "failure_signalled"
                              : guaranteed ? "false_failure"
                                           : "missed_success");
      }
      counts[outcome] = counts[outcome].get<int>() + 1;
      const EdrCheckOutcome record{values, w, o.index, outcome, o.end};
      if ((outcome == "false_success" || outcome == "false_failure") && out.forbidden.size() < kListed)
        out.forbidden.push_back(record);
      if (outcome == "missed_success" && out.missed.size() < kListed) out.missed.push_back(record);
    }
    out.rollouts += static_cast<int>(rollouts.size());
    out.success += counts["success"].get<int>();
    out.failure_signalled += counts["failure_signalled"].get<int>();
    out.false_success += counts["false_success"].get<int>();
    out.false_failure += counts["false_failure"].get<int>();
    out.missed_success += counts["missed_success"].get<int>();
    out.timeout += counts["timeout"].get<int>();
    out.unstable += counts["unstable"].get<int>();
    out.worlds.push_back({{"params", values}, {"guaranteed", guaranteed}, {"outcomes", counts}});
  }
  return out;
}

nlohmann::json edr_check_json(const Task& task, const EdrCheck& check) {
  auto listed = [&](const std::vector<EdrCheckOutcome>& list) {
    nlohmann::json out = nlohmann::json::array();
    for (const EdrCheckOutcome& o : list)
      out.push_back({{"params", o.values},
                     {"world", o.world},
                     {"index", o.index},
                     {"outcome", o.outcome},
                     {"end", point_json(o.end, task.dimension)}});
    return out;
  };
  return {{"rollouts", check.rollouts},
          {"outcomes",
           {{"success", check.success},
            {"failure_signalled", check.failure_signalled},
            {"false_success", check.false_success},
            {"false_failure", check.false_failure},
            {"missed_success", check.missed_success},
            {"timeout", check.timeout}}},
          {"unstable", check.unstable},
          {"forbidden", listed(check.forbidden)},
          {"missed", listed(check.missed)},
          {"worlds", check.worlds}};
}

}  // namespace cmt

// Rollouts of an EDR strategy in worlds drawn over the model parameters (edr_check.h).
#include "experiments/edr/edr_check.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <random>
#include <sstream>

#include "experiments/common/point_json.h"
#include "experiments/validation/validation.h"
#include "experiments/validation/verifier_model.h"
#include "sim/rollout.h"
#include "verifier/atom_cone.h"

namespace cmt {
namespace {

constexpr std::size_t kListed = 50;  // forbidden and missed outcomes listed in full
constexpr const char* kEdrOutcomes[] = {"success",       "failure_signalled", "false_success",
                                        "false_failure", "missed_success",    "timeout",
                                        "unstable"};

// The verifier's terminations in the goal over all slices and the sweeps between adjacent ones (edr.h), each
// as a convex set with its atom's friction cone.
struct GoalPiece {
  ConvexPiece hull;
  FrictionCone cone;
};

std::vector<GoalPiece> goal_terminations(const EdrResult& verdict) {
  std::vector<GoalPiece> out;
  for (const EdrSlice& s : verdict.slices) {
    if (!s.success) continue;
    for (const ReachedPiece& p : s.success->pieces())
      out.push_back({convex_piece(p), atom_friction_cone(s.task->cspace, p.atom)});
  }
  for (const SlicePiece& p : verdict.swept_success)
    out.push_back({convex_piece(p.piece), atom_friction_cone(*p.cspace, p.piece.atom)});
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
  for (const GoalPiece& g : goal)
    if (point_to_piece(r.position, g.hull) <= u.eps_s + margin &&
        g.cone.angle_lower_bound(r.force_direction) <= u.theta_f)
      return true;
  return false;
}

std::vector<double> draw_world(const Task& task, std::mt19937_64& rng) {
  std::vector<double> values;
  for (const ModelParameter& p : task.model_error)
    values.push_back(p.discrete()
                         ? p.values[std::uniform_int_distribution<std::size_t>(0, p.values.size() - 1)(rng)]
                         : std::uniform_real_distribution<double>(p.min, p.max)(rng));
  return values;
}

// ` --world NAME=VALUE` per parameter, at full precision (cmt rollout reads the task at those values).
std::string world_flags(const Task& task, const std::vector<double>& values) {
  std::ostringstream os;
  os << std::setprecision(17);
  for (std::size_t p = 0; p < values.size(); ++p)
    os << " --world " << task.model_error[p].name << "=" << values[p];
  return os.str();
}

// One world: its task, the verifier's prediction there and its rollouts.
struct World {
  int index = 0;
  std::vector<double> values;
  std::shared_ptr<const LoadedTask> task;
  ValidationResult validation;  // prediction, rollouts, soundness and coverage
  bool guaranteed = false;      // the world's verification is reliable: success must be signalled
};

World run_world(const Task& task, const Strategy& strategy, int index, std::vector<double> values,
                int rollouts, const EdrCheckOptions& options) {
  World w{index, std::move(values), nullptr, {}, false};
  w.task = load_task_slice(task, w.values);
  ValidationResult& v = w.validation;
  v.task = task.name;
  v.strategy = strategy.name;
  v.options.seed = options.seed + static_cast<std::uint64_t>(index);
  v.options.mode = options.mode;
  v.prediction = verify_motions(*w.task, strategy.motions, rollout_verify_options(*w.task));
  w.guaranteed = v.prediction.reliable;
  SimOptions sim;
  sim.form = ControllerForm::kImpedance;
  sim.mode = options.mode;
  v.rollouts =
      run_rollouts(RolloutScene::build(w.task, sim), strategy, rollouts, v.options.seed, options.threads);
  score_soundness(*w.task, &v);
  score_coverage(*w.task, &v);
  return w;
}

// The EDR outcome of one rollout (edr_check.h).
std::string classify(const World& w, const RolloutOutcome& o, const std::vector<GoalPiece>& goal,
                     double margin, const EdrCheckOptions& options) {
  bool timed_out = o.motions.size() < w.validation.prediction.steps.size();
  for (const MotionOutcome& m : o.motions) timed_out = timed_out || m.termination == Termination::kNone;
  if (o.unstable) return "unstable";
  if (timed_out) return "timeout";
  std::seed_seq stream{options.seed, static_cast<std::uint64_t>(w.index), static_cast<std::uint64_t>(o.index),
                       std::uint64_t{0xED2}};
  std::mt19937_64 rng(stream);
  const Uncertainty& u = w.task->task.uncertainty;
  const Reading r = read_sensors(o.end, o.motions.back().contact_force, u, options.mode, rng);
  const bool in_goal = o.success;
  if (signals_success(r, goal, u, margin)) return in_goal ? "success" : "false_success";
  return !in_goal ? "failure_signalled" : w.guaranteed ? "false_failure" : "missed_success";
}

void count(EdrCheck* out, const std::string& outcome) {
  int* counter = outcome == "success"             ? &out->success
                 : outcome == "failure_signalled" ? &out->failure_signalled
                 : outcome == "false_success"     ? &out->false_success
                 : outcome == "false_failure"     ? &out->false_failure
                 : outcome == "missed_success"    ? &out->missed_success
                 : outcome == "timeout"           ? &out->timeout
                                                  : &out->unstable;
  ++*counter;
  ++out->rollouts;
}

// The world's rollouts classified and its soundness added to `out`.
void score_world(const Task& task, const World& w, const std::vector<GoalPiece>& goal, double margin,
                 const EdrCheckOptions& options, EdrCheck* out) {
  const ValidationResult& v = w.validation;
  const std::string flags = world_flags(task, w.values);
  auto replay = [&](int index) {
    return replay_command(*w.task, v.strategy, v.options.seed, index, options.mode,
                          ControllerForm::kImpedance) +
           flags;
  };
  nlohmann::json counts = nlohmann::json::object();
  for (const char* k : kEdrOutcomes) counts[k] = 0;
  for (const RolloutOutcome& o : v.rollouts) {
    const std::string outcome = classify(w, o, goal, margin, options);
    count(out, outcome);
    counts[outcome] = counts[outcome].get<int>() + 1;
    const EdrCheckOutcome record{w.values, w.index, o.index, outcome, o.end, replay(o.index)};
    if ((outcome == "false_success" || outcome == "false_failure") && out->forbidden.size() < kListed)
      out->forbidden.push_back(record);
    if (outcome == "missed_success" && out->missed.size() < kListed) out->missed.push_back(record);
  }
  out->ends += static_cast<int>(v.ends.size());
  out->outside += v.outside;
  for (const ObservedEnd& e : v.worst)
    if (out->outside_ends.size() < static_cast<std::size_t>(kMaxWorstEnds))
      out->outside_ends.push_back({w.values, w.index, e.rollout, "outside", e.end, replay(e.rollout)});
  out->worlds.push_back({{"params", w.values},
                         {"replay", replay(static_cast<int>(v.rollouts.size()) - 1)},
                         {"guaranteed", w.guaranteed},
                         {"outcomes", counts},
                         {"outside", v.outside},
                         {"coverage", v.coverage}});
}

}  // namespace

EdrCheck check_edr(const Task& task, const std::string& strategy_name, const EdrResult& verdict,
                   const EdrCheckOptions& options) {
  EdrCheck out;
  const std::vector<GoalPiece> goal = goal_terminations(verdict);
  double scale = 0;
  for (const EdrSlice& s : verdict.slices) scale = std::max(scale, s.task->cspace.scale());
  const double margin = kEdrContactRelativeSlack * scale;
  const Strategy& strategy = task.strategy_named(strategy_name);
  std::mt19937_64 worlds_rng(options.seed);
  const int per_world = std::max(1, options.rollouts_per_world);
  double coverage_sum = 0;
  int worlds = 0;
  for (std::int64_t done = 0; done < options.rollouts; done += per_world, ++worlds) {
    const int rollouts = static_cast<int>(std::min<std::int64_t>(per_world, options.rollouts - done));
    const World w = run_world(task, strategy, worlds, draw_world(task, worlds_rng), rollouts, options);
    score_world(task, w, goal, margin, options, &out);
    coverage_sum += w.validation.coverage;
  }
  out.soundness = out.ends == 0 ? 1.0 : static_cast<double>(out.ends - out.outside) / out.ends;
  out.coverage = worlds == 0 ? 0.0 : coverage_sum / worlds;
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
                     {"end", point_json(o.end, task.dimension)},
                     {"replay", o.replay}});
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
          {"missed_success", check.missed_success},
          {"ends", check.ends},
          {"outside", check.outside},
          {"soundness", check.soundness},
          {"coverage", check.coverage},
          {"outside_ends", listed(check.outside_ends)},
          {"forbidden", listed(check.forbidden)},
          {"missed", listed(check.missed)},
          {"worlds", check.worlds}};
}

}  // namespace cmt

// `cmt plan TASK --states [--max-atoms K] [--friction MU] [--eps-s E] [--theta-f T] [--list] --json`: the
// primitive states of Buckley's planner (§6.4.1, Table 6.3). `cmt plan TASK [--termination S] [--max-atoms K]
// [--max-motions M] --json [-o OUT.yaml] [--check N] [--extremes N]`: the planner's search over sticking
// arcs, or with the goal's sensed-position set (S = position) and sensed-force cones (S = force): types 1, 2
// and 3, §6.5–6.7, goal_stops.h; the planned strategy checked by the verifier, by rollouts and by §6.3.4's
// extreme-point experiment (docs/planner.md).
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/common/task_motions.h"
#include "experiments/common/task_overrides.h"
#include "experiments/plan/chain_verdicts.h"
#include "experiments/plan/extreme_points.h"
#include "experiments/validation/validation.h"
#include "experiments/validation/verifier_model.h"
#include "models/input_error.h"
#include "models/loaded_task.h"
#include "verifier/planner/goal_stops.h"
#include "verifier/planner/primitive_states.h"
#include "verifier/planner/search.h"
#include "verifier/planner/task_atoms.h"
#include "verifier/planner/verifier_check.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

struct PlanCli {
  std::string task, out, termination = "sticking";
  bool states = false, list = false, no_chain_projections = false;
  int max_atoms = 0, max_motions = 3, max_expansions = 200;
  // Rollouts of the planned strategy (0: none); threads of the rollouts and processes of the search's
  // verifier checks.
  int check = 0, threads = 1;
  int extremes = 0;  // rollouts per point of the extreme-point experiment (0: none)
  std::vector<double> grow = {1, 2, 4};
  std::uint64_t seed = 1;
  long long max_states = 1'000'000;
  std::optional<double> friction, eps_s, theta_f;
};

// The task's text with the given friction and sensing bounds written in (task_overrides.h: checked like a
// file).
std::string text_with_overrides(const PlanCli& cli) {
  const std::string text = read_task_text(cli.task);
  const auto base = load_task_from_string(text, cli.task);
  ParamSet params;
  const auto set = [&](ParamTarget::Kind kind, const std::string& name, const std::optional<double>& v,
                       const std::string& option) {
    if (v) params.push_back({{kind, name}, {*v}, option});
  };
  set(ParamTarget::Kind::kFriction, "", cli.friction, "--friction");
  set(ParamTarget::Kind::kUncertainty, "eps_s", cli.eps_s, "--eps-s");
  set(ParamTarget::Kind::kUncertainty, "theta_f", cli.theta_f, "--theta-f");
  if (params.empty()) return text;
  return apply_overrides(text, base->task, params);
}

std::shared_ptr<const LoadedTask> task_with_overrides(const PlanCli& cli) {
  return load_task_from_string(text_with_overrides(cli), cli.task);
}

nlohmann::json atom_names(const CSpace& c, const std::vector<int>& atoms) {
  nlohmann::json names = nlohmann::json::array();
  for (int a : atoms)
    names.push_back(a == c.atom_count()               ? std::string("free")
                    : a == planner::goal_stop_atom(c) ? std::string("goal")
                                                      : c.atom_name(a));
  return names;
}

nlohmann::json states_json(const CSpace& c, const std::vector<planner::State>& states) {
  nlohmann::json out = nlohmann::json::array();
  for (const planner::State& s : states) out.push_back(atom_names(c, s));
  return out;
}

// A set of commanded positions as its convex pieces: half-spaces [nx, ny, nz, offset] (n . x <= offset) and
// vertices.
nlohmann::json cpositions_json(const planner::CPositionSet& set, int dimension) {
  nlohmann::json pieces = nlohmann::json::array();
  for (const planner::ConvexPiece& piece : set.pieces()) {
    nlohmann::json hs = nlohmann::json::array(), vs = nlohmann::json::array();
    for (const HalfSpace& h : piece.halfspaces)
      hs.push_back({h.normal.x(), h.normal.y(), h.normal.z(), h.offset});
    for (const Vec3& v : piece.vertices) vs.push_back(point_json(v, dimension));
    pieces.push_back({{"halfspaces", hs}, {"vertices", vs}});
  }
  return pieces;
}

// Force cones as {direction, angle}.
nlohmann::json cones_json(const std::vector<ForceCone>& cones, int dimension) {
  nlohmann::json out = nlohmann::json::array();
  for (const ForceCone& f : cones)
    out.push_back({{"direction", point_json(f.direction, dimension)}, {"angle", f.angle}});
  return out;
}

// Axis boxes as {min, max} points.
nlohmann::json boxes_json(const std::vector<AxisBox>& boxes, int dimension) {
  nlohmann::json out = nlohmann::json::array();
  for (const AxisBox& b : boxes)
    out.push_back({{"min", point_json(b.min, dimension)}, {"max", point_json(b.max, dimension)}});
  return out;
}

// planned_1, planned_2, ...; when the task already has such a motion (a task written by -o planned again):
// planned_2_1, ..., the first prefix none of whose n names is taken.
std::vector<std::string> planned_motion_names(const Task& task, std::size_t n) {
  for (int k = 1;; ++k) {
    const std::string prefix = k == 1 ? "planned_" : "planned_" + std::to_string(k) + "_";
    std::vector<std::string> names;
    for (std::size_t i = 0; i < n; ++i) names.push_back(prefix + std::to_string(i + 1));
    if (std::none_of(names.begin(), names.end(), [&](const std::string& m) { return task.find_motion(m); }))
      return names;
  }
}

// The planned strategy written into the task (decision-free plans only), verified, and written to -o. Returns
// the planned task (nothing when no strategy is written).
std::shared_ptr<const LoadedTask> add_strategy(const PlanCli& cli, const std::string& text,
                                               const LoadedTask& task, const planner::PlanResult& plan,
                                               const std::vector<std::string>& names,
                                               const MotionTermination& sensed, nlohmann::json& out) {
  if (plan.steps.empty()) {
    out["strategy"] = nlohmann::json::array();
    out["strategy_reason"] = "the start lies in the goal: no motion is needed";
    return nullptr;
  }
  if (!plan.decision_free) {
    out["strategy"] = nullptr;
    out["strategy_reason"] =
        "the plan branches on sensed states; only decision-free plans are written as strategies (and "
        "verified)";
    return nullptr;
  }
  std::vector<AddedMotion> motions;
  for (std::size_t i = 0; i < plan.steps.size(); ++i)
    motions.push_back(
        {names[i], Motion::Kind::kSpring, plan.steps[i].arc.commanded, false, sensed.position, sensed.force});
  const std::string name = free_strategy_name(task.task, "planned");
  const std::string planned = task_yaml_with_motions(text, task.task, motions, name, "the planner's");
  const auto planned_task = load_task_from_string(planned, cli.task);
  const Strategy& strategy = planned_task->task.strategy_named(name);
  out["strategy"] = strategy.motions;
  out["strategy_name"] = name;
  // The search's chain check already verified these commanded positions under this model from the start.
  if (plan.chain_verified) {
    out["verified"] = {{"reliable", true}, {"failure", ""}};
  } else {
    const VerifyResult v = verify_strategy(*planned_task, strategy, rollout_verify_options(*planned_task));
    out["verified"] = {{"reliable", v.reliable}, {"failure", v.failure}};
  }
  if (cli.check > 0) {  // the physics check: `cmt validate` of the planned strategy
    ValidateOptions options;
    options.n = cli.check;
    options.seed = cli.seed;
    options.threads = cli.threads;
    const nlohmann::json r = validation_json(*planned_task, run_validation(planned_task, name, options));
    out["check"] = {{"rollouts", r["rollouts"]},
                    {"successes", r["successes"]},
                    {"outside", r["outside"]},
                    {"soundness", r["soundness"]},
                    {"seed", cli.seed}};
  }
  if (!cli.out.empty()) {
    std::ofstream file(cli.out);
    if (!(file << planned)) throw InputError(cli.out, "-o", "cannot write the planned task");
    out["written"] = cli.out;
  }
  return planned_task;
}

// §6.3.4's experiment (experiments/plan/extreme_points.h) on the planned strategy: JSON `extremes`.
void add_extremes(const PlanCli& cli, const std::shared_ptr<const LoadedTask>& planned,
                  const planner::PlanResult& plan, const std::vector<std::string>& names,
                  nlohmann::json& out) {
  std::vector<PlannedMotionCell> cells;
  for (std::size_t i = 0; i < plan.steps.size(); ++i)
    cells.push_back({names[i], plan.steps[i].arc.commanded, plan.steps[i].arc.arc.cpositions});
  ExtremePointOptions options;
  options.rollouts = cli.extremes;
  options.grow = cli.grow;
  options.seed = cli.seed;
  options.threads = cli.threads;
  const std::vector<MotionExtremes> result =
      run_extreme_points(planned, out["strategy_name"].get<std::string>(), cells, options);
  out["extremes"] = extreme_points_json(*planned, result, options);
}

// The planner's request (every field but the verifier callbacks), its goal stops and the termination of every
// planned motion, from the task and the options.
struct PlanSetup {
  planner::PlanRequest request;
  planner::GoalStops stops;
  MotionTermination terminate;
};

PlanSetup plan_setup(const LoadedTask& task, const PlanCli& cli) {
  const CSpace& c = task.cspace;
  const Uncertainty& u = task.task.uncertainty;
  PlanSetup out;
  planner::PlanRequest& request = out.request;
  planner::GoalStops& stops = out.stops;
  request.start_atoms = planner::start_atoms(task);
  request.start_point = planner::region_centroid(task.task.start);
  request.goal_atom = planner::goal_atoms(task);
  stops.partial_faces = planner::partial_goal_faces(task, request.goal_atom);
  request.goal_near.assign(request.goal_atom.size(), false);
  for (const planner::PartialGoalFace& f : stops.partial_faces)
    request.goal_near[static_cast<std::size_t>(f.atom)] = true;
  if (cli.termination == "force") stops.sensed_forces = planner::goal_sensed_forces(task);
  if (cli.termination == "position" || cli.termination == "force") {
    stops.sensed_positions = planner::goal_sensed_positions(task, stops.sensed_forces);
    stops.senses = planner::sensing_atoms(task, stops.sensed_positions, stops.sensed_forces);
    out.terminate.position = stops.sensed_positions;
    out.terminate.force = stops.sensed_forces;
  }
  request.eps_s = u.eps_s;
  request.theta_f = u.theta_f;
  request.max_atoms = cli.max_atoms > 0 ? cli.max_atoms : c.atom_count();
  request.max_motions = cli.max_motions;
  request.max_expansions = cli.max_expansions;
  request.chain_projections = !cli.no_chain_projections;
  return out;
}

// The plan's motions (name, commanded position, depth, source, cpositions, spositions, sforces) and steps
// (state, motion, targets, heads) into out["motions"] and out["steps"].
void add_plan_steps(const LoadedTask& task, const planner::PlanResult& plan,
                    const std::vector<std::string>& names, const MotionTermination& sensed,
                    nlohmann::json* out) {
  const CSpace& c = task.cspace;
  nlohmann::json motions = nlohmann::json::array(), steps = nlohmann::json::array();
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    const planner::GraphArc& arc = plan.steps[i].arc;
    motions.push_back({{"name", names[i]},
                       {"commanded", point_json(arc.commanded, task.task.dimension)},
                       {"depth", arc.depth},
                       {"source", arc.from_start_projection   ? "start projection"
                                  : arc.from_chain_projection ? "chain projection"
                                                              : "simulation"},
                       {"cpositions", cpositions_json(arc.arc.cpositions, task.task.dimension)},
                       {"spositions", boxes_json(sensed.position, task.task.dimension)},
                       {"sforces", cones_json(sensed.force, task.task.dimension)}});
    steps.push_back({{"state", atom_names(c, plan.steps[i].state)},
                     {"motion", names[i]},
                     {"targets", atom_names(c, arc.arc.targets)},
                     {"heads", states_json(c, arc.heads)}});
  }
  (*out)["motions"] = motions;
  (*out)["steps"] = steps;
}

// Success: a plan whose strategy the verifier found reliable (or no motion needed) and whose rollouts, if
// run, all reached the goal, those commanded at its cells' vertices (--extremes) too. A branching plan is
// not verified: exit 1 with its strategy_reason.
bool plan_verified(const planner::PlanResult& plan, const nlohmann::json& out) {
  bool verified = plan.found && (plan.steps.empty() ||
                                 (out.contains("verified") && out["verified"]["reliable"].get<bool>()));
  if (out.contains("check"))
    verified =
        verified && out["check"]["outside"] == 0 && out["check"]["successes"] == out["check"]["rollouts"];
  if (out.contains("extremes")) verified = verified && out["extremes"]["vertices_all_succeed"].get<bool>();
  return verified;
}

void run_plan_search(const PlanCli& cli, CommandState& state) {
  const auto start = std::chrono::steady_clock::now();
  const std::string text = text_with_overrides(cli);
  const auto task = load_task_from_string(text, cli.task);
  if (task->task.dimension != 3)
    throw InputError(cli.task, "dimension",
                     "the planner needs a 3-D task (its commanded positions vary in y)");
  const CSpace& c = task->cspace;
  PlanSetup setup = plan_setup(*task, cli);
  planner::PlanRequest& request = setup.request;
  const VerifyOptions verify_options = rollout_verify_options(*task);  // as `cmt verify`
  // The search's verifier checks, memoized, verified ahead in up to `--threads` forked children.
  ChainVerdicts verdicts(*task, verify_options, setup.terminate, cli.threads);
  request.confirm_chain = [&](const std::vector<Vec3>& commanded) { return verdicts.get(commanded); };
  request.start_targets = [&](const Vec3& commanded) -> std::optional<std::vector<int>> {
    const planner::ChainVerdict v = verdicts.get({commanded});
    if (v.ends.empty()) return std::nullopt;
    return v.ends.front();
  };
  request.prefetch = [&](const std::vector<std::vector<Vec3>>& chains) { verdicts.prefetch(chains); };
  request.lookahead = cli.threads;
  const MotionTermination sensed = setup.terminate;  // P_s and F_s (empty for sticking termination)
  planner::AtomSimulation simulation(c, task->task.uncertainty, std::move(setup.stops));
  planner::PlanResult plan;
  if (cli.termination != "sticking" && sensed.position.empty())
    plan.reason =
        "no sensed-position set: no goal polygon on an axis-aligned plane keeps eps_s clear of the contacts "
        "outside the goal that may sense its force (docs/planner.md, \"Goal stops\")";
  else if (cli.termination == "force" && sensed.force.empty())
    plan.reason = "no sensed-force set: no goal polygon lies on a face with a circular friction cone";
  else
    plan = planner::plan_sticking(simulation, c, request);
  verdicts.stop();  // checks verified ahead that the search did not need
  const double search_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json out = {{"task", task->task.name},
                        {"task_file", std::filesystem::absolute(cli.task).string()},
                        {"found", plan.found},
                        {"termination", cli.termination},
                        {"spositions", boxes_json(sensed.position, task->task.dimension)},
                        {"sforces", cones_json(sensed.force, task->task.dimension)},
                        {"start_states", states_json(c, plan.start_states)},
                        {"expanded", plan.expanded},
                        {"arcs", plan.arcs},
                        {"confirmed", plan.confirmed},
                        {"rejected", plan.rejected},
                        {"widened", plan.widened},
                        {"decision_free", plan.decision_free},
                        {"chains_checked", plan.chains_checked},
                        {"start_projections", plan.start_projections},
                        {"chain_projections", plan.chain_projections},
                        {"search_seconds", search_seconds},
                        {"verifier_seconds", verdicts.seconds()}};
  const std::vector<std::string> names = planned_motion_names(task->task, plan.steps.size());
  add_plan_steps(*task, plan, names, sensed, &out);
  if (plan.found) {
    const auto planned = add_strategy(cli, text, *task, plan, names, sensed, out);
    if (planned && cli.extremes > 0) add_extremes(cli, planned, plan, names, out);
  } else {
    out["reason"] = plan.reason, out["strategy"] = nullptr;
  }
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const bool verified = plan_verified(plan, out);
  if (state.json)
    print_json(out);
  else
    std::cout << (plan.found ? "found: " + out["strategy"].dump() + " " + out["motions"].dump()
                             : "not found: " + plan.reason)
              << "\n";
  state.exit_status = verified ? kExitSuccess : kExitFailureFound;
}

void run_plan(const PlanCli& cli, CommandState& state) {
  if (!cli.states) return run_plan_search(cli, state);
  const auto start = std::chrono::steady_clock::now();
  const auto task = task_with_overrides(cli);
  const CSpace& c = task->cspace;
  const Uncertainty& u = task->task.uncertainty;
  const planner::PrimitiveStates p = planner::primitive_states(c, u.eps_s, u.theta_f, cli.max_atoms,
                                                               static_cast<std::size_t>(cli.max_states));
  nlohmann::json by_size = nlohmann::json::object();
  for (std::size_t k = 1; k < p.by_size.size(); ++k) by_size[std::to_string(k)] = p.by_size[k];
  nlohmann::json out = {{"task", task->task.name},
                        {"faces", c.faces().size()},
                        {"edges", c.edges().size()},
                        {"vertices", c.vertices().size()},
                        {"atoms", p.atoms},
                        {"friction", task->task.friction},
                        {"eps_s", u.eps_s},
                        {"theta_f", u.theta_f},
                        {"max_atoms", cli.max_atoms},
                        {"primitive_states", p.states.size()},
                        {"by_size", by_size},
                        {"truncated", p.truncated},
                        {"max_states", cli.max_states}};
  if (cli.list) {
    nlohmann::json states = nlohmann::json::array();
    for (const std::vector<int>& s : p.states) {
      nlohmann::json names = nlohmann::json::array();
      for (int a : s) names.push_back(c.atom_name(a));
      states.push_back(names);
    }
    out["states"] = states;
  }
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (state.json) {
    print_json(out);
  } else {
    std::cout << task->task.name << ": " << p.atoms << " atoms, " << p.states.size() << " primitive states"
              << (cli.max_atoms > 0 ? " of at most " + std::to_string(cli.max_atoms) + " atoms" : "")
              << (p.truncated ? " (truncated)" : "") << "; by size:";
    for (std::size_t k = 1; k < p.by_size.size(); ++k) std::cout << " " << k << ": " << p.by_size[k];
    std::cout << "\n";
  }
  state.exit_status = kExitSuccess;
}

}  // namespace

void add_plan_command(CLI::App& app, CommandState& state) {
  auto cli = std::make_shared<PlanCli>();
  auto* cmd = app.add_subcommand(
      "plan",
      "Buckley's planner (ch. 6): a strategy of spring motions that sticks in the goal, or (--states) "
      "its primitive states");
  cmd->add_option("TASK", cli->task, "task YAML file")->required();
  cmd->add_flag(
      "--states", cli->states,
      "count the primitive states: sets of atoms no two of which sensing can tell apart (Sec 6.4.1)");
  cmd->add_option("--max-atoms", cli->max_atoms, "only states of at most K atoms (default 0: any number)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--max-motions", cli->max_motions, "the longest branch of a planned strategy (default 3)")
      ->check(CLI::Range(1, 20));
  cmd->add_option("--max-expansions", cli->max_expansions, "states the search may expand (default 200)")
      ->check(CLI::Range(1, 100000));
  cmd->add_flag("--no-chain-projections", cli->no_chain_projections,
                "no continuations of the start projections (later motions from the simulation's cells only)");
  cmd->add_option(
         "--termination", cli->termination,
         "how the planned motions end: sticking (the default, type 1), position (type 2: also on "
         "sensing a position in the goal's sensed-position set) or force (type 3: on sensing a position "
         "in that set, grown to the goal's edges where force tells walls apart, and a force in the goal "
         "faces' sensed-force cones)")
      ->check(CLI::IsMember({"sticking", "position", "force"}));
  cmd->add_option("--check", cli->check,
                  "run N MuJoCo rollouts of the planned strategy (`cmt validate`) and report them as check")
      ->check(CLI::Range(0, 1'000'000));
  cmd->add_option("--extremes", cli->extremes,
                  "Sec 6.3.4's experiment: N rollouts with each motion commanded at each vertex of its "
                  "cpositions, and at the vertices of the cpositions grown by --grow (JSON extremes)")
      ->check(CLI::Range(0, 1'000'000));
  cmd->add_option("--grow", cli->grow, "growths of the cpositions for --extremes, in eps_p (default 1 2 4)")
      ->check(CLI::Range(0.0, 1000.0));
  cmd->add_option("--seed", cli->seed, "master seed of the --check and --extremes rollouts (default 1)");
  cmd->add_option(
         "--threads", cli->threads,
         "threads of the --check and --extremes rollouts, and verifier checks of the search run at once "
         "(forked processes; default 1); the plan does not depend on it")
      ->check(CLI::Range(1, 256));
  cmd->add_option("-o", cli->out,
                  "write the task with the planned strategy added (spring motions planned_1, ...)");
  cmd->add_option("--max-states", cli->max_states,
                  "stop after this many states (default 10^6); truncated: true says the counts are partial")
      ->check(CLI::Range(1LL, 100'000'000LL));
  cmd->add_flag("--list", cli->list, "also list every state's atoms");
  cmd->add_option("--friction", cli->friction, "use this friction coefficient instead of the task's");
  cmd->add_option("--eps-s", cli->eps_s, "use this position-sensing error instead of the task's");
  cmd->add_option("--theta-f", cli->theta_f, "use this force-sensing error instead of the task's");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([cli, &state] { run_plan(*cli, state); });
}

}  // namespace cmt

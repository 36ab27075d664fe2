// `cmt backproject TASK --motions M1,M2,... [--json] [--view DIR] [--check N --points K --seed S --threads T
// --check-mode extreme|uniform --check-dir DIR]`: the strong backprojections of a chain of damper and spring
// motions (Buckley §5.4, Alg 5.2, §5.4.3 damper, §5.4.4 spring under the via-point model; docs/teaching.md
// "Backprojections"). From the goal backwards: S_k = S_{m_k}(S_{k+1}), S_{n+1} = the goal. Prints per motion
// the base B (where it may stop outside its target), the weak backprojection W(B) and S, whether the task's
// start lies in S_1, and the forward verifier's verdict for the chain from S_1 under the rollouts' model (a
// chain with a spring: the via-point model, the position form's); --check runs MuJoCo rollouts of the chain
// from points of S_1 (a chain with a spring: the position form). Exit 0: the start lies in S_1 (and the
// check, if run, had no failure); 1: not; 2: bad input.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <sstream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/cli/teach_view.h"
#include "experiments/report/view_page.h"
#include "experiments/teach/backprojection_check.h"
#include "experiments/validation/verifier_model.h"
#include "experiments/validation/verify_json.h"
#include "models/input_error.h"
#include "models/loaded_task.h"
#include "verifier/backprojection.h"
#include "verifier/verify.h"

namespace cmt {
namespace {

struct BackprojectCli {
  std::string task, motions, check_mode = "extreme", check_dir, view;
  int check = 0, points = 20, threads = 1;
  std::uint64_t seed = 1;
};

std::vector<std::string> split_names(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream in(list);
  for (std::string name; std::getline(in, name, ',');)
    if (!name.empty()) out.push_back(name);
  return out;
}

// The chain's motions, checked: known, and without sensing termination (the backprojection base counts
// stops by sticking only).
std::vector<std::string> chain_of(const LoadedTask& task, const BackprojectCli& cli) {
  const std::vector<std::string> chain = split_names(cli.motions);
  if (chain.empty()) throw InputError(cli.task, "--motions", "give one or more motions, first first");
  for (const std::string& name : chain) {
    const Motion* m = task.task.find_motion(name);
    if (!m) throw InputError(cli.task, "motions." + name, "no such motion (--motions)");
    if (m->terminate.any())
      throw InputError(cli.task, "motions." + name + ".terminate",
                       "sensing termination: the backprojection base counts stops by sticking only");
  }
  return chain;
}

bool has_kind(const LoadedTask& task, const std::vector<std::string>& chain, Motion::Kind kind) {
  return std::any_of(chain.begin(), chain.end(),
                     [&](const std::string& name) { return task.task.find_motion(name)->kind == kind; });
}
bool has_spring(const LoadedTask& task, const std::vector<std::string>& chain) {
  return has_kind(task, chain, Motion::Kind::kSpring);
}
bool has_damper(const LoadedTask& task, const std::vector<std::string>& chain) {
  return has_kind(task, chain, Motion::Kind::kDamper);
}

// One motion's backprojection of `target`, as the damper's fields (the spring's model in `model`).
struct StepBackprojection {
  ReachedSet base, weak, strong;
  bool fallback = false, free_rest = false;
  int steps = 0;
  std::string model;
};

StepBackprojection backproject_motion(const LoadedTask& task, const AtomCones& cones,
                                      const ReachedSet& target, const Motion& m, double kappa,
                                      double margin) {
  if (m.kind == Motion::Kind::kSpring) {
    SpringBackprojection b = backproject_spring(task, target, m.target, margin);
    return {std::move(b.base),
            std::move(b.weak),
            std::move(b.strong),
            b.fallback,
            b.free_rest,
            b.steps,
            spring_model_name(SpringModel::kViaPoint)};
  }
  DamperBackprojection b = backproject_damper(task, cones, target, m.target, kappa, margin);
  return {std::move(b.base), std::move(b.weak), std::move(b.strong), b.fallback, false, b.steps, "damper"};
}

// The chain's strong backprojections, the last motion first (Buckley Alg 5.2): per motion its JSON step and
// (with_layers) its layers for the 3-D page; `strong` is the first motion's, S_1.
struct ChainBackprojection {
  nlohmann::json steps;
  std::vector<BackprojectionLayers> layers;
  ReachedSet strong;
  bool fallback;
};

ChainBackprojection backproject_chain(const LoadedTask& task, const AtomCones& cones, ReachedSet target,
                                      const std::vector<std::string>& chain, double kappa, double margin,
                                      bool with_layers) {
  ChainBackprojection out{nlohmann::json::array(), {}, std::move(target), false};
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    const auto t0 = std::chrono::steady_clock::now();
    const StepBackprojection b =
        backproject_motion(task, cones, out.strong, *task.task.find_motion(*it), kappa, margin);
    out.fallback = out.fallback || b.fallback;
    out.steps.push_back(
        {{"motion", *it},
         {"model", b.model},
         {"free_rest", b.free_rest},
         {"base", pieces_json(task, b.base.pieces())},
         {"base_area", b.base.area()},
         {"weak_area", b.weak.area()},
         {"strong", pieces_json(task, b.strong.pieces())},
         {"strong_area", b.strong.area()},
         {"fallback", b.fallback},
         {"work_items", b.steps},
         {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()}});
    if (with_layers) out.layers.push_back({*it, b.base.pieces(), b.weak.pieces(), b.strong.pieces()});
    out.strong = b.strong;
  }
  return out;
}

// The outcome in words: per motion its areas, whether S lies inside S_1, the forward check and the rollouts.
void print_backproject_text(const nlohmann::json& out, const VerifyResult& forward) {
  for (const nlohmann::json& s : out["steps"])
    std::cout << s["motion"].get<std::string>() << ": may stop outside its target on "
              << s["base_area"].get<double>() << " area; weak backprojection " << s["weak_area"].get<double>()
              << "; strong backprojection " << s["strong_area"].get<double>() << "\n";
  std::cout << "start " << (out["start_inside"].get<bool>() ? "inside" : "not inside")
            << " the strong backprojection\n"
            << "forward verification from it under the rollouts' model: "
            << (forward.reliable ? "reliable" : "not reliable: " + forward.failure) << "\n";
  if (out.contains("check"))
    std::cout << "check: " << out["check"]["successes"] << " of " << out["check"]["rollouts"]
              << " rollouts from " << out["check"]["points"].size() << " points reach the goal ("
              << out["check"]["unstable"] << " unstable, " << out["check"]["outside"] << " ends outside the "
              << "prediction)\n";
}

void run_backproject(const BackprojectCli& cli, CommandState& state) {
  const auto start_time = std::chrono::steady_clock::now();
  const std::string text = read_task_text(cli.task);
  const auto task = load_task_from_string(text, cli.task);
  const std::vector<std::string> chain = chain_of(*task, cli);
  if (cli.check > 0 && has_spring(*task, chain) && has_damper(*task, chain))
    throw InputError(cli.task, "--check",
                     "a chain of dampers and springs: the check runs a spring's chain in the position form, "
                     "which has no damper");
  const AtomCones cones(task->cspace);
  const double kappa = kStopRelativeSpeed;
  // S keeps the rollouts' contact resolution from W: their contact lets the robot sink and rise by about the
  // contact lift, so a start closer to W than that may behave as one in it.
  const double margin = rollout_contact_lift(*task);
  // With model error the goal is its part on the surface (loaded_task.h).
  const ReachedSet goal = ReachedSet::from_regions(*task, task->task.goal, !task->task.model_error.empty());
  const ChainBackprojection backprojection =
      backproject_chain(*task, cones, goal, chain, kappa, margin, !cli.view.empty());
  const ReachedSet& target = backprojection.strong;  // S_1
  const ReachedSet start = ReachedSet::from_region(*task, task->task.start);
  const std::vector<ReachedPiece> outside = start.pieces_outside(target, task->surface_tolerance());
  nlohmann::json out = {{"task", task->task.name},
                        {"motions", chain},
                        {"stop_relative_speed", kappa},
                        {"margin", margin},
                        {"steps", backprojection.steps},
                        {"start_inside", outside.empty()},
                        {"start_outside", pieces_json(*task, outside)},
                        {"fallback", backprojection.fallback}};
  // The forward verifier under the rollouts' model (contact lift, servo coast, slow stops) from S_1: the
  // backprojection is first-order, so this is what certifies S_1 for the rollouts. A spring's backprojection
  // is the via-point model's, the position form's: the forward check and the rollouts use that form.
  const bool spring = has_spring(*task, chain);
  VerifyOptions forward_options = rollout_verify_options(*task);
  if (spring) forward_options.spring_model = SpringModel::kViaPoint;
  const VerifyResult forward =
      verify_strategy_from(*task, Strategy::sequence("", chain), target, forward_options);
  out["forward"] = {{"reliable", forward.reliable},
                    {"failure", forward.failure},
                    {"outside_goal", pieces_json(*task, forward.outside_goal)}};
  bool check_ok = true;
  if (cli.check > 0) {
    BackprojectionCheckOptions o;
    o.points = cli.points;
    o.n = cli.check;
    o.seed = cli.seed;
    o.threads = cli.threads;
    o.mode = cli.check_mode == "uniform" ? SampleMode::kUniform : SampleMode::kExtreme;
    if (spring) o.form = ControllerForm::kPosition;
    o.dir = cli.check_dir.empty() ? std::filesystem::temp_directory_path() / "cmt-backproject"
                                  : std::filesystem::path(cli.check_dir);
    const BackprojectionCheck check = check_backprojection(text, *task, chain, target, o);
    check_ok = check.failures == 0 && check.outside == 0;
    out["check"] = backprojection_check_json(check, task->task.dimension);
  }
  if (!cli.view.empty()) {
    const std::filesystem::path page = std::filesystem::path(cli.view) / "index.html";
    report::write_view_assets(cli.view);
    report::write_view_page(
        backprojection_view_data(*task, backprojection.layers, task->task.name + " / backprojections"), page,
        ".");
    out["view"] = page.string();
  }
  out["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  if (state.json)
    print_json(out);
  else
    print_backproject_text(out, forward);
  state.exit_status = outside.empty() && check_ok ? kExitSuccess : 1;
}

}  // namespace

void add_backproject_command(CLI::App& app, CommandState& state) {
  auto cli = std::make_shared<BackprojectCli>();
  auto* cmd = app.add_subcommand(
      "backproject",
      "strong backprojections of a chain of damper and spring motions from the goal (Buckley Sec 5.4)");
  cmd->add_option("TASK", cli->task, "task YAML file")->required();
  cmd->add_option("--motions", cli->motions, "the chain's motions, first first (comma separated)")
      ->required();
  cmd->add_option("--check", cli->check, "run this many rollouts from each of --points points of S (0: none)")
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--points", cli->points, "start points of the check (default 20)")
      ->check(CLI::Range(1, 10000));
  cmd->add_option("--seed", cli->seed, "seed of the check's points and rollouts (default 1)");
  cmd->add_option("--threads", cli->threads, "rollout threads (default 1)")->check(CLI::Range(1, 256));
  cmd->add_option("--check-mode", cli->check_mode,
                  "error sampling of the check: extreme (default) or uniform")
      ->check(CLI::IsMember({"uniform", "extreme"}));
  cmd->add_option("--check-dir", cli->check_dir, "where the check's point task files go");
  cmd->add_option("--view", cli->view,
                  "write a 3-D page to this directory: per motion B, W(B) and S (Buckley Figs 5.5, 5.8)");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([cli, &state] { run_backproject(*cli, state); });
}

}  // namespace cmt

// `cmt teach TASK --session FILE [--json] [-o OUT.yaml]`, and interactive on stdin without --session
// (docs/teaching.md): Buckley's teaching loop (§5.1) over verifier/teaching.
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "controllers/termination.h"
#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/cli/sticking_command.h"
#include "experiments/cli/teach_view.h"
#include "experiments/report/view_page.h"
#include "experiments/teach/preimage_check.h"
#include "experiments/teach/session_file.h"
#include "experiments/teach/teach_json.h"
#include "experiments/validation/verifier_model.h"
#include "models/input_error.h"

namespace cmt {
namespace {

using teaching::TeachOptions;

std::string interval(double lo, double hi) {
  std::ostringstream out;
  out.precision(4);
  if (hi - lo < 1e-9) {
    out << "= " << lo + 0.0;  // + 0.0: no "-0"
  } else {
    out << "in [" << lo + 0.0 << ", " << hi + 0.0 << "]";
  }
  return out.str();
}

// "f4 (may stick; x in [-6, -1], y in [-6, 6], z = 0)": the atom, the motion's stick class there (`cmt
// sticking`: must, may, or never when only a slow-slide stop or the contact lift ends the motion there) and
// the bounding box of its pieces.
std::string pieces_text(const LoadedTask& task, const std::string& motion,
                        const std::vector<ReachedPiece>& pieces) {
  static const report::StickClassOf stick_class = verifier_stick_classes();
  std::map<int, std::pair<Vec3, Vec3>> boxes;
  for (const ReachedPiece& p : pieces)
    for (const Vec3& q : p.polygon) {
      auto [it, fresh] = boxes.try_emplace(p.atom, q, q);
      it->second.first = it->second.first.cwiseMin(q);
      it->second.second = it->second.second.cwiseMax(q);
    }
  std::string out;
  for (const auto& [atom, box] : boxes) {
    out += (out.empty() ? "" : ", ") + task.cspace.atom_name(atom) + " (" + stick_class(task, motion, atom) +
           " stick; x " + interval(box.first.x(), box.second.x()) + ", y " +
           interval(box.first.y(), box.second.y()) + ", z " + interval(box.first.z(), box.second.z()) + ")";
  }
  return out;
}

void print_step(std::ostream& os, const teaching::Session& session, const teaching::TeachStep& step,
                std::size_t index) {
  os << "step " << index + 1 << ": " << step.motion << ", chain [" << teaching::strategy_text(step.chain)
     << "]\n";
  if (step.solved.empty())
    os << "  solved nothing of the start\n";
  else
    os << "  solved " << step.solved.size() << " start cell(s), measure " << step.solved_measure << "\n";
  if (step.remaining.empty()) {
    os << "  the start is solved\n";
  } else {
    os << "  remaining: " << step.remaining.size() << " cell(s), measure " << step.remaining_measure
       << "\n  why: " << step.failure << "\n";
    if (!step.blocking.empty())
      os << "  " << step.motion
         << (step.chain.nodes.size() == 1
                 ? " may stop outside the goal at: "
                 : " may stop where the motions taught before do not reach the goal: ")
         << pieces_text(session.task(), step.motion, step.blocking) << "\n";
    if (step.unchecked_reason_atoms > 0)
      os << "  (" << step.unchecked_reason_atoms << " more termination atoms not checked)\n";
  }
  os << "  " << step.verifications << " verifications"
     << (step.dispatches ? ", " + std::to_string(step.dispatches) + " sensed dispatches tried" : "") << ", "
     << step.seconds << " s\n";
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

struct TeachCli {
  std::string task, session, out, name = "taught";
  int depth = 2;
  SpringModel spring_model = SpringModel::kVelocity;
  int check = 0;  // rollouts per solved cell, 0 = no pre-image check
  std::uint64_t seed = 1;
  int threads = 1;
  std::string check_mode = "extreme", check_dir;
  std::string view;  // directory of the 3-D page, "" = none
};

const teaching::TeachStep& propose(teaching::Session& session, const SessionStep& step) {
  return step.inline_motion ? session.propose(*step.inline_motion) : session.propose(step.motion);
}

// One line of the interactive mode as a teaching step; throws InputError on a bad line.
SessionStep parse_line(const std::string& line, const Task& task) {
  std::istringstream in(line);
  std::string word;
  in >> word;
  if (word == "spring" || word == "damper") {
    std::vector<std::string> numbers;
    for (std::string x; in >> x;) numbers.push_back(x);
    std::string yaml = "steps: [{" + word + ": [";
    for (std::size_t i = 0; i < numbers.size(); ++i) yaml += (i ? ", " : "") + numbers[i];
    return parse_session(yaml + "]}]", "(input)", task).front();
  }
  return parse_session("steps: [" + word + "]", "(input)", task).front();
}

// Reads motions from stdin: a motion name, `spring x y z`, `damper x y z`, `undo`, `save FILE`, `quit`.
// Talks on `os` (stderr with --json, so that stdout holds the one JSON object).
void interactive(teaching::Session& session, std::vector<SessionStep>& transcript, std::ostream& os) {
  const bool terminal = isatty(STDIN_FILENO);
  const Task& task = session.task().task;
  if (terminal)
    os << "Propose motions, the strategy's last motion first: a motion name, spring x y z, damper x y z;\n"
          "undo, save FILE (the teaching session so far), quit.\n";
  std::string line;
  while (!session.solved()) {
    if (terminal) os << "teach> " << std::flush;
    if (!std::getline(std::cin, line)) break;
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    if (word == "quit") break;
    if (word == "undo") {
      const bool undone = session.undo();
      if (undone) transcript.pop_back();
      os << (undone ? "undone; " + std::to_string(transcript.size()) + " step(s) left\n"
                    : "no step to undo\n");
      continue;
    }
    if (word == "save") {
      std::string file;
      words >> file;
      std::ofstream out(file);
      out << "steps:\n";
      for (const SessionStep& s : transcript) out << "  - " << session_step_yaml(s, task.dimension) << "\n";
      os << (out ? "saved " + file : "cannot write " + file) << "\n";
      continue;
    }
    try {
      const SessionStep step = parse_line(line, session.task().task);
      const teaching::TeachStep& taught = propose(session, step);  // the step exists before it is numbered
      transcript.push_back(step);
      print_step(os, session, taught, session.steps().size() - 1);
    } catch (const InputError& e) {
      os << e.reason() << " (" << e.key() << ")\n";
    }
  }
}

// Proposes the teaching session file's steps (until the start is solved), or reads them from stdin. Returns
// how many of the file's steps were not run.
std::size_t run_session(const TeachCli& cli, const Task& task, teaching::Session& session, bool json) {
  if (cli.session.empty()) {
    std::vector<SessionStep> transcript;
    interactive(session, transcript, json ? std::cerr : std::cout);
    return 0;
  }
  const std::vector<SessionStep> steps = load_session(cli.session, task);
  for (const SessionStep& s : steps) {
    if (session.solved()) break;
    const teaching::TeachStep& step = propose(session, s);
    if (!json) print_step(std::cout, session, step, session.steps().size() - 1);
  }
  const std::size_t not_run = steps.size() - session.steps().size();
  if (!json && not_run > 0)
    std::cout << "the start was solved after step " << session.steps().size()
              << "; the teaching session's last " << not_run << " step(s) were not run\n";
  return not_run;
}

std::optional<PreimageCheck> run_check(const TeachCli& cli, const Task& task,
                                       const teaching::Session& session) {
  if (cli.check == 0) return std::nullopt;
  PreimageCheckOptions o;
  o.n = cli.check;
  o.seed = cli.seed;
  o.threads = cli.threads;
  o.mode = *parse_sample_mode(cli.check_mode);
  o.dir = cli.check_dir.empty() ? std::filesystem::temp_directory_path() /
                                      ("cmt-teach-" + task.name + "-" + std::to_string(cli.seed))
                                : std::filesystem::path(cli.check_dir);
  return check_preimages(read_text(cli.task), session, o);
}

// What `cmt teach` did, for its output.
struct TeachOutcome {
  std::optional<Strategy> strategy;
  bool solved = false;
  std::string written_name;  // the taught strategy's name in the -o file, "" when none was written
  std::size_t steps_not_run = 0;
  std::optional<PreimageCheck> check;
  std::filesystem::path page;  // the 3-D page, empty without --view
};

nlohmann::json outcome_json(const TeachCli& cli, const teaching::Session& session,
                            const TeachOptions& options, const TeachOutcome& o, double seconds) {
  nlohmann::json j = teach_json(session, seconds);
  if (!o.written_name.empty()) j["written"] = {{"file", cli.out}, {"strategy", o.written_name}};
  j["session"] = cli.session.empty() ? nlohmann::json(nullptr) : nlohmann::json(cli.session);
  j["steps_not_run"] = o.steps_not_run;
  j["options"] = {{"depth", options.refine_depth},
                  {"spring_model", spring_model_name(options.verify.spring_model)},
                  {"stop_relative_speed", options.verify.stop_relative_speed},
                  {"contact_lift", options.verify.contact_lift},
                  {"servo_coast", options.verify.servo_coast}};
  if (o.check) j["check"] = preimage_check_json(*o.check);
  if (!o.page.empty()) j["view"] = o.page.string();
  return j;
}

void print_outcome(const TeachCli& cli, const teaching::Session& session, const TeachOutcome& o) {
  const std::string& name = session.task().task.name;
  if (o.solved) {
    std::cout << name << ": solved; taught strategy [" << teaching::strategy_text(*o.strategy) << "]"
              << (o.written_name.empty() ? "" : ", written to " + cli.out + " as '" + o.written_name + "'")
              << "\n";
  } else {
    std::cout << name << ": NOT solved"
              << (session.solved() ? " (the start is covered by different chains that no one strategy runs)"
                                   : "")
              << "\n";
  }
  if (!o.check) return;
  const PreimageCheck& c = *o.check;
  std::cout << "pre-image check: " << c.successes << " of " << c.rollouts << " rollouts reached the goal ("
            << c.unstable << " unstable, " << c.failures << " failed, " << c.outside
            << " motion ends outside the prediction) from " << c.cells.size() << " solved cell(s)\n";
  for (const CellCheck& cell : c.cells)
    if (!cell.replay.empty()) std::cout << "  failure in " << cell.task_file << ": " << cell.replay << "\n";
}

void run_teach(const TeachCli& cli, CommandState& state) {
  const auto start = std::chrono::steady_clock::now();
  const auto task = load_task(cli.task);
  TeachOptions options;
  options.refine_depth = cli.depth;
  options.verify = {cli.spring_model, kStopRelativeSpeed, rollout_contact_lift(*task),
                    rollout_servo_coast(*task), rollout_spring_lag()};
  teaching::Session session(task, options);
  TeachOutcome o;
  o.steps_not_run = run_session(cli, task->task, session, state.json);
  o.strategy = session.strategy();
  o.solved = session.solved() && o.strategy.has_value();
  if (o.solved && !cli.out.empty()) {
    o.written_name = free_strategy_name(task->task, cli.name);
    std::ofstream out(cli.out);
    out << taught_task_yaml(read_text(cli.task), session, *o.strategy, o.written_name);
    if (!out) throw std::runtime_error("cannot write " + cli.out);
  }
  o.check = run_check(cli, task->task, session);
  if (!cli.view.empty()) {
    o.page = std::filesystem::path(cli.view) / "index.html";
    report::write_view_assets(cli.view);
    report::write_view_page(teach_view_data(session, task->task.name + " / teaching session"), o.page, ".");
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (state.json)
    print_json(outcome_json(cli, session, options, o, seconds));
  else
    print_outcome(cli, session, o);
  const bool check_failed = o.check && (o.check->failures > 0 || o.check->outside > 0);
  state.exit_status = o.solved && !check_failed ? kExitSuccess : kExitFailureFound;
}

}  // namespace

void add_teach_command(CLI::App& app, CommandState& state) {
  auto cli = std::make_shared<TeachCli>();
  auto* cmd =
      app.add_subcommand("teach", "Teach a strategy by proposing motions, the last first (Buckley ch. 5)");
  cmd->add_option("TASK", cli->task, "task YAML file")->required();
  cmd->add_option(
      "--session", cli->session,
      "teaching session YAML file (steps: motion names or {spring: [x, y, z]} / {damper: [x, y, z]}); "
      "without it, motions are read from stdin");
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->add_option("-o,--output", cli->out, "write the task with the taught strategy added");
  cmd->add_option("--name", cli->name, "name of the taught strategy in the written task (default taught)")
      ->check([](const std::string& name) {
        return !name.empty() &&
                       name.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_-") == std::string::npos
                   ? std::string()
                   : "a strategy name matches [a-z0-9_-]+";
      });
  cmd->add_option("--depth", cli->depth, "how often a start cell may be halved (default 2)")
      ->check(CLI::Range(0, 8));
  cmd->add_option("--spring-model", cli->spring_model,
                  "spring trajectory model: velocity (default) or via-point")
      ->transform(
          CLI::CheckedTransformer(std::map<std::string, SpringModel>{{"velocity", SpringModel::kVelocity},
                                                                     {"via-point", SpringModel::kViaPoint}},
                                  CLI::ignore_case));
  cmd->add_option(
         "--check", cli->check,
         "pre-image check: this many MuJoCo rollouts from each solved cell (its chain as the strategy, "
         "the cell as the start); every one must reach the goal")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--seed", cli->seed, "master seed of the check's rollouts (default 1)");
  cmd->add_option("--threads", cli->threads, "threads for the check's rollouts (results do not depend on it)")
      ->check(CLI::Range(1, 256));
  cmd->add_option("--check-mode", cli->check_mode,
                  "error sampling of the check: extreme (default: starts mostly at the cell's vertices and "
                  "edges, errors at their bounds) or uniform")
      ->check(CLI::IsMember({"uniform", "extreme"}));
  cmd->add_option("--check-dir", cli->check_dir,
                  "where the check writes one task file per solved cell (for replays; default: a directory "
                  "under the system's temporary directory)");
  cmd->add_option(
      "--view", cli->view,
      "write a 3-D page of the teaching session to DIR/index.html: per step the solved and remaining start "
      "cells, where the motion may stop, and the stops to avoid (docs/teaching.md)");
  cmd->callback([cli, &state] { run_teach(*cli, state); });
}

}  // namespace cmt

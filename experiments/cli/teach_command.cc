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
#include "models/task_error.h"

namespace cmt {
namespace {

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
  const double total = step.solved_measure + step.remaining_measure;
  os << "step " << index + 1 << ": " << step.motion << ", chain [";
  for (std::size_t i = 0; i < step.chain.size(); ++i) os << (i ? ", " : "") << step.chain[i];
  os << "]\n";
  if (step.solved.empty())
    os << "  solved nothing of the start\n";
  else
    os << "  solved " << step.solved.size() << " start cell(s), measure " << step.solved_measure << "\n";
  if (step.remaining.empty()) {
    os << "  the start is solved\n";
  } else {
    os << "  remaining: " << step.remaining.size() << " cell(s), measure " << step.remaining_measure
       << (total > 0 ? "" : "") << "\n  why: " << step.failure << "\n";
    if (!step.blocking.empty())
      os << "  " << step.motion
         << (step.chain.size() == 1 ? " may stop outside the goal at: "
                                    : " may stop where the motions taught before do not reach the goal: ")
         << pieces_text(session.task(), step.motion, step.blocking) << "\n";
    if (step.unchecked_reason_atoms > 0)
      os << "  (" << step.unchecked_reason_atoms << " more termination atoms not checked)\n";
  }
  os << "  " << step.verifications << " verifications, " << step.seconds << " s\n";
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

// One line of the interactive mode as a session step; throws TaskError on a bad line.
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
          "undo, save FILE (the session so far), quit.\n";
  std::string line;
  while (!session.solved()) {
    if (terminal) os << "teach> " << std::flush;
    if (!std::getline(std::cin, line)) break;
    std::istringstream words(line);
    std::string word;
    if (!(words >> word)) continue;
    if (word == "quit") break;
    if (word == "undo") {
      if (session.undo()) transcript.pop_back();
      os << (transcript.empty() ? "no steps\n"
                                : "undone; " + std::to_string(transcript.size()) + " step(s)\n");
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
      SessionStep step = parse_line(line, session.task().task);
      transcript.push_back(step);
      const teaching::TeachStep& taught = propose(session, step);  // before steps().size() is read
      print_step(os, session, taught, session.steps().size() - 1);
    } catch (const TaskError& e) {
      os << e.reason() << " (" << e.key() << ")\n";
    }
  }
}

void run_teach(const TeachCli& cli, CommandState& state) {
  const auto start = std::chrono::steady_clock::now();
  const auto task = load_task(cli.task);
  const std::vector<SessionStep> steps =
      cli.session.empty() ? std::vector<SessionStep>{} : load_session(cli.session, task->task);
  teaching::TeachOptions options;
  options.refine_depth = cli.depth;
  options.verify = {cli.spring_model, kStopRelativeSpeed, rollout_contact_lift(*task),
                    rollout_servo_coast(*task)};
  teaching::Session session(task, options);
  std::vector<SessionStep> transcript;
  std::size_t skipped_steps = 0;
  if (cli.session.empty()) {
    interactive(session, transcript, state.json ? std::cerr : std::cout);
  } else {
    for (const SessionStep& s : steps) {
      if (session.solved()) break;
      const teaching::TeachStep& step = propose(session, s);
      if (!state.json) print_step(std::cout, session, step, session.steps().size() - 1);
    }
    if (!state.json && session.steps().size() < steps.size())
      std::cout << "the start was solved after step " << session.steps().size() << "; the session's last "
                << steps.size() - session.steps().size() << " step(s) were not run\n";
  }
  skipped_steps = steps.size() - std::min(steps.size(), session.steps().size());
  const auto strategy = session.strategy();
  const bool solved = session.solved() && strategy.has_value();
  std::string name;
  if (solved && !cli.out.empty()) {
    name = free_strategy_name(task->task, cli.name);
    std::ofstream out(cli.out);
    out << taught_task_yaml(read_text(cli.task), session, *strategy, name);
    if (!out) throw std::runtime_error("cannot write " + cli.out);
  }
  std::optional<PreimageCheck> check;
  if (cli.check > 0) {
    PreimageCheckOptions o;
    o.n = cli.check;
    o.seed = cli.seed;
    o.threads = cli.threads;
    o.mode = *parse_sample_mode(cli.check_mode);
    o.dir = cli.check_dir.empty() ? std::filesystem::temp_directory_path() /
                                        ("cmt-teach-" + task->task.name + "-" + std::to_string(cli.seed))
                                  : std::filesystem::path(cli.check_dir);
    check = check_preimages(read_text(cli.task), session, o);
  }
  const bool check_failed = check && (check->failures > 0 || check->outside > 0);
  const std::filesystem::path page = std::filesystem::path(cli.view) / "index.html";
  if (!cli.view.empty()) {
    report::write_view_assets(cli.view);
    report::write_view_page(teach_view_data(session, task->task.name + " / teaching session"), page, ".");
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (state.json) {
    nlohmann::json j = teach_json(session, seconds);
    if (!name.empty()) j["written"] = {{"file", cli.out}, {"strategy", name}};
    j["session"] = cli.session.empty() ? nlohmann::json(nullptr) : nlohmann::json(cli.session);
    j["steps_not_run"] = skipped_steps;
    j["options"] = {{"depth", cli.depth},
                    {"spring_model", spring_model_name(options.verify.spring_model)},
                    {"stop_relative_speed", options.verify.stop_relative_speed},
                    {"contact_lift", options.verify.contact_lift},
                    {"servo_coast", options.verify.servo_coast}};
    if (check) j["check"] = preimage_check_json(*check);
    if (!cli.view.empty()) j["view"] = page.string();
    print_json(j);
  } else if (solved) {
    std::cout << task->task.name << ": solved; taught strategy [";
    for (std::size_t i = 0; i < strategy->size(); ++i) std::cout << (i ? ", " : "") << (*strategy)[i];
    std::cout << "]" << (name.empty() ? "" : ", written to " + cli.out + " as '" + name + "'") << "\n";
  } else {
    std::cout << task->task.name << ": NOT solved"
              << (session.solved() ? " (the start is covered by different chains that no one strategy runs)"
                                   : "")
              << "\n";
  }
  if (check && !state.json) {
    std::cout << "pre-image check: " << check->successes << " of " << check->rollouts
              << " rollouts reached the goal (" << check->unstable << " unstable, " << check->failures
              << " failed, " << check->outside << " motion ends outside the prediction) from "
              << check->cells.size() << " solved cell(s)\n";
    for (const CellCheck& c : check->cells)
      if (!c.replay.empty()) std::cout << "  failure in " << c.task_file << ": " << c.replay << "\n";
  }
  state.exit_status = solved && !check_failed ? kExitSuccess : kExitFailureFound;
}

}  // namespace

void add_teach_command(CLI::App& app, CommandState& state) {
  auto cli = std::make_shared<TeachCli>();
  auto* cmd =
      app.add_subcommand("teach", "Teach a strategy by proposing motions, the last first (Buckley ch. 5)");
  cmd->add_option("TASK", cli->task, "task YAML file")->required();
  cmd->add_option("--session", cli->session,
                  "session YAML file (steps: motion names or {spring: [x, y, z]} / {damper: [x, y, z]}); "
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
      "write a 3-D page of the session to DIR/index.html: per step the solved and remaining start "
      "cells, where the motion may stop, and the stops to avoid (docs/teaching.md)");
  cmd->callback([cli, &state] { run_teach(*cli, state); });
}

}  // namespace cmt

// cmt-fuzz: feeds hostile and extreme task files to `cmt info` / `cmt verify` and reports every crash, hang,
// unexpected exit status or malformed JSON answer (docs/fuzzing.md).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <thread>

#include "experiments/fuzz/fuzz_run.h"
#include "experiments/fuzz/mutator.h"

namespace fs = std::filesystem;
using namespace cmt::fuzz;

namespace {

constexpr int kExitUsage = 2;

struct Options {
  std::string cmt;
  std::vector<std::string> seeds;
  size_t inputs = 1000;
  uint64_t seed = 1;
  std::string command = "info";
  int jobs = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  double time_limit = 20;
  double hard_limit = 0;
  std::string out = "fuzz-out";
  bool json = false;
  std::string replay;
  size_t minimize = 20;
  size_t minimize_tries = 300;
  double minimize_seconds = 300;
  long memory_mb = 4096;
  std::vector<std::string> mutations;  // empty: all
  size_t max_mutations = 4;
};

int usage_error(const std::string& message, bool json) {
  std::cerr << "cmt-fuzz: " << message << "\n";
  if (json) std::cout << nlohmann::json{{"error", {{"message", message}}}}.dump(2) << "\n";
  return kExitUsage;
}

// The cmt program next to this one (both are built into build/bin).
std::string default_cmt() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "cmt" : (self.parent_path() / "cmt").string();
}

// *.yaml files of a directory, sorted by name.
std::vector<std::string> yaml_files(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.is_regular_file() && entry.path().extension() == ".yaml")
      files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> seed_files(const std::vector<std::string>& args) {
  std::vector<std::string> files;
  for (const auto& arg : args) {
    if (fs::is_directory(arg)) {
      const auto found = yaml_files(arg);
      files.insert(files.end(), found.begin(), found.end());
    } else {
      files.push_back(arg);
    }
  }
  return files;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void add_options(CLI::App& app, Options& o) {
  app.add_option("--cmt", o.cmt, "the cmt program (default: cmt next to cmt-fuzz)");
  app.add_option("--seeds", o.seeds,
                 "seed task files or directories of *.yaml (default: models/tasks/ and "
                 "models/tasks/soundness/)");
  app.add_option("--inputs", o.inputs, "number of mutated inputs")->check(CLI::PositiveNumber);
  app.add_option("--seed", o.seed, "random seed; input i depends only on (seed, i)");
  app.add_option("--command", o.command, "the cmt command to run")->check(CLI::IsMember({"info", "verify"}));
  app.add_option("--jobs,-j", o.jobs, "parallel cmt processes")->check(CLI::Range(1, 256));
  app.add_option("--time-limit", o.time_limit, "verify: the verifier's --time-limit in seconds")
      ->check(CLI::PositiveNumber);
  app.add_option("--hard-limit", o.hard_limit,
                 "seconds before a run is killed and counted as a hang (default: time limit + 15 for verify, "
                 "10 for info)");
  app.add_option("--out", o.out, "output directory: work/ and failures/");
  app.add_flag("--json", o.json, "print the summary as one JSON object");
  app.add_option("--replay", o.replay, "run every *.yaml of this corpus directory as is (no mutation)")
      ->check(CLI::ExistingDirectory);
  app.add_option("--minimize", o.minimize, "minimize the first input of at most this many failure classes");
  app.add_option("--minimize-tries", o.minimize_tries, "cmt runs per minimization, at most");
  app.add_option("--minimize-seconds", o.minimize_seconds, "seconds per minimization, at most");
  app.add_option("--mutations", o.mutations,
                 "only these mutations (names as in docs/fuzzing.md), e.g. the numeric ones for verify runs")
      ->delimiter(',');
  app.add_option("--max-mutations", o.max_mutations, "mutations per input: 1 to this many")
      ->check(CLI::Range(1, 16));
  app.add_option("--memory-limit", o.memory_mb, "address-space limit of each cmt run in MB (0: none)");
}

RunConfig run_config(const Options& o) {
  RunConfig config;
  config.cmt = o.cmt;
  config.command = o.command;
  config.out_dir = o.out;
  config.time_limit = o.time_limit;
  config.hard_limit = o.hard_limit;
  config.memory_mb = o.memory_mb;
  config.jobs = o.jobs;
  config.minimize_classes = o.minimize;
  config.minimize_tries = o.minimize_tries;
  config.minimize_seconds = o.minimize_seconds;
  return config;
}

int report(const Summary& summary, bool json) {
  if (json)
    std::cout << summary_json(summary).dump(2) << "\n";
  else
    std::cout << summary_text(summary);
  return summary.failures.empty() ? 0 : 1;
}

int replay(const Options& o, RunConfig& config) {
  const auto files = yaml_files(o.replay);
  if (files.empty()) return usage_error("no *.yaml files in " + o.replay, o.json);
  return report(run_inputs(config, files.size(),
                           [&](size_t i) {
                             const std::string text = read_text(files[i]);
                             const std::string strategy = strategy_in_text(text);
                             return InputCase{o.command + "-" + fs::path(files[i]).stem().string(), text,
                                              strategy.empty() ? "s" : strategy, files[i]};
                           }),
                o.json);
}

int fuzz(const Options& o, RunConfig& config) {
  std::vector<std::string> seed_args = o.seeds;
  if (seed_args.empty()) {
    seed_args = {std::string(CMT_SOURCE_DIR) + "/models/tasks",
                 std::string(CMT_SOURCE_DIR) + "/models/tasks/soundness"};
  }
  std::vector<SeedTask> seeds;
  try {
    for (const auto& file : seed_files(seed_args)) seeds.push_back(load_seed(file));
  } catch (const std::exception& e) {
    return usage_error(e.what(), o.json);
  }
  if (seeds.empty()) return usage_error("no seed task files", o.json);
  try {
    make_mutant(seeds, o.seed, 0, o.mutations,
                o.max_mutations);  // checks the --mutations names before any run
  } catch (const std::invalid_argument& e) {
    return usage_error(std::string("--mutations: ") + e.what(), o.json);
  }
  return report(
      run_inputs(config, o.inputs,
                 [&](size_t i) {
                   const Mutant m = make_mutant(seeds, o.seed, i, o.mutations, o.max_mutations);
                   std::string origin = seeds[m.seed_index].path + " +";
                   for (const auto& name : m.mutations) origin += " " + name;
                   return InputCase{o.command + "-" + std::to_string(i), m.text, m.strategy, origin};
                 }),
      o.json);
}

}  // namespace

int main(int argc, char** argv) {
  // Under a sanitizer build (-DCMT_SANITIZE=ON) a report must end the run with a signal, which counts as a
  // failure: ASan's default exit status 1 and UBSan's print-and-continue would pass the checks. Leak reports
  // are left out (CGAL's and MuJoCo's process-lifetime statics). The user's own settings win.
  setenv("ASAN_OPTIONS", "abort_on_error=1:detect_leaks=0", /*overwrite=*/0);
  setenv("UBSAN_OPTIONS", "halt_on_error=1:abort_on_error=1:print_stacktrace=1", /*overwrite=*/0);
  CLI::App app{"cmt-fuzz: hostile and extreme task files for cmt info / cmt verify (docs/fuzzing.md)"};
  Options o;
  add_options(app, o);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const bool json = std::find(argv, argv + argc, std::string("--json")) != argv + argc;
    return usage_error(e.what(), json);
  }
  if (o.cmt.empty()) o.cmt = default_cmt();
  if (access(o.cmt.c_str(), X_OK) != 0) return usage_error("cannot execute cmt at " + o.cmt, o.json);
  RunConfig config = run_config(o);
  if (o.command == "verify" && !cmt_supports_time_limit(o.cmt)) {
    std::cerr << "cmt-fuzz: `" << o.cmt
              << " verify` has no --time-limit option; relying on the hard limit only\n";
    config.pass_time_limit = false;
  }
  try {
    fs::create_directories(o.out);
    return o.replay.empty() ? fuzz(o, config) : replay(o, config);
  } catch (const std::exception& e) {
    std::cerr << "cmt-fuzz: " << e.what() << "\n";
    return kExitUsage;
  }
}

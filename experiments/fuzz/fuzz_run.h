// Runs many task files through `cmt info` or `cmt verify` in parallel, checks every answer (outcome.h), saves
// the failing inputs with their details, minimizes one input per failure class and summarizes the run.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace cmt::fuzz {

struct RunConfig {
  std::string cmt;               // path of the cmt program
  std::string command = "info";  // info | verify
  std::string out_dir;
  double time_limit = 20;  // verify: passed as --time-limit when cmt supports it
  bool pass_time_limit = true;
  double hard_limit = 0;  // seconds before SIGKILL; 0: time_limit + 15 (verify) or 10 (info)
  long memory_mb = 4096;
  int jobs = 2;
  size_t minimize_classes = 20;  // minimize the first input of at most this many failure classes
  size_t minimize_tries = 300;
  double minimize_seconds = 300;
  bool quiet = false;  // no progress lines on stderr
};

// One input: the task text, a strategy name for verify, and where it came from (for the failure report).
struct InputCase {
  std::string name;  // file stem: <command>-<index> or <command>-<corpus stem>
  std::string text;
  std::string strategy;
  std::string origin;
};

struct Failure {
  std::string name;
  std::string path;      // the failing input, under out_dir/failures/
  std::string min_path;  // its minimized form, or "" when it was not minimized
  std::string status;
  std::string kind;
  std::string detail;
  std::string failure_class;
  std::string origin;
};

struct Summary {
  std::string command;
  size_t inputs = 0;
  std::map<std::string, size_t> by_status;  // "0", "1", "2", "signal 11", "hard time-out", ...
  size_t timed_out = 0;                     // clean timed_out: true answers
  std::vector<Failure> failures;
  std::map<std::string, size_t> classes;  // failure class -> count
  bool time_limit_passed = false;
  double seconds = 0;
};

// Runs inputs 0..count-1, made on demand by make_input (called from worker threads).
Summary run_inputs(const RunConfig& config, size_t count, const std::function<InputCase(size_t)>& make_input);

// Whether `cmt verify` accepts --time-limit (its --help names the option).
bool cmt_supports_time_limit(const std::string& cmt);

nlohmann::json summary_json(const Summary& summary);
std::string summary_text(const Summary& summary);

}  // namespace cmt::fuzz

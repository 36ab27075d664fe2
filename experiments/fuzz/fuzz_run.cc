#include "experiments/fuzz/fuzz_run.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>

#include "experiments/fuzz/child_process.h"
#include "experiments/fuzz/minimizer.h"
#include "experiments/fuzz/outcome.h"

namespace cmt::fuzz {

namespace {

namespace fs = std::filesystem;

double hard_limit_of(const RunConfig& config) {
  if (config.hard_limit > 0) return config.hard_limit;
  return config.command == "verify" ? config.time_limit + 15 : 10;
}

std::string format_seconds(double s) {
  std::ostringstream out;
  out.precision(3);
  out << s;
  return out.str();
}

std::vector<std::string> command_line(const RunConfig& config, const std::string& file,
                                      const std::string& strategy) {
  if (config.command == "info") return {config.cmt, "info", file, "--json"};
  std::vector<std::string> argv = {config.cmt, "verify", file, "--strategy", strategy, "--json"};
  if (config.pass_time_limit) {
    argv.push_back("--time-limit");
    argv.push_back(format_seconds(config.time_limit));
  }
  return argv;
}

std::string shell_quote(const std::string& word) {
  if (!word.empty() &&
      word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:") ==
          std::string::npos) {
    return word;
  }
  std::string out = "'";
  for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string joined_command(const std::vector<std::string>& argv) {
  std::string out;
  for (const auto& word : argv) {
    if (!out.empty()) out += ' ';
    out += shell_quote(word);
  }
  return out;
}

void write_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

void append_file(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::app);
  out << text;
}

struct Execution {
  std::vector<std::string> argv;
  ChildResult child;
  Outcome outcome;
};

// Runs cmt on the task file; its captured output files are removed again.
Execution execute(const RunConfig& config, const std::string& file, const std::string& strategy) {
  Execution e;
  e.argv = command_line(config, file, strategy);
  const ChildLimits limits{hard_limit_of(config), config.memory_mb};
  e.child = run_child(e.argv, limits, file + ".out", file + ".err");
  fs::remove(file + ".out");
  fs::remove(file + ".err");
  e.outcome = check_outcome(e.child);
  return e;
}

// The report beside a saved failure: how to rerun it and what happened.
std::string failure_report(const Execution& e, const Failure& f) {
  std::ostringstream out;
  out << "command: " << joined_command(e.argv) << "\n"
      << "status: " << f.status << " after " << format_seconds(e.child.seconds) << " s\n"
      << "failure: " << f.kind << ": " << f.detail << "\n"
      << "class: " << f.failure_class << "\n"
      << "origin: " << f.origin << "\n"
      << "--- stderr (tail) ---\n"
      << tail_lines(e.child.err, 30) << "\n";
  if (f.kind == "bad-json" || f.kind == "no-error-message") {
    out << "--- stdout (head) ---\n" << e.child.out.substr(0, 2000) << "\n";
  }
  return out.str();
}

// Calls work(i) for i in [0, count) on `jobs` TBB threads, one item per task (each runs child processes for
// seconds, so no batching).
void parallel_for(size_t count, int jobs, const std::function<void(size_t)>& work) {
  if (count == 0) return;
  tbb::task_arena arena(std::max(1, jobs));
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, count, 1),
        [&](const tbb::blocked_range<size_t>& range) {
          for (size_t i = range.begin(); i != range.end(); ++i) work(i);
        },
        tbb::simple_partitioner());
  });
}

struct Record {
  std::string status;
  bool timed_out = false;
  std::optional<Failure> failure;
  std::string text;      // kept for failures only (the minimizer's starting point)
  std::string strategy;  // idem
};

// Minimizes one saved failure and records the result beside it.
void minimize_failure(const RunConfig& config, Failure& failure, const std::string& text,
                      const std::string& strategy) {
  size_t attempt = 0;
  const Outcome original{true, false, failure.status, failure.kind, failure.detail};
  auto still_fails = [&](const std::string& candidate) {
    const std::string file =
        config.out_dir + "/work/" + failure.name + ".try-" + std::to_string(attempt++) + ".yaml";
    write_file(file, candidate);
    const Execution e = execute(config, file, strategy);
    fs::remove(file);
    return same_failure(original, e.outcome);
  };
  const std::string smallest =
      minimize_text(text, still_fails, {config.minimize_tries, config.minimize_seconds});
  failure.min_path = config.out_dir + "/failures/" + failure.name + ".min.yaml";
  write_file(failure.min_path, smallest);
  const Execution last = execute(config, failure.min_path, strategy);
  append_file(config.out_dir + "/failures/" + failure.name + ".txt",
              "--- minimized: " + failure.min_path + " (" + std::to_string(smallest.size()) + " bytes, " +
                  std::to_string(attempt) + " tries) ---\ncommand: " + joined_command(last.argv) +
                  "\nstatus: " + last.outcome.status +
                  (last.outcome.failure ? " (" + last.outcome.kind + ")" : " (passes)") +
                  "\n--- stderr (tail) ---\n" + tail_lines(last.child.err, 30) + "\n");
}

}  // namespace

bool cmt_supports_time_limit(const std::string& cmt) {
  const std::string base =
      (fs::temp_directory_path() / ("cmt-fuzz-help-" + std::to_string(getpid()))).string();
  const ChildResult help = run_child({cmt, "verify", "--help"}, {20, 4096}, base + ".out", base + ".err");
  fs::remove(base + ".out");
  fs::remove(base + ".err");
  return (help.out + help.err).find("--time-limit") != std::string::npos;
}

Summary run_inputs(const RunConfig& config, size_t count,
                   const std::function<InputCase(size_t)>& make_input) {
  const auto start = std::chrono::steady_clock::now();
  fs::create_directories(config.out_dir + "/work");
  fs::create_directories(config.out_dir + "/failures");

  std::vector<Record> records(count);
  std::atomic<size_t> done{0};
  std::atomic<size_t> failed{0};
  std::mutex log;
  const size_t every = std::clamp<size_t>(count / 20, 1, 1000);  // long runs report at least every 1,000
  parallel_for(count, config.jobs, [&](size_t i) {
    const InputCase input = make_input(i);
    const std::string file = config.out_dir + "/work/" + input.name + ".yaml";
    write_file(file, input.text);
    const Execution e = execute(config, file, input.strategy);
    Record& r = records[i];
    r.status = e.outcome.status;
    r.timed_out = e.outcome.timed_out;
    if (e.outcome.failure) {
      Failure f{input.name,
                config.out_dir + "/failures/" + input.name + ".yaml",
                "",
                e.outcome.status,
                e.outcome.kind,
                e.outcome.detail,
                failure_class(e.outcome, e.child.err, file),
                input.origin};
      fs::copy_file(file, f.path, fs::copy_options::overwrite_existing);
      write_file(config.out_dir + "/failures/" + input.name + ".txt", failure_report(e, f));
      r.failure = f;
      r.text = input.text;
      r.strategy = input.strategy;
      ++failed;
    }
    fs::remove(file);
    const size_t n = ++done;
    if (!config.quiet && (n % every == 0 || n == count)) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::lock_guard<std::mutex> lock(log);
      std::cerr << "cmt-fuzz: " << n << "/" << count << " inputs, " << failed << " failures, "
                << format_seconds(s) << " s\n";
    }
  });

  Summary summary;
  summary.command = config.command;
  summary.inputs = count;
  summary.time_limit_passed = config.command == "verify" && config.pass_time_limit;
  std::vector<size_t> to_minimize;
  for (size_t i = 0; i < count; ++i) {
    const Record& r = records[i];
    ++summary.by_status[r.status];
    summary.timed_out += r.timed_out;
    if (!r.failure) continue;
    if (summary.classes[r.failure->failure_class]++ == 0 && to_minimize.size() < config.minimize_classes) {
      to_minimize.push_back(i);
    }
  }
  if (!to_minimize.empty() && !config.quiet) {
    std::cerr << "cmt-fuzz: minimizing " << to_minimize.size() << " failure(s), one per class\n";
  }
  parallel_for(to_minimize.size(), config.jobs, [&](size_t k) {
    Record& r = records[to_minimize[k]];
    minimize_failure(config, *r.failure, r.text, r.strategy);
  });
  for (const auto& r : records) {
    if (r.failure) summary.failures.push_back(*r.failure);
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

nlohmann::json summary_json(const Summary& summary) {
  nlohmann::json failures = nlohmann::json::array();
  for (const auto& f : summary.failures) {
    failures.push_back({{"name", f.name},
                        {"path", f.path},
                        {"min_path", f.min_path},
                        {"status", f.status},
                        {"kind", f.kind},
                        {"detail", f.detail},
                        {"class", f.failure_class},
                        {"origin", f.origin}});
  }
  nlohmann::json classes = nlohmann::json::array();
  for (const auto& [signature, n] : summary.classes) {
    const auto example = std::find_if(summary.failures.begin(), summary.failures.end(),
                                      [&](const Failure& f) { return f.failure_class == signature; });
    classes.push_back(
        {{"class", signature}, {"count", n}, {"example", example->path}, {"min_path", example->min_path}});
  }
  return {{"command", summary.command},
          {"inputs", summary.inputs},
          {"by_status", summary.by_status},
          {"timed_out", summary.timed_out},
          {"failure_count", summary.failures.size()},
          {"failures", failures},
          {"failure_classes", classes},
          {"time_limit_passed", summary.time_limit_passed},
          {"seconds", summary.seconds}};
}

std::string summary_text(const Summary& summary) {
  std::ostringstream out;
  out << "cmt-fuzz: " << summary.inputs << " inputs through `cmt " << summary.command << "` in "
      << format_seconds(summary.seconds) << " s\n  by exit status:";
  for (const auto& [status, n] : summary.by_status) out << " [" << status << "] " << n;
  out << "\n  timed_out answers: " << summary.timed_out << "\n  failures: " << summary.failures.size()
      << " in " << summary.classes.size() << " class(es)\n";
  for (const auto& [signature, n] : summary.classes) {
    const auto example = std::find_if(summary.failures.begin(), summary.failures.end(),
                                      [&](const Failure& f) { return f.failure_class == signature; });
    out << "    " << n << " x " << signature << "\n      e.g. " << example->path;
    if (!example->min_path.empty()) out << " (minimized: " << example->min_path << ")";
    out << "\n";
  }
  return out.str();
}

}  // namespace cmt::fuzz

#include "experiments/cli/rollout_cli.h"

#include <cmath>
#include <stdexcept>

#include "models/input_error.h"

namespace cmt {

void add_rollout_sampling_options(CLI::App* cmd, int& n, std::uint64_t& seed, int& threads,
                                  std::string& mode) {
  cmd->add_option("-n", n, "number of rollouts (> 0)")->capture_default_str();
  cmd->add_option("--seed", seed, "master seed; rollout i uses a stream derived from (seed, i)")
      ->capture_default_str();
  cmd->add_option("--threads", threads,
                  "worker threads (default: hardware threads); results do not depend on it");
  cmd->add_option("--mode", mode, "error sampling: uniform, or extreme (mostly on the bounds' boundaries)")
      ->check(CLI::IsMember({"uniform", "extreme"}))
      ->capture_default_str();
}

void check_rollout_sampling_options(int n, int threads) {
  if (n <= 0) throw CLI::ValidationError("-n", "must be > 0, got " + std::to_string(n));
  if (threads < 0) throw CLI::ValidationError("--threads", "must be >= 0, got " + std::to_string(threads));
}

namespace {

std::size_t parameter_index(const Task& task, const std::string& name) {
  std::string names;
  for (std::size_t p = 0; p < task.model_error.size(); ++p) {
    if (task.model_error[p].name == name) return p;
    names += (names.empty() ? "" : ", ") + task.model_error[p].name;
  }
  throw InputError(
      task.source_file, "--world",
      "no model parameter '" + name + "' (the task's: " + (names.empty() ? "none" : names) + ")");
}

double parameter_value(const Task& task, const std::string& item, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(v))
    throw InputError(task.source_file, "--world", "expected NAME=NUMBER, got '" + item + "'");
  return v;
}

}  // namespace

std::shared_ptr<const LoadedTask> task_in_world(std::shared_ptr<const LoadedTask> task,
                                                const std::vector<std::string>& world) {
  if (world.empty()) return task;
  const Task& t = task->task;
  std::vector<double> values;
  for (const ModelParameter& p : t.model_error) values.push_back(p.nominal);
  for (const std::string& item : world) {
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos)
      throw InputError(t.source_file, "--world", "expected NAME=NUMBER, got '" + item + "'");
    const std::size_t p = parameter_index(t, item.substr(0, eq));
    values[p] = parameter_value(t, item, item.substr(eq + 1));
    const ModelParameter& m = t.model_error[p];
    if (!m.admits(values[p]))
      throw InputError(t.source_file, "--world",
                       m.name + " = " + item.substr(eq + 1) +
                           (m.discrete() ? " is not one of its values"
                                         : " is outside its interval [" + std::to_string(m.min) + ", " +
                                               std::to_string(m.max) + "]"));
  }
  return load_task_slice(t, values);
}

}  // namespace cmt

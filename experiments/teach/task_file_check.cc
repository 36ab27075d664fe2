// Physics check of a written task file (task_file_check.h).
#include "experiments/teach/task_file_check.h"

#include <fstream>
#include <stdexcept>

namespace cmt {

TaskFileCheck check_task_file(const std::filesystem::path& file, const std::string& text,
                              const std::string& strategy, ValidateOptions options,
                              const std::string& dir_option) {
  std::ofstream out(file);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + file.string() + " (" + dir_option + ")");
  options.counterexample_budget = 0;
  const ValidationResult r = run_validation(load_task(file), strategy, options);
  TaskFileCheck c;
  c.rollouts = static_cast<int>(r.rollouts.size());
  c.successes = r.successes;
  c.unstable = r.unstable;
  c.outside = r.outside;
  c.soundness = r.soundness;
  if (r.counterexample) c.replay = r.counterexample->replay;
  return c;
}

}  // namespace cmt

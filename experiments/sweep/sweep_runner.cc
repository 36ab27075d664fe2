#include "experiments/sweep/sweep_runner.h"

#include <chrono>
#include <stdexcept>

#include "experiments/common/json_text.h"
#include "experiments/sweep/sweep_progress.h"
#include "models/input_error.h"

namespace cmt {

std::string describe_unit(const SweepUnit& u) {
  std::string s = u.task + "/" + u.strategy + " seed " + std::to_string(u.seed);
  if (!u.params.empty()) {
    s += ' ';  // appended separately: "literal" + string&& trips GCC 12's false -Wrestrict (PR 105329)
    s += json_text(u.params);
  }
  return s;
}

SweepRunCounts run_units(ResultsStore& store, const std::vector<SweepUnit>& units,
                         const std::set<std::string>& done, const UnitExecutor& execute,
                         const SweepRunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  SweepRunCounts counts;
  counts.units = static_cast<int>(units.size());
  std::vector<const SweepUnit*> todo;
  for (const SweepUnit& u : units) {
    if (done.count(u.unit_key))
      ++counts.skipped;
    else
      todo.push_back(&u);
  }
  SweepProgress progress(static_cast<int>(todo.size()), options.progress_bar, options.log_prefix);
  for (const SweepUnit* u : todo) {
    const auto unit_start = std::chrono::steady_clock::now();
    try {
      const UnitRecord record = execute(*u, options.threads);
      if (store.commit_unit(u->unit_key, record))
        ++counts.ran;
      else
        ++counts.taken;
    } catch (const InputError& e) {
      progress.finish();
      throw InputError(e.file(), e.key(), e.reason() + " (in sweep unit " + describe_unit(*u) + ")");
    } catch (const std::exception& e) {
      progress.finish();
      throw std::runtime_error(std::string(e.what()) + " (in sweep unit " + describe_unit(*u) + ")");
    }
    progress.unit_done(describe_unit(*u),
                       std::chrono::duration<double>(std::chrono::steady_clock::now() - unit_start).count());
  }
  progress.finish();
  counts.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return counts;
}

}  // namespace cmt

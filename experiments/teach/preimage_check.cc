// Rollouts from the solved cells of a teaching session (preimage_check.h).
#include "experiments/teach/preimage_check.h"

#include "experiments/teach/task_file_check.h"
#include "experiments/teach/teach_json.h"

namespace cmt {

PreimageCheck check_preimages(const std::string& task_yaml, const teaching::Session& session,
                              const PreimageCheckOptions& options) {
  PreimageCheck out;
  std::filesystem::create_directories(options.dir);
  const std::vector<teaching::TeachStep>& steps = session.steps();
  for (std::size_t s = 0; s < steps.size(); ++s) {
    for (const teaching::StartCell& cell : steps[s].solved) {
      CellCheck c;
      c.step = static_cast<int>(s);
      c.cell = cell.path;
      c.strategy = free_strategy_name(session.task().task, "taught");
      const std::filesystem::path file =
          options.dir / (session.task().task.name + "_step" + std::to_string(s + 1) + "_cell" +
                         (cell.path.empty() ? std::string("_start") : "_" + cell.path) + ".yaml");
      c.task_file = file.string();
      const std::string text = cell_task_yaml(task_yaml, session, cell.chain, c.strategy, cell.region);
      ValidateOptions v;
      v.n = options.n;
      v.seed = options.seed;
      v.threads = options.threads;
      v.mode = options.mode;
      const TaskFileCheck r = check_task_file(file, text, c.strategy, v, "--check-dir");
      c.rollouts = r.rollouts;
      c.successes = r.successes;
      c.unstable = r.unstable;
      c.outside = r.outside;
      c.soundness = r.soundness;
      c.replay = r.replay;
      out.rollouts += c.rollouts;
      out.successes += c.successes;
      out.unstable += c.unstable;
      out.failures += r.failures();
      out.outside += c.outside;
      out.cells.push_back(std::move(c));
    }
  }
  return out;
}

nlohmann::json preimage_check_json(const PreimageCheck& check) {
  nlohmann::json cells = nlohmann::json::array();
  for (const CellCheck& c : check.cells) {
    nlohmann::json j = {{"step", c.step},         {"cell", c.cell},         {"task_file", c.task_file},
                        {"strategy", c.strategy}, {"rollouts", c.rollouts}, {"successes", c.successes},
                        {"unstable", c.unstable}, {"outside", c.outside},   {"soundness", c.soundness}};
    if (!c.replay.empty()) j["replay"] = c.replay;
    cells.push_back(j);
  }
  return {{"rollouts", check.rollouts}, {"successes", check.successes}, {"unstable", check.unstable},
          {"failures", check.failures}, {"outside", check.outside},     {"cells", cells}};
}

}  // namespace cmt

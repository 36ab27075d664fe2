// cmt merge OUT IN... and cmt export-csv DB -o DIR (docs/sweeps.md): combine the results databases of shards
// (a Slurm array, separate machines) into one, and write a database's tables as CSV files.
#include <filesystem>
#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/results/results_store.h"

namespace cmt {

namespace {

// Reading commands must not create an empty database from a mistyped path.
void require_file(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw std::runtime_error(path + ": no such results database");
}

}  // namespace

void add_merge_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string out;
    std::vector<std::string> in;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("merge", "Merge results databases (shards) into one; finished units win");
  cmd->add_option("OUT", o->out, "target results database (created if missing)")->required();
  cmd->add_option("IN", o->in, "results databases to merge in")->required();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([o, &state] {
    for (const std::string& f : o->in) require_file(f);
    ResultsStore store(o->out);
    nlohmann::json inputs = nlohmann::json::array();
    for (const std::string& f : o->in) {
      const MergeCounts c = store.merge_from(f);
      inputs.push_back({{"file", f},
                        {"runs", c.runs},
                        {"new_units", c.new_units},
                        {"merged", c.merged},
                        {"already_done", c.already_done}});
      if (!state.json)
        std::cout << f << ": " << c.merged << " finished units merged, " << c.already_done
                  << " already done, " << c.new_units << " new units\n";
    }
    const nlohmann::json j = {{"db", o->out},
                              {"inputs", inputs},
                              {"done_in_db", store.count_units("done")},
                              {"pending_in_db", store.count_units("pending")}};
    if (state.json) print_json(j);
    state.exit_status = kExitSuccess;
  });
}

void add_export_csv_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string db, dir;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand("export-csv", "Write a results database's tables (and summary.csv) as CSV");
  cmd->add_option("DB", o->db, "results database")->required();
  cmd->add_option("-o,--output", o->dir, "output folder (created if missing)")->required();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->callback([o, &state] {
    require_file(o->db);
    ResultsStore store(o->db);
    nlohmann::json files = nlohmann::json::array();
    for (const auto& f : store.export_csv(o->dir)) files.push_back(f.string());
    if (state.json)
      print_json({{"db", o->db}, {"files", files}});
    else
      for (const auto& f : files) std::cout << f.get<std::string>() << "\n";
    state.exit_status = kExitSuccess;
  });
}

}  // namespace cmt

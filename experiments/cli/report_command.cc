// `cmt report RESULTS.sqlite -o DIR [--teach FILE...] [--edr FILE...] [--plan FILE...] [--json]`: the HTML
// and Markdown report of a sweep's results database with its figures (experiments/report/report.h). Exit
// status 2 when the database is missing, is not a cmt results database or holds bad content.
#include <iostream>

#include "experiments/cli/cli_output.h"
#include "experiments/cli/command.h"
#include "experiments/cli/sticking_command.h"
#include "experiments/cli/view_command.h"
#include "experiments/report/report.h"

namespace cmt {

void add_report_command(CLI::App& app, CommandState& state) {
  struct Options {
    std::string database, out_dir;
    std::vector<std::string> teach, edr, plan;
  };
  auto options = std::make_shared<Options>();
  auto* cmd =
      app.add_subcommand("report", "Write an HTML/Markdown report with figures from a results database");
  cmd->add_option("DATABASE", options->database, "results database written by cmt sweep")->required();
  cmd->add_option("-o,--output", options->out_dir, "report directory (created if missing)")->required();
  cmd->add_flag("--json", state.json, "print one JSON object on stdout");
  cmd->add_option(
      "--teach", options->teach,
      "`cmt teach --json` or `cmt backproject --json` result files to show in a Teaching sessions section");
  cmd->add_option("--edr", options->edr,
                  "`cmt edr --json` result files to show in an Error detection and recovery section");
  cmd->add_option("--plan", options->plan,
                  "`cmt plan --json` result files to show in a Planned strategies section");
  cmd->callback([options, &state] {
    const report::ReportSummary r = report::write_report(
        options->database, options->out_dir, verifier_stick_classes(), replay_counterexample,
        std::vector<std::filesystem::path>(options->teach.begin(), options->teach.end()),
        std::vector<std::filesystem::path>(options->edr.begin(), options->edr.end()),
        std::vector<std::filesystem::path>(options->plan.begin(), options->plan.end()));
    if (state.json)
      print_json({{"index", r.index.string()},
                  {"markdown", r.markdown.string()},
                  {"figures_json", r.figures_json.string()},
                  {"configs", r.configs},
                  {"done", r.done},
                  {"pending", r.pending},
                  {"figures", r.figures}});
    else
      std::cout << "report: " << r.index.string() << " (" << r.configs << " configurations, " << r.done
                << " done, " << r.pending << " pending, " << r.figures << " figures)\n";
    state.exit_status = kExitSuccess;
  });
}

}  // namespace cmt

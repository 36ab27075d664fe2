// `cmt report`: from a results database (cmt sweep) to a report directory:
//   DIR/index.html, DIR/report.md   the table of every configuration (verdict vs physics) and its figures
//   DIR/figures/config_<id>_<view>.png   C-space views with predicted and observed ends (cspace_figure.h)
//   DIR/figures/config_<id>_sticking.png stick fraction vs command angle (sticking_figure.h)
//   DIR/figures.json                 each figure's plot area, data ranges and legend colors (plot_canvas.h)
#pragma once

#include <filesystem>
#include <vector>

#include "experiments/report/view_data.h"

namespace cmt::report {

struct ReportSummary {
  std::filesystem::path index, markdown, figures_json;
  int configs = 0, done = 0, pending = 0, figures = 0;
};

// Throws InputError (file, key, reason) for a bad database or bad content in it, std::runtime_error when the
// output cannot be written.
// `stick_class`: shades the 3-D pages' predicted pieces by their atom's stick class (empty: no shading).
// `replay`: draws each configuration's counterexample trajectory on its 3-D page (empty: none drawn).
// `teach_results`: `cmt teach --json` output files shown in a "Teaching sessions" section (a file that is not
// such JSON is a InputError naming it); `edr_results`: `cmt edr --json` files, an "Error detection and
// recovery" section; `plan_results`: `cmt plan --json` files, a "Planned strategies" section.
ReportSummary write_report(const std::filesystem::path& database, const std::filesystem::path& out_dir,
                           const StickClassOf& stick_class = {}, const CounterexampleReplay& replay = {},
                           const std::vector<std::filesystem::path>& teach_results = {},
                           const std::vector<std::filesystem::path>& edr_results = {},
                           const std::vector<std::filesystem::path>& plan_results = {});

}  // namespace cmt::report

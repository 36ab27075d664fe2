// The report's content independent of its format: a summary block (units, verdicts, soundness, coverage,
// false alarms, times), an overview table with the key columns and a thumbnail per configuration, the full
// table of every column (verdict vs physics), and per-configuration sections with their notes and figures.
// report_documents.h renders it as Markdown and HTML.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "experiments/report/results_db.h"

namespace cmt::report {

// A piece of a table cell or paragraph: plain text, a link, code (a command line) or an image.
struct Span {
  std::string text;  // the alt text of an image
  std::string href;  // non-empty: a link
  bool code = false;
  std::string image;  // non-empty: an image (a thumbnail) shown small, linked to href when that is set
};
using Cell = std::vector<Span>;  // spans are separated by a space

struct Table {
  std::vector<std::string> headers;
  std::vector<std::vector<Cell>> rows;
  // HTML only: a CSS width per column ("" or missing: the column shares what the others leave).
  std::vector<std::string> widths;
};

struct FigureRef {
  std::string file;  // relative to the report directory
  std::string caption;
};

// One configuration as the report shows it.
struct ConfigSection {
  const ConfigRow* row = nullptr;
  std::string label;               // "cube / stick {"friction":0.3}"
  std::vector<FigureRef> figures;  // the C-space views first, then the stick-fraction figure
  std::vector<std::string> notes;  // e.g. "pending: no rollouts yet", the verifier's failure
  std::string
      view_page;  // the configuration's 3-D page (experiments/view), relative to the report; "" if none
};

// The numbers of the summary block. Metrics count over the done configurations; real values are NaN when
// no configuration has one.
struct SummaryStats {
  static constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();
  int configs = 0, done = 0, pending = 0;
  // Verdicts: a configuration without a prediction has none yet; a verifier out of its time budget gives
  // none.
  int reliable = 0, not_reliable = 0, timed_out = 0, no_verdict = 0;
  int rollouts = 0, successes = 0, unstable = 0, ends = 0, outside = 0;
  double min_soundness = kNoValue, mean_soundness = kNoValue;
  int soundness_bugs = 0;
  double min_coverage = kNoValue, mean_coverage = kNoValue;
  // Verified NOT reliable, at least one rollout and every rollout succeeded, and no counterexample recorded.
  int false_alarms = 0;
  double verify_seconds = 0;   // sum over the configurations with a prediction
  double rollout_seconds = 0;  // sum over the done configurations
  // The adversarial search (falsify_table.cc), over the done configurations that have one.
  int falsified = 0, falsify_rollouts = 0, falsify_outside = 0;
  // Of those, the configurations whose failure search ran (verified unreliable), and those where no rollout
  // of any phase failed: false alarms that survived the search.
  int failure_searched = 0, failure_false_alarms = 0;
  double mean_coverage_before = kNoValue, mean_coverage_after = kNoValue;
};

struct SummaryLine {
  std::string label;  // "units", "verdicts", ...
  std::string text;
};

struct ReportContent {
  std::string database;           // path as given
  std::vector<std::string> runs;  // one line per sweep run
  SummaryStats stats;
  std::vector<SummaryLine> summary;  // the stats in words
  Table overview;                    // the first page: key columns, a thumbnail and links per configuration
  Table table;                       // every column, one row per configuration
  // "Adversarial rollouts": one row per configuration with an adversarial search (falsify_table.cc); no
  // rows, no section.
  Table falsify;
  // "Teaching sessions": one row per `cmt teach --json` result given to `cmt report --teach`; no rows, no
  // section.
  Table teaching;
  // "Error detection and recovery": one row per `cmt edr --json` result given to `cmt report --edr`, and per
  // result with a physics check its outcomes against the first model parameter (edr_figure.h).
  Table edr;
  std::vector<FigureRef> edr_figures;
  // "Planned strategies": one row per `cmt plan --json` result given to `cmt report --plan`; for results
  // with §6.3.4's experiment (`--extremes`), a row per motion in `extremes` and a figure each
  // (extremes_figure.h).
  Table planner;
  std::vector<FigureRef> plan_figures;  // per plan with a loadable task_file, its cells in each view
  Table extremes;
  std::vector<FigureRef> extremes_figures;
  std::vector<ConfigSection> sections;
};

// "task / strategy {params}" (params omitted when empty).
std::string config_label(const ConfigRow& row);
// A number with `decimals` fixed decimals, "n/a" when NaN or infinite.
std::string format_fixed(double value, int decimals);
// The replay command of a counterexample JSON ("replay"), its compact JSON when it has none, "" for null.
std::string counterexample_command(const nlohmann::json& counterexample);
// The HTML id of a configuration's section: "config-<id>".
std::string section_anchor(const ConfigRow& row);
// See SummaryStats::false_alarms.
bool is_false_alarm(const ConfigRow& row);
// The verdict column's text: "reliable", "NOT reliable", "verifier timed out" or "pending".
std::string verdict_text(const ConfigRow& row);

// A member of a JSON object; missing members, and any member of a non-object, read as null (the sections
// built from commands' JSON show what the object has).
const nlohmann::json& json_member(const nlohmann::json& j, const char* key);
// A number member, 0 when missing or not a number; a boolean member, false when missing or not a boolean.
double json_number(const nlohmann::json& j, const char* key);
bool json_flag(const nlohmann::json& j, const char* key);
// A table cell of plain text.
Cell text_cell(const std::string& s);

// ---- The adversarial search (falsify_table.cc; docs/falsify.md "In sweeps and the report") ----

// The configuration's search (metrics.falsify) when it is done and has one, else nullptr.
const nlohmann::json* falsify_data(const ConfigRow& row);
// The "Adversarial rollouts" table: per configuration with a search, its task / strategy, verdict, search
// rollouts, searches, ends outside found by the search, the best signed distance per motion, coverage
// before -> after, pieces reached / total and the unreached pieces (step, motion, atom name, kind,
// measure).
Table falsify_table(const std::vector<ConfigSection>& sections);

// ---- Teaching sessions (teaching_table.cc; docs/teaching.md) ----

// A `cmt teach --json` object and the label it is shown under (its file name).
struct TeachingRun {
  std::string label;
  nlohmann::json result;
  std::string view_link;  // the teaching session's 3-D page relative to the report, "" without one
};
Table teaching_table(const std::vector<TeachingRun>& runs);

// ---- Planned strategies (planner_table.cc; docs/planner.md) ----

// Per `cmt plan --json` object: task, found (or why not), the motions, the verifier's verdict, the rollouts.
Table planner_table(const std::vector<nlohmann::json>& runs);
// Per motion of each result with `extremes`: task, motion, what it claims (a cell, or one commanded
// position), its vertices' rollouts and successes, and the success rate at each growth.
Table extremes_table(const std::vector<nlohmann::json>& runs);

// ---- Error detection and recovery (edr_table.cc; docs/edr.md) ----

// Per `cmt edr --json` object: task, strategy, the verdict and why not, per slice the goal's termination area
// and H's, the confusable pairs found, seconds.
Table edr_table(const std::vector<nlohmann::json>& runs);
// The configuration's note on its search ("" without one): rollouts, ends outside, the farthest one's
// replay command.
std::string falsify_note(const ConfigRow& row);
// Adds the search's numbers of a configuration to the summary counts (SummaryStats::falsified ...); the
// means are finished by summarize.
void count_falsify(const ConfigRow& row, SummaryStats& stats, double* sum_before, double* sum_after,
                   int* with_coverage);

SummaryStats summarize(const std::vector<ConfigSection>& sections);
std::vector<SummaryLine> summary_lines(const SummaryStats& stats);

// Builds the summary, the overview and the full table (one row per section, in order) from the sections.
ReportContent build_report_content(const ResultsDb& db, std::vector<ConfigSection> sections);

}  // namespace cmt::report

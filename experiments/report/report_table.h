// The report's content independent of its format: the per-configuration table (verdict vs physics), the
// summary line and per-configuration sections with their figures. report_documents.h renders it as Markdown
// and HTML.
#pragma once

#include <string>
#include <vector>

#include "experiments/report/results_db.h"

namespace cmt::report {

// A piece of a table cell or paragraph: plain text, a link, or code (a command line).
struct Span {
  std::string text;
  std::string href;  // non-empty: a link
  bool code = false;
};
using Cell = std::vector<Span>;  // spans are separated by a space

struct Table {
  std::vector<std::string> headers;
  std::vector<std::vector<Cell>> rows;
};

struct FigureRef {
  std::string file;  // relative to the report directory
  std::string caption;
};

// One configuration as the report shows it.
struct ConfigSection {
  const ConfigRow* row = nullptr;
  std::string label;  // "cube / stick {"friction":0.3}"
  std::vector<FigureRef> figures;
  std::vector<std::string> notes;  // e.g. "pending: no rollouts yet", the verifier's failure
};

struct ReportContent {
  std::string database;           // path as given
  std::vector<std::string> runs;  // one line per sweep run
  std::string summary;
  Table table;
  std::vector<ConfigSection> sections;
};

// "task / strategy {params}" (params omitted when empty).
std::string config_label(const ConfigRow& row);
// A number with `decimals` fixed decimals, "n/a" when NaN or infinite.
std::string format_fixed(double value, int decimals);
// The replay command of a counterexample JSON ("replay"), its compact JSON when it has none, "" for null.
std::string counterexample_command(const nlohmann::json& counterexample);

// Builds the table (one row per section, in order) and the summary line from the sections.
ReportContent build_report_content(const ResultsDb& db, std::vector<ConfigSection> sections);

}  // namespace cmt::report

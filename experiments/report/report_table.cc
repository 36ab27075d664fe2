#include "experiments/report/report_table.h"

#include <cmath>
#include <cstdio>

#include "experiments/common/json_text.h"
#include "experiments/common/verifier_budget.h"

namespace cmt::report {
namespace {

// Soundness and coverage are fractions judged against 1: four decimals show a single outside end in 10^4.
constexpr int kFractionDecimals = 4;
constexpr int kSecondsDecimals = 2;
constexpr int kRadiusDecimals = 3;

Cell text(const std::string& s) { return {{s, "", false}}; }

std::string percent(int part, int whole) {
  if (whole <= 0) return "n/a";
  return format_fixed(100.0 * part / whole, 1) + "%";
}

std::string verdict(const ConfigRow& c) {
  if (!c.prediction) return "pending";
  // A unit whose verifier ran out of its time budget has no verdict (experiments/common/verifier_budget.h).
  if (c.prediction->failure.rfind(kVerifierTimedOut, 0) == 0) return "verifier timed out";
  return c.prediction->reliable ? "reliable" : "NOT reliable";
}

std::vector<Cell> table_row(const ConfigSection& s) {
  const ConfigRow& c = *s.row;
  std::vector<Cell> row;
  row.push_back(text(std::to_string(c.config_id)));
  row.push_back(text(c.task));
  row.push_back(text(c.strategy));
  row.push_back(text(c.params.empty() ? "-" : json_text(c.params)));
  row.push_back(text(verdict(c)));
  row.push_back(text(c.done() ? "done" : "pending"));
  row.push_back(text(std::to_string(c.seed)));
  if (c.done() && c.metrics) {
    const MetricsRow& m = *c.metrics;
    row.push_back(text(std::to_string(m.rollouts)));
    row.push_back(text(std::to_string(m.successes) + " (" + percent(m.successes, m.rollouts) + ")"));
    row.push_back(text(std::to_string(m.unstable)));
    row.push_back(text(std::to_string(m.ends)));
    row.push_back(text(std::to_string(m.outside)));
    row.push_back(text(format_fixed(m.soundness, kFractionDecimals)));
    row.push_back(text(format_fixed(m.coverage, kFractionDecimals) + " (r " +
                       format_fixed(m.coverage_radius, kRadiusDecimals) + ")"));
    row.push_back(text(m.soundness_bug ? "BUG" : "no"));
    const std::string replay = counterexample_command(m.counterexample);
    row.push_back(replay.empty() ? text("-") : Cell{{replay, "", true}});
    row.push_back(text(format_fixed(m.verify_seconds, kSecondsDecimals)));
    row.push_back(text(format_fixed(m.rollout_seconds, kSecondsDecimals)));
  } else {
    row.push_back(text(std::to_string(c.n)));                    // requested
    for (int i = 0; i < 8; ++i) row.push_back(text("pending"));  // successes .. counterexample
    row.push_back(
        text(c.prediction ? format_fixed(c.prediction->verify_seconds, kSecondsDecimals) : "pending"));
    row.push_back(text("pending"));
  }
  Cell figures;
  for (const FigureRef& f : s.figures) figures.push_back({f.caption, f.file, false});
  row.push_back(figures.empty() ? text("-") : figures);
  return row;
}

std::string summary(const std::vector<ConfigSection>& sections) {
  int done = 0, pending = 0, predicted = 0, reliable = 0, bugs = 0, rollouts = 0, ends = 0, outside = 0;
  double soundness_sum = 0;
  int soundness_count = 0;
  for (const ConfigSection& s : sections) {
    const ConfigRow& c = *s.row;
    if (c.prediction) {
      ++predicted;
      reliable += c.prediction->reliable;
    }
    if (!c.done() || !c.metrics) {
      ++pending;
      continue;
    }
    ++done;
    const MetricsRow& m = *c.metrics;
    bugs += m.soundness_bug;
    rollouts += m.rollouts;
    ends += m.ends;
    outside += m.outside;
    if (std::isfinite(m.soundness)) {
      soundness_sum += m.soundness;
      ++soundness_count;
    }
  }
  return std::to_string(sections.size()) + " configurations (" + std::to_string(done) + " done, " +
         std::to_string(pending) + " pending); " + std::to_string(reliable) + " of " +
         std::to_string(predicted) + " predicted reliable; " + std::to_string(bugs) + " soundness bugs; " +
         std::to_string(rollouts) + " rollouts, " + std::to_string(outside) + " of " + std::to_string(ends) +
         " motion ends outside the prediction; mean soundness " +
         (soundness_count ? format_fixed(soundness_sum / soundness_count, kFractionDecimals) : "n/a") + ".";
}

}  // namespace

std::string config_label(const ConfigRow& row) {
  std::string label = row.task + " / " + row.strategy;
  if (!row.params.empty()) {  // two appends: GCC 12 warns falsely (-Wrestrict, bug 105329) on " " + string
    label += ' ';
    label += json_text(row.params);
  }
  return label;
}

std::string format_fixed(double value, int decimals) {
  if (!std::isfinite(value)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

std::string counterexample_command(const nlohmann::json& counterexample) {
  if (counterexample.is_null()) return "";
  if (counterexample.is_object() && counterexample.contains("replay") && counterexample["replay"].is_string())
    return counterexample["replay"].get<std::string>();
  return json_text(counterexample);
}

ReportContent build_report_content(const ResultsDb& db, std::vector<ConfigSection> sections) {
  ReportContent out;
  out.database = db.path.string();
  for (const RunRow& r : db.runs)
    out.runs.push_back("run " + std::to_string(r.run_id) + ": " + (r.spec_path.empty() ? "-" : r.spec_path) +
                       (r.created.empty() ? "" : ", created " + r.created));
  out.table.headers = {"config",        "task",
                       "strategy",      "params",
                       "verdict",       "status",
                       "seed",          "N",
                       "successes",     "unstable",
                       "ends",          "outside",
                       "soundness",     "coverage (radius)",
                       "soundness bug", "counterexample replay",
                       "verify s",      "rollout s",
                       "figures"};
  for (const ConfigSection& s : sections) out.table.rows.push_back(table_row(s));
  out.summary = summary(sections);
  out.sections = std::move(sections);
  return out;
}

}  // namespace cmt::report

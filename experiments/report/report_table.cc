#include "experiments/report/report_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "experiments/common/json_text.h"
#include "experiments/common/verifier_budget.h"

namespace cmt::report {

Cell text_cell(const std::string& s) { return {{s, "", false, ""}}; }

const nlohmann::json& json_member(const nlohmann::json& j, const char* key) {
  static const nlohmann::json null;
  if (!j.is_object()) return null;
  const auto it = j.find(key);
  return it == j.end() ? null : *it;
}

double json_number(const nlohmann::json& j, const char* key) {
  const nlohmann::json& v = json_member(j, key);
  return v.is_number() ? v.get<double>() : 0.0;
}

bool json_flag(const nlohmann::json& j, const char* key) {
  const nlohmann::json& v = json_member(j, key);
  return v.is_boolean() && v.get<bool>();
}
namespace {

// Soundness and coverage are fractions judged against 1: four decimals show a single outside end in 10^4.
constexpr int kFractionDecimals = 4;
constexpr int kSecondsDecimals = 2;
constexpr int kRadiusDecimals = 3;
constexpr const char* kPending = "pending";

Cell link(const std::string& s, const std::string& href) { return {{s, href, false, ""}}; }

std::string percent(int part, int whole) {
  if (whole <= 0) return "n/a";
  return format_fixed(100.0 * part / whole, 1) + "%";
}

enum class Verdict { kPending, kReliable, kNotReliable, kTimedOut };

Verdict verdict_of(const ConfigRow& c) {
  if (!c.prediction) return Verdict::kPending;
  // A unit whose verifier ran out of its time budget has no verdict (experiments/common/verifier_budget.h).
  if (c.prediction->failure.rfind(kVerifierTimedOut, 0) == 0) return Verdict::kTimedOut;
  return c.prediction->reliable ? Verdict::kReliable : Verdict::kNotReliable;
}

std::string verdict(const ConfigRow& c) {
  switch (verdict_of(c)) {
    case Verdict::kPending:
      return kPending;
    case Verdict::kReliable:
      return "reliable";
    case Verdict::kNotReliable:
      return "NOT reliable";
    case Verdict::kTimedOut:
      return "verifier timed out";
  }
  return kPending;
}

// The metrics of a configuration that is done, else nullptr.
const MetricsRow* done_metrics(const ConfigRow& c) { return c.done() && c.metrics ? &*c.metrics : nullptr; }

std::vector<Cell> full_row(const ConfigSection& s) {
  const ConfigRow& c = *s.row;
  std::vector<Cell> row;
  row.push_back(text_cell(std::to_string(c.config_id)));
  row.push_back(text_cell(c.task));
  row.push_back(text_cell(c.strategy));
  row.push_back(text_cell(c.params.empty() ? "-" : json_text(c.params)));
  row.push_back(text_cell(verdict(c)));
  row.push_back(text_cell(c.done() ? "done" : kPending));
  row.push_back(text_cell(std::to_string(c.seed)));
  if (const MetricsRow* m = done_metrics(c)) {
    row.push_back(text_cell(std::to_string(m->rollouts)));
    row.push_back(text_cell(std::to_string(m->successes) + " (" + percent(m->successes, m->rollouts) + ")"));
    row.push_back(text_cell(std::to_string(m->unstable)));
    row.push_back(text_cell(std::to_string(m->ends)));
    row.push_back(text_cell(std::to_string(m->outside)));
    row.push_back(text_cell(format_fixed(m->soundness, kFractionDecimals)));
    row.push_back(text_cell(format_fixed(m->coverage, kFractionDecimals) + " (r " +
                            format_fixed(m->coverage_radius, kRadiusDecimals) + ")"));
    row.push_back(text_cell(m->soundness_bug ? "BUG" : "no"));
    const std::string replay = counterexample_command(m->counterexample);
    row.push_back(replay.empty() ? text_cell("-") : Cell{{replay, "", true, ""}});
    row.push_back(text_cell(format_fixed(m->verify_seconds, kSecondsDecimals)));
    row.push_back(text_cell(format_fixed(m->rollout_seconds, kSecondsDecimals)));
  } else {
    row.push_back(text_cell(std::to_string(c.n)));                   // requested
    for (int i = 0; i < 8; ++i) row.push_back(text_cell(kPending));  // successes .. counterexample
    row.push_back(
        text_cell(c.prediction ? format_fixed(c.prediction->verify_seconds, kSecondsDecimals) : kPending));
    row.push_back(text_cell(kPending));
  }
  Cell figures;
  for (const FigureRef& f : s.figures) figures.push_back({f.caption, f.file, false, ""});
  row.push_back(figures.empty() ? text_cell("-") : figures);
  return row;
}

std::string overview_verdict(const ConfigRow& c) {
  return is_false_alarm(c) ? verdict(c) + " (no failure found)" : verdict(c);
}

std::string overview_soundness(const MetricsRow& m) {
  const std::string value = format_fixed(m.soundness, kFractionDecimals);
  return m.soundness_bug ? value + ", BUG" : value;
}

// "#config-<id>", a link to the configuration's section. Built with += only: GCC 12 reports a false
// -Wrestrict on "literal" + std::string, its bug 105329.
std::string section_link(const ConfigRow& c) {
  std::string href = "#";
  href += section_anchor(c);
  return href;
}

// The configuration's first figure (a C-space view), small, linked to the full-size PNG.
Cell thumbnail(const ConfigSection& s) {
  if (s.figures.empty()) return text_cell("-");
  const FigureRef& f = s.figures.front();
  return {{f.caption, f.file, false, f.file}};
}

Cell links(const ConfigSection& s) {
  Cell cell = link("details", section_link(*s.row));
  if (!s.view_page.empty()) cell.push_back({"3-D view", s.view_page, false, ""});
  return cell;
}

std::vector<Cell> overview_row(const ConfigSection& s) {
  const ConfigRow& c = *s.row;
  std::vector<Cell> row;
  row.push_back(link(std::to_string(c.config_id), section_link(c)));
  row.push_back(text_cell(s.label));
  row.push_back(text_cell(overview_verdict(c)));
  if (const MetricsRow* m = done_metrics(c)) {
    row.push_back(text_cell(std::to_string(m->successes) + "/" + std::to_string(m->rollouts)));
    row.push_back(text_cell(overview_soundness(*m)));
    row.push_back(text_cell(format_fixed(m->coverage, kFractionDecimals)));
  } else {
    for (int i = 0; i < 3; ++i) row.push_back(text_cell(kPending));
  }
  row.push_back(thumbnail(s));
  row.push_back(links(s));
  return row;
}

Table overview_table(const std::vector<ConfigSection>& sections) {
  Table t;
  t.headers = {"config",    "configuration", "verdict", "rollouts ok/all",
               "soundness", "coverage",      "figure",  "links"};
  // The thumbnails are 120 px wide; the label takes what the fixed columns leave.
  t.widths = {"4.5em", "", "9em", "6em", "6.5em", "5.5em", "136px", "6em"};
  for (const ConfigSection& s : sections) t.rows.push_back(overview_row(s));
  return t;
}

Table full_table(const std::vector<ConfigSection>& sections) {
  Table t;
  t.headers = {"config",        "task",
               "strategy",      "params",
               "verdict",       "status",
               "seed",          "N",
               "successes",     "unstable",
               "ends",          "outside",
               "soundness",     "coverage (radius)",
               "soundness bug", "counterexample replay",
               "verify s",      "rollout s",
               "figures"};
  for (const ConfigSection& s : sections) t.rows.push_back(full_row(s));
  return t;
}

// Minimum and mean of the finite values added.
class MinMean {
 public:
  void add(double v) {
    if (!std::isfinite(v)) return;
    min_ = count_ ? std::min(min_, v) : v;
    sum_ += v;
    ++count_;
  }
  double min() const { return count_ ? min_ : SummaryStats::kNoValue; }
  double mean() const { return count_ ? sum_ / count_ : SummaryStats::kNoValue; }

 private:
  double min_ = 0, sum_ = 0;
  int count_ = 0;
};

void count_verdict(const ConfigRow& c, SummaryStats& s) {
  switch (verdict_of(c)) {
    case Verdict::kPending:
      ++s.no_verdict;
      break;
    case Verdict::kReliable:
      ++s.reliable;
      break;
    case Verdict::kNotReliable:
      ++s.not_reliable;
      break;
    case Verdict::kTimedOut:
      ++s.timed_out;
      break;
  }
  if (c.prediction && std::isfinite(c.prediction->verify_seconds))
    s.verify_seconds += c.prediction->verify_seconds;
}

void count_metrics(const MetricsRow& m, SummaryStats& s) {
  s.rollouts += m.rollouts;
  s.successes += m.successes;
  s.unstable += m.unstable;
  s.ends += m.ends;
  s.outside += m.outside;
  s.soundness_bugs += m.soundness_bug;
  if (std::isfinite(m.rollout_seconds)) s.rollout_seconds += m.rollout_seconds;
}

// "1 soundness bug", "2 soundness bugs".
std::string count_of(int n, const std::string& noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

std::string verdicts_text(const SummaryStats& s) {
  std::string out =
      std::to_string(s.reliable) + " reliable, " + std::to_string(s.not_reliable) + " NOT reliable";
  if (s.timed_out) out += ", " + std::to_string(s.timed_out) + " verifier timed out";
  if (s.no_verdict) out += ", " + std::to_string(s.no_verdict) + " without a verdict yet";
  return out;
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

std::string verdict_text(const ConfigRow& row) { return verdict(row); }

std::string section_anchor(const ConfigRow& row) { return "config-" + std::to_string(row.config_id); }

bool is_false_alarm(const ConfigRow& row) {
  const MetricsRow* m = done_metrics(row);
  return verdict_of(row) == Verdict::kNotReliable && m && m->rollouts > 0 && m->successes == m->rollouts &&
         m->counterexample.is_null();
}

SummaryStats summarize(const std::vector<ConfigSection>& sections) {
  SummaryStats s;
  MinMean soundness, coverage;
  double before = 0, after = 0;
  int with_coverage = 0;
  for (const ConfigSection& section : sections) {
    const ConfigRow& c = *section.row;
    count_falsify(c, s, &before, &after, &with_coverage);
    ++s.configs;
    ++(c.done() ? s.done : s.pending);
    count_verdict(c, s);
    s.false_alarms += is_false_alarm(c);
    if (const MetricsRow* m = done_metrics(c)) {
      count_metrics(*m, s);
      soundness.add(m->soundness);
      coverage.add(m->coverage);
    }
  }
  s.min_soundness = soundness.min();
  s.mean_soundness = soundness.mean();
  s.min_coverage = coverage.min();
  s.mean_coverage = coverage.mean();
  if (with_coverage > 0) {
    s.mean_coverage_before = before / with_coverage;
    s.mean_coverage_after = after / with_coverage;
  }
  return s;
}

std::vector<SummaryLine> summary_lines(const SummaryStats& s) {
  const auto fraction = [](double v) { return format_fixed(v, kFractionDecimals); };
  const auto seconds = [](double v) { return format_fixed(v, kSecondsDecimals) + " s"; };
  std::vector<SummaryLine> lines = {
      {"units", count_of(s.configs, "configuration") + ": " + std::to_string(s.done) + " done, " +
                    std::to_string(s.pending) + " pending"},
      {"verdicts", verdicts_text(s)},
      {"rollouts", std::to_string(s.successes) + " of " + std::to_string(s.rollouts) + " succeeded, " +
                       std::to_string(s.unstable) + " unstable; " + std::to_string(s.outside) + " of " +
                       std::to_string(s.ends) + " motion ends outside the prediction"},
      {"soundness", "min " + fraction(s.min_soundness) + ", mean " + fraction(s.mean_soundness) + "; " +
                        count_of(s.soundness_bugs, "soundness bug") +
                        " (verified reliable, a rollout failed)"},
      {"coverage", "min " + fraction(s.min_coverage) + ", mean " + fraction(s.mean_coverage)},
      {"false alarms", std::to_string(s.false_alarms) +
                           " (verified NOT reliable, every rollout succeeded, no counterexample found)"},
      {"time",
       "verify " + seconds(s.verify_seconds) + ", rollouts " + seconds(s.rollout_seconds) + " (totals)"},
  };
  if (s.falsified > 0)
    lines.push_back(
        {"adversarial rollouts",
         count_of(s.falsified, "configuration") + " searched: " + std::to_string(s.falsify_rollouts) +
             " search rollouts, " + std::to_string(s.falsify_outside) +
             " motion ends outside the prediction found by the search; mean coverage " +
             fraction(s.mean_coverage_before) + " before, " + fraction(s.mean_coverage_after) + " after" +
             (s.failure_searched > 0
                  ? "; failure search under " + count_of(s.failure_searched, "unreliable verdict") + ": " +
                        std::to_string(s.failure_false_alarms) + " with no failing rollout (false alarms)"
                  : std::string())});
  return lines;
}

ReportContent build_report_content(const ResultsDb& db, std::vector<ConfigSection> sections) {
  ReportContent out;
  out.database = db.path.string();
  for (const RunRow& r : db.runs)
    out.runs.push_back("run " + std::to_string(r.run_id) + ": " + (r.spec_path.empty() ? "-" : r.spec_path) +
                       (r.created.empty() ? "" : ", created " + r.created));
  out.stats = summarize(sections);
  out.summary = summary_lines(out.stats);
  out.overview = overview_table(sections);
  out.table = full_table(sections);
  out.falsify = falsify_table(sections);
  out.sections = std::move(sections);
  return out;
}

}  // namespace cmt::report

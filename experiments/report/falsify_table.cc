// The report's "Adversarial rollouts" section (report_table.h falsify_table; docs/falsify.md "In sweeps and
// the report"): per configuration whose sweep unit ran the adversarial search, the numbers of its
// metrics.falsify object (`cmt falsify --json`'s, without `threads`), and the summary counts and notes.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include "experiments/report/report_table.h"

namespace cmt::report {

namespace {

using nlohmann::json;

constexpr int kFractionDecimals = 4;  // coverage, as in the main table

const json& member(const json& j, const char* key) { return json_member(j, key); }

double number(const json& j, const char* key) {
  const json& v = member(j, key);
  return v.is_number() ? v.get<double>() : SummaryStats::kNoValue;
}

int integer(const json& j, const char* key) {
  const json& v = member(j, key);
  return v.is_number() ? static_cast<int>(v.get<double>()) : 0;
}

std::string string(const json& j, const char* key) {
  const json& v = member(j, key);
  return v.is_string() ? v.get<std::string>() : "";
}

const json& array(const json& j, const char* key) {
  static const json empty = json::array();
  const json& v = member(j, key);
  return v.is_array() ? v : empty;
}

// Four significant digits: distances and measures come in the task's units, whatever its scale.
std::string significant(double v) {
  if (!std::isfinite(v)) return "n/a";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::string section_link(const ConfigRow& c) {
  std::string href = "#";
  href += section_anchor(c);
  return href;
}

// "v1 -0.0123; v2 0.5 (outside)": per prediction step, the falsification's largest signed distance.
std::string best_distances(const json& f) {
  std::string out;
  for (const json& m : array(f, "motions")) {
    if (!out.empty()) out += "; ";
    const double d = number(m, "best_signed_distance");
    out += string(m, "motion");
    out += ' ';
    out += significant(d);
    if (std::isfinite(d) && d > 0) out += " (outside)";
  }
  return out.empty() ? "-" : out;
}

std::string coverage_change(const json& f) {
  return format_fixed(number(f, "coverage_before"), kFractionDecimals) + " → " +
         format_fixed(number(f, "coverage_after"), kFractionDecimals);
}

// "7/9 (random 5, falsify 1, coverage 1)".
std::string pieces_reached(const json& f) {
  const json& pieces = array(f, "pieces");
  std::map<std::string, int> by;
  int reached = 0;
  for (const json& p : pieces)
    if (member(p, "reached").is_boolean() && member(p, "reached").get<bool>()) {
      ++reached;
      ++by[string(p, "reached_by")];
    }
  std::string out = std::to_string(reached) + "/" + std::to_string(pieces.size());
  std::string detail;
  for (const char* how : {"random", "falsify", "coverage", "gap"})
    if (by.count(how))
      detail += (detail.empty() ? "" : ", ") + std::string(how) + " " + std::to_string(by[how]);
  return detail.empty() ? out : out + " (" + detail + ")";
}

// "step 1 v2: f3 (face, measure 0.25, closest end 0.01, searched)"; one per unreached piece.
Cell unreached(const json& f) {
  Cell cell;
  const json& pieces = array(f, "unreached_pieces");
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const json& p = pieces[i];
    std::string s = "step " + std::to_string(integer(p, "step")) + " " + string(p, "motion") + ": " +
                    string(p, "atom_name") + " (" + string(p, "kind") + ", measure " +
                    significant(number(p, "measure"));
    if (const double closest = number(p, "closest_end"); std::isfinite(closest))
      s += ", closest end " + significant(closest);
    if (member(p, "searched").is_boolean() && member(p, "searched").get<bool>()) s += ", searched";
    s += i + 1 < pieces.size() ? ");" : ")";
    cell.push_back({s, "", false, ""});
  }
  return cell.empty() ? text_cell("-") : cell;
}

// Unreached gaps listed in the report's cell, the nearest approaches first.
constexpr std::size_t kReportedGaps = 3;

// "1/3; unreached: p2 at (0.381, 1, -1.705), closest end 0.602; ..."; "0/0 (no gap)" when the search found
// every lattice point covered; "-" without a gap search.
Cell gaps(const json& f) {
  const json& all = array(f, "gaps");
  if (all.empty()) return text_cell(integer(f, "gap_budget") > 0 ? "0/0 (no gap)" : "-");
  std::string text = std::to_string(integer(f, "gaps_reached")) + "/" + std::to_string(all.size());
  std::vector<const json*> unreached;
  for (const json& g : all)
    if (member(g, "reached").is_boolean() && !member(g, "reached").get<bool>()) unreached.push_back(&g);
  std::stable_sort(unreached.begin(), unreached.end(), [](const json* a, const json* b) {
    const double da = number(*a, "closest_end"), db = number(*b, "closest_end");
    return std::isfinite(da) && (!std::isfinite(db) || da < db);
  });
  for (std::size_t i = 0; i < unreached.size() && i < kReportedGaps; ++i) {
    const json& g = *unreached[i];
    std::string at;
    for (const json& x : array(g, "point"))
      at += (at.empty() ? "" : ", ") + significant(x.is_number() ? x.get<double>() : SummaryStats::kNoValue);
    text += "; unreached: " + string(g, "motion") + " at (" + at + "), closest end " +
            significant(number(g, "closest_end"));
  }
  if (unreached.size() > kReportedGaps)
    text += "; and " + std::to_string(unreached.size() - kReportedGaps) + " more unreached";
  return text_cell(text);
}

bool flag(const json& j, const char* key) {
  const json& v = member(j, key);
  return v.is_boolean() && v.get<bool>();
}

// The failure search under an unreliable verdict (docs/falsify.md "Failure search"): "-" without a budget,
// "not run (reliable)" under a reliable verdict, else "400 rollouts, closest 0.3 to a predicted failure; 2
// failed (first by failure, 0.12 from the goal)" or "...; none failed: a false alarm". `failures` counts the
// failed rollouts of every phase, the random ones included.
std::string failure_search(const json& f) {
  if (!flag(f, "failure_searched"))
    return integer(f, "failure_budget") > 0 && flag(f, "reliable") ? "not run (reliable)" : "-";
  std::string out = std::to_string(integer(f, "failure_rollouts")) + " rollouts";
  if (const double closest = number(f, "failure_closest"); std::isfinite(closest))
    out += ", closest " + significant(closest) + " to a predicted failure";
  const int failures = integer(f, "failures");
  if (failures == 0) return out + "; none failed: a false alarm";
  out += "; " + std::to_string(failures) + " failed";
  const json& first = member(f, "first_failure");
  if (first.is_object())
    out += " (first by " + string(first, "how") + ", " + significant(number(first, "goal_distance")) +
           " from the goal)";
  return out;
}

std::vector<Cell> falsify_row(const ConfigSection& s, const json& f) {
  const ConfigRow& c = *s.row;
  std::vector<Cell> row;
  row.push_back({{std::to_string(c.config_id), section_link(c), false, ""}});
  row.push_back(text_cell(s.label));
  row.push_back(text_cell(verdict_text(c)));
  std::string rollouts = std::to_string(integer(f, "rollouts"));
  if (const int unstable = integer(f, "unstable"); unstable > 0)
    rollouts += " (" + std::to_string(unstable) + " unstable)";
  row.push_back(text_cell(rollouts));
  row.push_back(text_cell(std::to_string(integer(f, "searches"))));
  row.push_back(text_cell(std::to_string(integer(f, "outside"))));
  row.push_back(text_cell(best_distances(f)));
  row.push_back(text_cell(coverage_change(f)));
  row.push_back(text_cell(pieces_reached(f)));
  row.push_back(unreached(f));
  row.push_back(gaps(f));
  row.push_back(text_cell(failure_search(f)));
  return row;
}

}  // namespace

const nlohmann::json* falsify_data(const ConfigRow& row) {
  if (!row.done() || !row.metrics || !row.metrics->falsify.is_object()) return nullptr;
  return &row.metrics->falsify;
}

Table falsify_table(const std::vector<ConfigSection>& sections) {
  Table t;
  t.headers = {"id",  // not "config": the full table's first header, which report.md readers look for
               "configuration",
               "verdict",
               "search rollouts",
               "searches",
               "ends outside (search)",
               "best signed distance per motion",
               "coverage before → after",
               "pieces reached/total",
               "unreached pieces",
               "gaps reached/targeted",
               "failure search (unreliable verdicts)"};
  for (const ConfigSection& s : sections)
    if (const json* f = falsify_data(*s.row)) t.rows.push_back(falsify_row(s, *f));
  return t;
}

std::string falsify_note(const ConfigRow& row) {
  const json* f = falsify_data(row);
  if (f == nullptr) return "";
  std::string note = "adversarial search: " + std::to_string(integer(*f, "rollouts")) + " search rollouts, ";
  const int outside = integer(*f, "outside");
  std::string failure;
  if (flag(*f, "failure_searched"))
    failure = integer(*f, "failures") == 0
                  ? "; failure search: none of " + std::to_string(integer(*f, "failure_rollouts")) +
                        " rollouts failed (a false alarm)"
                  : "; failure search: " + failure_search(*f);
  if (outside == 0)
    return note + "no motion end outside the prediction; coverage " + coverage_change(*f) + failure;
  note += std::to_string(outside) + " motion end" + (outside == 1 ? "" : "s") + " outside the prediction";
  const json& bugs = array(*f, "soundness_bugs");
  if (!bugs.empty()) {
    const json& worst = bugs.front();  // farthest first
    note += " (farthest " + significant(number(worst, "distance")) + ")";
    if (const std::string replay = string(worst, "replay"); !replay.empty())
      note += ", replay with: " + replay;
  }
  return note + failure;
}

void count_falsify(const ConfigRow& row, SummaryStats& s, double* sum_before, double* sum_after,
                   int* with_coverage) {
  const json* f = falsify_data(row);
  if (f == nullptr) return;
  ++s.falsified;
  s.falsify_rollouts += integer(*f, "rollouts");
  s.falsify_outside += integer(*f, "outside");
  if (flag(*f, "failure_searched")) {
    ++s.failure_searched;
    if (integer(*f, "failures") == 0) ++s.failure_false_alarms;
  }
  const double before = number(*f, "coverage_before"), after = number(*f, "coverage_after");
  if (std::isfinite(before) && std::isfinite(after)) {
    *sum_before += before;
    *sum_after += after;
    ++*with_coverage;
  }
}

}  // namespace cmt::report

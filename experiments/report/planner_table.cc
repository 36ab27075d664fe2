// The report's "Planned strategies" section (report_table.h planner_table; docs/planner.md "In the main
// job"): one row per `cmt plan --json` object given to `cmt report --plan`.
#include <sstream>

#include "experiments/report/report_table.h"

namespace cmt::report {
namespace {

using nlohmann::json;

std::string names(const json& list) {
  if (!list.is_array()) return "";
  std::string out;
  for (const json& n : list)
    out += (out.empty() ? "" : ", ") + (n.is_string() ? n.get<std::string>() : n.dump());
  return out;
}

// "planned_1 to (0, 0, -1.958), depth 0.07, may stop in f2; ..."
std::string motions_text(const json& run) {
  const json& motions = json_member(run, "motions");
  const json& steps = json_member(run, "steps");
  if (!motions.is_array()) return "";
  std::ostringstream out;
  out.precision(4);
  for (std::size_t i = 0; i < motions.size(); ++i) {
    if (i > 0) out << "; ";
    out << json_member(motions[i], "name").get<std::string>() << " to (";
    const json& c = json_member(motions[i], "commanded");
    for (std::size_t k = 0; k < c.size(); ++k) out << (k ? ", " : "") << c[k].get<double>();
    out << "), depth " << json_number(motions[i], "depth");
    if (steps.is_array() && i < steps.size())
      out << ", from " << names(json_member(steps[i], "state")) << ", may stop in "
          << names(json_member(steps[i], "targets"));
  }
  return out.str();
}

std::string verified_text(const json& run) {
  const json& v = json_member(run, "verified");
  if (!v.is_object()) return "not verified";
  if (json_member(v, "reliable").get<bool>()) return "reliable";
  return "NOT reliable: " + json_member(v, "failure").get<std::string>();
}

std::string check_text(const json& run) {
  const json& c = json_member(run, "check");
  if (!c.is_object()) return "not run";
  std::ostringstream out;
  out << json_member(c, "successes").get<int>() << " / " << json_member(c, "rollouts").get<int>()
      << " reached the goal, " << json_member(c, "outside").get<int>()
      << " ends outside the prediction (seed " << json_member(c, "seed").get<long long>() << ")";
  return out.str();
}

}  // namespace

Table planner_table(const std::vector<json>& runs) {
  Table t;
  t.headers = {"task",    "termination", "found",    "strategy",
               "motions", "verifier",    "rollouts", "planning time (s)"};
  for (const json& run : runs) {
    const bool found = json_member(run, "found").get<bool>();
    std::ostringstream seconds;
    seconds.precision(3);
    seconds << json_number(run, "seconds");
    t.rows.push_back({text_cell(json_member(run, "task").get<std::string>()),
                      text_cell(json_member(run, "termination").get<std::string>()),
                      text_cell(found ? "yes" : "no: " + json_member(run, "reason").get<std::string>()),
                      text_cell(names(json_member(run, "strategy"))), text_cell(motions_text(run)),
                      text_cell(found ? verified_text(run) : ""), text_cell(check_text(run)),
                      text_cell(seconds.str())});
  }
  return t;
}

namespace {

std::string trials_text(const json& trials) {
  std::ostringstream out;
  out.precision(3);
  const json& points = json_member(trials, "points");
  out << json_member(trials, "successes").get<int>() << " / " << json_member(trials, "rollouts").get<int>()
      << " at " << (points.is_array() ? points.size() : 0) << " points";
  return out.str();
}

std::string grown_text(const json& grown) {
  std::ostringstream out;
  out.precision(3);
  if (!grown.is_array()) return "";
  for (const json& g : grown) {
    if (out.tellp() > 0) out << "; ";
    out << json_number(g, "factor") << " eps_p: " << 100 * json_number(g, "rate") << " % (" << trials_text(g)
        << ")";
  }
  return out.str();
}

}  // namespace

Table extremes_table(const std::vector<json>& runs) {
  Table t;
  t.headers = {"task", "motion", "claims", "at the vertices: reached the goal", "outside, grown by"};
  for (const json& run : runs) {
    const json& e = json_member(run, "extremes");
    if (!e.is_object()) continue;
    for (const json& m : json_member(e, "motions")) {
      t.rows.push_back({text_cell(json_member(run, "task").get<std::string>()),
                        text_cell(json_member(m, "motion").get<std::string>()),
                        text_cell(json_flag(m, "claims_cell") ? "a cell" : "one commanded position"),
                        text_cell(trials_text(json_member(m, "vertices"))),
                        text_cell(grown_text(json_member(m, "grown")))});
    }
  }
  return t;
}

}  // namespace cmt::report

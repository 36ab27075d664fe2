// The report's "Error detection and recovery" section (report_table.h edr_table; docs/edr.md): one row per
// `cmt edr --json` object given to `cmt report --edr`.
#include <sstream>

#include "experiments/report/report_table.h"

namespace cmt::report {
namespace {

using nlohmann::json;

double number(const json& j, const char* key) { return json_number(j, key); }
bool flag(const json& j, const char* key) { return json_flag(j, key); }

// "alpha=-1: no goal, H 2.53; alpha=0.5: goal 0.63, H 0": per slice its parameters, the goal's termination
// area (or "no goal") and H's.
std::string slices_text(const json& slices) {
  if (!slices.is_array()) return "";
  std::ostringstream out;
  out.precision(3);
  for (const json& s : slices) {
    if (out.tellp() > 0) out << "; ";
    const json& params = json_member(s, "params");
    std::string p;
    if (params.is_object())
      for (const auto& [name, value] : params.items()) {
        std::ostringstream v;
        v.precision(4);
        v << (value.is_number() ? value.get<double>() : 0.0);
        p += (p.empty() ? "" : ",") + name + "=" + v.str();
      }
    out << (p.empty() ? "nominal" : p) << ": ";
    if (!flag(s, "terminates")) {
      out << "may not terminate";
      continue;
    }
    if (flag(s, "goal_empty"))
      out << "no goal";
    else
      out << "goal " << number(s, "success_area");
    out << ", H " << number(s, "failure_area");
  }
  return out.str();
}

// "1000 rollouts in 50 worlds: success 480, failure signalled 520, false success 0, false failure 0, missed
// success 0, time-out 0".
std::string check_text(const json& check) {
  if (!check.is_object()) return "not run";
  const json& o = json_member(check, "outcomes");
  const json& worlds = json_member(check, "worlds");
  std::ostringstream out;
  out << number(check, "rollouts") << " rollouts in " << (worlds.is_array() ? worlds.size() : 0)
      << " worlds: success " << number(o, "success") << ", failure signalled "
      << number(o, "failure_signalled") << ", false success " << number(o, "false_success")
      << ", false failure " << number(o, "false_failure") << ", missed success "
      << number(o, "missed_success") << ", time-out " << number(o, "timeout");
  return out.str();
}

}  // namespace

Table edr_table(const std::vector<nlohmann::json>& runs) {
  Table t;
  t.headers = {"task",
               "strategy",
               "EDR-reliable",
               "why not",
               "slices: goal termination area, H area",
               "confusable pairs",
               "physics check (worlds drawn over the parameters)",
               "seconds"};
  for (const json& j : runs) {
    const json& task = json_member(j, "task");
    const json& strategy = json_member(j, "strategy");
    const json& reason = json_member(j, "reason");
    std::ostringstream s;
    s.precision(3);
    s << number(j, "seconds");
    t.rows.push_back({text_cell(task.is_string() ? task.get<std::string>() : "?"),
                      text_cell(strategy.is_string() ? strategy.get<std::string>() : "?"),
                      text_cell(flag(j, "edr_reliable") ? "yes" : "no"),
                      text_cell(reason.is_string() ? reason.get<std::string>() : ""),
                      text_cell(slices_text(json_member(j, "slices"))),
                      text_cell(std::to_string(static_cast<int>(number(j, "confusion_count")))),
                      text_cell(check_text(json_member(j, "check"))), text_cell(s.str())});
  }
  return t;
}

}  // namespace cmt::report

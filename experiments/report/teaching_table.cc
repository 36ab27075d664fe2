// The report's "Teaching sessions" section (report_table.h teaching_table; docs/teaching.md "In the main
// job"): one row per `cmt teach --json` or `cmt backproject --json` object given to `cmt report --teach`.
#include <sstream>
#include <tuple>

#include "experiments/report/report_table.h"

namespace cmt::report {
namespace {

using nlohmann::json;

const json& member(const json& j, const char* key) { return json_member(j, key); }

double number(const json& j, const char* key) { return json_number(j, key); }

std::string names(const json& list);

// A strategy's sensing test in a few words: "position in 2 boxes", "force in 1 cone".
std::string test_text(const json& when) {
  std::string out;
  for (const auto& [key, one, many] :
       {std::tuple{"position", " box", " boxes"}, std::tuple{"force", " cone", " cones"}}) {
    const json& sets = member(when, key);
    if (!sets.is_array()) continue;
    out += (out.empty() ? "" : " and ") + std::string(key) + " in " + std::to_string(sets.size()) +
           (sets.size() == 1 ? one : many);
  }
  return out.empty() ? "?" : out;
}

// A branch item of a strategy list (docs/task-format.md "Conditional strategies"): "branch [position in 1
// box: (right); else: ()]".
std::string branch_text(const json& branches) {
  if (!branches.is_array()) return "branch ?";
  std::string out;
  for (const json& b : branches) {
    out += out.empty() ? "" : "; ";
    out += member(b, "else").is_array() ? "else: " + names(member(b, "else"))
                                        : test_text(member(b, "when")) + ": " + names(member(b, "then"));
  }
  return "branch [" + out + "]";
}

// A strategy list: motion names, and a branch item in words.
std::string names(const json& list) {
  if (!list.is_array()) return "none";
  std::string out;
  for (const json& n : list) {
    out += out.empty() ? "" : ", ";
    if (n.is_string())
      out += n.get<std::string>();
    else if (n.is_object() && n.contains("branch"))
      out += branch_text(n["branch"]);
    else
      out += n.dump();
  }
  return "(" + out + ")";
}

// The steps' texts joined by "; " (numbers to 4 digits).
template <class StepText>
std::string steps_joined(const json& steps, StepText step_text) {
  if (!steps.is_array()) return "";
  std::ostringstream out;
  out.precision(4);
  for (const json& s : steps) {
    if (out.tellp() > 0) out << "; ";
    const json& motion = member(s, "motion");
    out << (motion.is_string() ? motion.get<std::string>() : "?");
    step_text(s, out);
  }
  return out.str();
}

// "p1 (p1): solved 0, left 2 (termination of motion 'p1' is not inside the goal); p2 (p2, p1): solved 2, left
// 0".
std::string steps_text(const json& steps) {
  return steps_joined(steps, [](const json& s, std::ostringstream& out) {
    out << " " << names(member(s, "chain")) << ": solved " << number(s, "solved_measure") << ", left "
        << number(s, "remaining_measure");
    if (member(s, "failure").is_string()) out << " (" << member(s, "failure").get<std::string>() << ")";
  });
}

std::string check_text(const json& check) {
  if (!check.is_object()) return "not run";
  std::ostringstream out;
  out << member(check, "successes").get<int>() << " / " << member(check, "rollouts").get<int>()
      << " reached the goal, " << member(check, "failures").get<int>() << " failed, "
      << member(check, "outside").get<int>() << " ends outside the prediction, "
      << member(check, "unstable").get<int>() << " unstable";
  return out.str();
}

// "v2: strong backprojection area 123.2 (stops outside the target: area 0); ...": a `cmt backproject --json`
// object's steps.
std::string backprojection_text(const json& steps) {
  return steps_joined(steps, [](const json& s, std::ostringstream& out) {
    out << ": strong backprojection area " << number(s, "strong_area") << " (stops outside the target: area "
        << number(s, "base_area") << ")";
  });
}

// A `cmt backproject --json` object (docs/teaching.md "Backprojections") rather than a teaching session.
bool is_backprojection(const json& j) { return member(j, "start_inside").is_boolean(); }

}  // namespace

Table teaching_table(const std::vector<TeachingRun>& runs) {
  Table t;
  t.headers = {"task",
               "session",
               "solved",
               "taught strategy",
               "steps (chain: measure solved, left; why)",
               "pre-image check",
               "seconds"};
  for (const TeachingRun& r : runs) {
    const json& j = r.result;
    const json& task = member(j, "task");
    std::ostringstream s;
    s.precision(3);
    s << number(j, "seconds");
    Cell session = text_cell(r.label);
    if (!r.view_link.empty()) session.push_back({"3-D view", r.view_link, false, ""});
    if (is_backprojection(j)) {
      t.rows.push_back(
          {text_cell(task.is_string() ? task.get<std::string>() : "?"), session,
           text_cell(member(j, "start_inside").get<bool>() ? "yes (start in S)" : "no (start not in S)"),
           text_cell(names(member(j, "motions"))), text_cell(backprojection_text(member(j, "steps"))),
           text_cell(check_text(member(j, "check"))), text_cell(s.str())});
      continue;
    }
    t.rows.push_back(
        {text_cell(task.is_string() ? task.get<std::string>() : "?"), session,
         text_cell(member(j, "solved").is_boolean() && member(j, "solved").get<bool>() ? "yes" : "no"),
         text_cell(member(j, "strategy").is_array() ? names(member(j, "strategy")) : "none"),
         text_cell(steps_text(member(j, "steps"))), text_cell(check_text(member(j, "check"))),
         text_cell(s.str())});
  }
  return t;
}

}  // namespace cmt::report

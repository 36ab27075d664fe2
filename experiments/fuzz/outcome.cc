#include "experiments/fuzz/outcome.h"

#include <cstring>
#include <nlohmann/json.hpp>

namespace cmt::fuzz {

namespace {

// The stdout check of a run that exited 0, 1 or 2.
void check_json(const ChildResult& result, Outcome& outcome) {
  nlohmann::json answer;
  try {
    answer = nlohmann::json::parse(result.out);
  } catch (const nlohmann::json::exception& e) {
    outcome.failure = true;
    outcome.kind = "bad-json";
    outcome.detail = result.out.empty() ? "empty stdout" : e.what();
    return;
  }
  if (!answer.is_object()) {
    outcome.failure = true;
    outcome.kind = "bad-json";
    outcome.detail = std::string("stdout is a JSON ") + answer.type_name() + ", not an object";
    return;
  }
  if (result.exit_code == 2) {
    const auto error = answer.find("error");
    if (error == answer.end() || !error->is_object() || !error->contains("message") ||
        !(*error)["message"].is_string()) {
      outcome.failure = true;
      outcome.kind = "no-error-message";
      outcome.detail = "exit 2 without error.message";
    }
    return;
  }
  const auto timed_out = answer.find("timed_out");
  outcome.timed_out = timed_out != answer.end() && timed_out->is_boolean() && timed_out->get<bool>();
}

void replace_all(std::string& text, const std::string& from, const std::string& to) {
  if (from.empty()) return;
  for (size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
    text.replace(at, from.size(), to);
  }
}

}  // namespace

Outcome check_outcome(const ChildResult& result) {
  Outcome outcome;
  if (result.killed_on_time) {
    outcome = {true, false, "hard time-out", "hang", "killed after the hard time limit"};
  } else if (!result.exited) {
    outcome.failure = true;
    outcome.status = "signal " + std::to_string(result.signal);
    outcome.kind = "signal";
    outcome.detail = strsignal(result.signal);
  } else if (result.exit_code < 0 || result.exit_code > 2) {
    outcome.failure = true;
    outcome.status = "exit " + std::to_string(result.exit_code);
    outcome.kind = "exit-status";
    outcome.detail = "exit status " + std::to_string(result.exit_code);
  } else {
    outcome.status = std::to_string(result.exit_code);
    check_json(result, outcome);
  }
  return outcome;
}

bool same_failure(const Outcome& original, const Outcome& candidate) {
  return candidate.failure && candidate.kind == original.kind && candidate.status == original.status;
}

std::string failure_class(const Outcome& outcome, const std::string& err, const std::string& input_path) {
  std::string last;
  size_t end = err.size();
  while (end > 0) {
    const size_t start = err.rfind('\n', end - 1);
    const size_t from = start == std::string::npos ? 0 : start + 1;
    last = err.substr(from, end - from);
    if (last.find_first_not_of(" \t\r") != std::string::npos) break;
    last.clear();
    if (start == std::string::npos) break;
    end = start;
  }
  std::string signature =
      outcome.kind + ": " + (outcome.kind == "bad-json" ? "" : outcome.detail) + " | " + last;
  replace_all(signature, input_path, "<file>");
  for (char& c : signature) {
    if (c >= '0' && c <= '9') c = '#';
  }
  if (signature.size() > 160) signature.resize(160);
  return signature;
}

std::string tail_lines(const std::string& text, size_t lines) {
  size_t start = text.size();
  if (start > 0 && text[start - 1] == '\n') --start;  // the final newline ends the last line
  for (size_t n = 0; n < lines; ++n) {
    if (start == 0) return text;
    const size_t newline = text.rfind('\n', start - 1);
    if (newline == std::string::npos) return text;
    start = newline;
  }
  return text.substr(start + 1);
}

}  // namespace cmt::fuzz

#include "models/yaml_document.h"

#include <yaml-cpp/depthguard.h>

#include <cctype>
#include <sstream>
#include <utility>
#include <vector>

#include "models/task_error.h"

namespace cmt {

namespace {

bool is_key_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// A block key on one row: indentation, any number of "- " list markers, a plain name, then a colon that ends
// the token (followed by a blank or the end of the row). Returns the key's column, or npos.
std::size_t block_key(const std::string& row, std::string* key) {
  std::size_t i = 0;
  while (i < row.size() && row[i] == ' ') ++i;
  while (i + 1 < row.size() && row[i] == '-' && row[i + 1] == ' ') {
    ++i;
    while (i < row.size() && row[i] == ' ') ++i;
  }
  const std::size_t begin = i;
  while (i < row.size() && is_key_char(row[i])) ++i;
  if (i == begin) return std::string::npos;
  const std::size_t end = i;
  while (i < row.size() && row[i] == ' ') ++i;
  if (i >= row.size() || row[i] != ':') return std::string::npos;
  if (i + 1 < row.size() && !std::isspace(static_cast<unsigned char>(row[i + 1]))) return std::string::npos;
  *key = row.substr(begin, end - begin);
  return begin;
}

}  // namespace

std::string enclosing_key_path(const std::string& text, int line) {
  std::vector<std::pair<std::size_t, std::string>> stack;  // (column of the key, key)
  std::istringstream in(text);
  std::string row, key;
  for (int n = 1; n <= line && std::getline(in, row); ++n) {
    const std::size_t column = block_key(row, &key);
    if (column == std::string::npos) continue;
    while (!stack.empty() && stack.back().first >= column) stack.pop_back();
    stack.emplace_back(column, key);
  }
  std::string path;
  for (const auto& entry : stack) path += (path.empty() ? "" : ".") + entry.second;
  return path;
}

namespace {

// A line that is neither blank, a comment, a directive nor a document marker, and not the null literal.
bool has_content(const std::string& text) {
  std::istringstream in(text);
  std::string row;
  while (std::getline(in, row)) {
    if (!row.empty() && row.back() == '\r') row.pop_back();
    const std::size_t first = row.find_first_not_of(" \t");
    if (first == std::string::npos || row[first] == '#' || row[0] == '%') continue;
    const std::string rest = row.substr(first);
    if (rest == "---" || rest == "..." || rest == "~" || rest == "null" || rest == "Null" || rest == "NULL")
      continue;
    return true;
  }
  return false;
}

}  // namespace

int second_document_line(const std::string& text) {
  const auto marker = [](const std::string& row, const char* m) {
    return row.compare(0, 3, m) == 0 && (row.size() == 3 || row[3] == ' ' || row[3] == '\t');
  };
  bool started = false, ended = false;  // the first document has begun / has been closed by "..."
  std::istringstream in(text);
  std::string row;
  for (int n = 1; std::getline(in, row); ++n) {
    if (!row.empty() && row.back() == '\r') row.pop_back();
    if (marker(row, "---")) {
      if (started) return n;
      started = true;
      continue;
    }
    if (marker(row, "...")) {
      ended = true;
      continue;
    }
    const std::size_t first = row.find_first_not_of(" \t");
    const bool content = first != std::string::npos && row[first] != '#' && !(first == 0 && row[0] == '%');
    if (!content) continue;
    if (ended) return n;
    started = true;
  }
  return 0;
}

YAML::Node load_yaml_document(const std::string& text, const std::string& file_label) {
  // The second document is found in the text: yaml-cpp's LoadAll never returns on some malformed input (a
  // stray ',' before the first key), where Load, which reads the first document only, stops.
  if (const int line = second_document_line(text); line > 0)
    throw TaskError(file_label, "",
                    "the file holds more than one YAML document (the second starts at line " +
                        std::to_string(line) + "); a task or spec file is exactly one",
                    TextLocation{line, 1});
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::DeepRecursion& e) {
    const TextLocation where{e.mark.line + 1, e.mark.column + 1};
    throw TaskError(file_label, enclosing_key_path(text, where.line),
                    "malformed YAML: nested too deeply (the YAML reader stops at depth " +
                        std::to_string(e.depth()) + ")",
                    where);
  } catch (const YAML::ParserException& e) {
    const TextLocation where{e.mark.line + 1, e.mark.column + 1};
    throw TaskError(file_label, enclosing_key_path(text, where.line), "malformed YAML: " + e.msg, where);
  }
  // yaml-cpp reads some malformed text (a stray ',' before the first key) as no document at all.
  if (root.IsNull() && text.find_first_not_of(" \t\r\n") != std::string::npos && has_content(text))
    throw TaskError(file_label, "", "malformed YAML: no value could be read from the text");
  return root;
}

}  // namespace cmt

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

YAML::Node load_yaml_document(const std::string& text, const std::string& file_label) {
  std::vector<YAML::Node> documents;
  try {
    documents = YAML::LoadAll(text);
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
  if (documents.size() > 1)
    throw TaskError(file_label, "",
                    "the file holds " + std::to_string(documents.size()) +
                        " YAML documents (separated by ---); a task or spec file is exactly one");
  return documents.empty() ? YAML::Node() : documents.front();
}

}  // namespace cmt

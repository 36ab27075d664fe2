#include "experiments/cli/cli_output.h"

#include <fstream>
#include <iostream>
#include <sstream>

#include "experiments/common/json_text.h"

namespace cmt {

void print_json(const nlohmann::json& object) { std::cout << json_text(object, 2) << std::endl; }

int report_bad_input(const std::string& message, bool json, const std::string& file, const std::string& key,
                     const std::string& reason, TextLocation where) {
  std::cerr << "cmt: error: " << message << std::endl;
  if (json) {
    nlohmann::json error = {{"message", message}};
    if (!file.empty()) error["file"] = file;
    if (!key.empty()) error["key"] = key;
    if (!reason.empty()) error["reason"] = reason;
    if (where.line > 0) {
      error["line"] = where.line;
      error["column"] = where.column;
    }
    print_json({{"error", error}, {"exit_status", kExitBadInput}});
  }
  return kExitBadInput;
}

std::string read_task_text(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot open the file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace cmt

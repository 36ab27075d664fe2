// The error every bad-input path raises: it names the file, the key (a YAML key path, a command-line option
// or a database table) and the reason; the cmt program turns it into exit status 2. A YAML syntax error also
// carries where in the text it is (1-based line and column). Task files raise TaskError
// (models/task_error.h), sweep specs, results databases and command-line options raise InputError itself.
#pragma once

#include <stdexcept>
#include <string>

namespace cmt {

struct TextLocation {
  int line = 0;  // 1-based; 0 = no location
  int column = 0;
  std::string text() const { return "line " + std::to_string(line) + ", column " + std::to_string(column); }
};

class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::string key, std::string reason, TextLocation where = {})
      : std::runtime_error(file + ": " + (where.line > 0 ? where.text() + ": " : std::string()) +
                           (key.empty() ? std::string("(top level)") : key) + ": " + reason),
        file_(std::move(file)),
        key_(std::move(key)),
        reason_(std::move(reason)),
        where_(where) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }
  const TextLocation& where() const { return where_; }

 private:
  std::string file_, key_, reason_;
  TextLocation where_;
};

}  // namespace cmt

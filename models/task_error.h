// The error every bad-input path raises: it names the file, the YAML key path and the reason
// (DEVELOPERS.md "Robust"); the cmt program turns it into exit status 2.
#pragma once

#include <stdexcept>
#include <string>

namespace cmt {

class TaskError : public std::runtime_error {
 public:
  TaskError(std::string file, std::string key, std::string reason)
      : std::runtime_error(file + ": " + (key.empty() ? std::string("(top level)") : key) + ": " + reason),
        file_(std::move(file)),
        key_(std::move(key)),
        reason_(std::move(reason)) {}
  const std::string& file() const { return file_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_, key_, reason_;
};

}  // namespace cmt

// Strict reading of YAML input files (task files, sweep specs): a YAML node together with its key path, so
// that every message names the file, the key and the reason (TaskError, exit status 2). Header-only, used by
// models/task_loader.cc and experiments/sweep/spec/sweep_spec.cc; needs yaml-cpp.
#pragma once

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <set>
#include <string>
#include <vector>

#include "models/task_error.h"

namespace cmt {

class YamlNode {
 public:
  YamlNode(YAML::Node node, std::string path, const std::string* file)
      : node_(node), path_(std::move(path)), file_(file) {}

  [[noreturn]] void fail(const std::string& reason) const { throw TaskError(*file_, path_, reason); }
  const std::string& path() const { return path_; }
  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  const YAML::Node& raw() const { return node_; }
  std::string child_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

  // A mapping whose keys are all allowed and none duplicated (the message lists the allowed keys sorted).
  void require_map(const std::vector<std::string>& allowed) const {
    if (!node_.IsMap()) fail("expected a mapping");
    std::set<std::string> seen;
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar()) fail("keys must be plain names");
      const std::string key = kv.first.as<std::string>();
      if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
        std::string list;
        for (const auto& a : std::set<std::string>(allowed.begin(), allowed.end()))
          list += (list.empty() ? "" : ", ") + a;
        YamlNode(kv.second, child_path(key), file_).fail("unknown key (allowed here: " + list + ")");
      }
      if (!seen.insert(key).second) YamlNode(kv.second, child_path(key), file_).fail("duplicated key");
    }
  }
  // The same with a set of allowed keys (a template, so that a braced list picks the overload above).
  template <class Set>
  requires std::same_as<Set, std::set<std::string>>
  void require_map(const Set& allowed) const {
    require_map(std::vector<std::string>(allowed.begin(), allowed.end()));
  }
  // The keys of a mapping in file order (yaml-cpp keeps it).
  std::vector<std::string> keys() const {
    if (!node_.IsMap()) fail("expected a mapping");
    std::vector<std::string> out;
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar()) fail("keys must be plain names");
      const std::string key = kv.first.as<std::string>();
      if (std::find(out.begin(), out.end(), key) != out.end())
        YamlNode(kv.second, child_path(key), file_).fail("duplicated key");
      out.push_back(key);
    }
    return out;
  }
  bool has(const std::string& key) const {
    return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
  }
  YamlNode at(const std::string& key) const {
    if (!has(key)) YamlNode(YAML::Node(), child_path(key), file_).fail("missing required key");
    return YamlNode(node_[key], child_path(key), file_);
  }
  YamlNode item(std::size_t i) const {
    return YamlNode(node_[i], path_ + "[" + std::to_string(i) + "]", file_);
  }
  std::size_t size() const { return node_.size(); }

  YamlNode sequence() const {
    if (!node_.IsSequence()) fail("expected a list");
    return *this;
  }
  // A non-empty list.
  YamlNode list() const {
    if (sequence().size() == 0) fail("the list is empty");
    return *this;
  }
  double number() const {
    if (!node_.IsScalar()) fail("expected a number");
    double v = 0;
    try {
      v = node_.as<double>();
    } catch (const YAML::Exception&) {
      fail("expected a number, got '" + node_.Scalar() + "'");
    }
    if (!std::isfinite(v)) fail("expected a finite number");
    return v;
  }
  long long integer(long long lo, long long hi) const {
    if (!node_.IsScalar()) fail("expected an integer");
    long long v = 0;
    try {
      v = node_.as<long long>();
    } catch (const YAML::Exception&) {
      fail("expected an integer, got '" + node_.Scalar() + "'");
    }
    if (v < lo || v > hi)
      fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
    return v;
  }
  std::string string() const {
    if (!node_.IsScalar()) fail("expected a string");
    return node_.as<std::string>();
  }
  std::vector<double> numbers() const {
    const YamlNode l = list();
    std::vector<double> v;
    for (std::size_t i = 0; i < l.size(); ++i) v.push_back(l.item(i).number());
    return v;
  }

 private:
  YAML::Node node_;
  std::string path_;
  const std::string* file_;
};

}  // namespace cmt

// A plain YAML document tree that the fuzzer can mutate freely (duplicate keys, raw bytes, opaque raw text)
// and write back as YAML: the top-level map in block style, everything below it in flow style.
#pragma once

#include <string>
#include <vector>

namespace cmt::fuzz {

struct YamlValue {
  enum class Kind { kScalar, kSequence, kMap, kRaw };
  Kind kind = Kind::kScalar;
  std::string text;              // scalar text, or YAML text written verbatim (kRaw)
  bool quoted = false;           // scalar written in double quotes (a string, never a number)
  std::vector<YamlValue> keys;   // map keys (scalars), parallel to items
  std::vector<YamlValue> items;  // sequence items, or map values

  static YamlValue scalar(std::string text, bool quoted = false);
  static YamlValue raw(std::string text);
  static YamlValue sequence(std::vector<YamlValue> items = {});
  static YamlValue map();
  void add(YamlValue key, YamlValue value);
};

// Parses the first document of text. Throws (yaml-cpp exceptions) when it is not valid YAML.
YamlValue parse_yaml(const std::string& text);

// The value in flow style: [a, b], {k: v}, plain or double-quoted scalars.
std::string to_flow(const YamlValue& value);

// The whole document: a top-level map one key per line, anything else as one flow line.
std::string to_document(const YamlValue& root);

// True when the scalar text reads as a YAML number (integer or float, including .inf and .nan forms).
bool is_number(const YamlValue& value);

// The deepest bracket / brace nesting in text, a cheap guard before parsing untrusted input.
int bracket_depth(const std::string& text);

}  // namespace cmt::fuzz

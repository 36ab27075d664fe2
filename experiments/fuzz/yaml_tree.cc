#include "experiments/fuzz/yaml_tree.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <regex>

namespace cmt::fuzz {

YamlValue YamlValue::scalar(std::string text, bool quoted) {
  YamlValue v;
  v.text = std::move(text);
  v.quoted = quoted;
  return v;
}

YamlValue YamlValue::raw(std::string text) {
  YamlValue v;
  v.kind = Kind::kRaw;
  v.text = std::move(text);
  return v;
}

YamlValue YamlValue::sequence(std::vector<YamlValue> items) {
  YamlValue v;
  v.kind = Kind::kSequence;
  v.items = std::move(items);
  return v;
}

YamlValue YamlValue::map() {
  YamlValue v;
  v.kind = Kind::kMap;
  return v;
}

void YamlValue::add(YamlValue key, YamlValue value) {
  keys.push_back(std::move(key));
  items.push_back(std::move(value));
}

namespace {

// Plain scalars keep a conservative alphabet; anything else is written double-quoted so that re-emitting a
// seed does not change its meaning.
bool safe_plain(const std::string& s) {
  if (s.empty() || s.front() == ' ' || s.back() == ' ' || (s.front() == '-' && s.size() > 1 && s[1] == ' ')) {
    return false;
  }
  for (unsigned char c : s) {
    if (!(std::isalnum(c) || c == '_' || c == '.' || c == '+' || c == '-' || c == '/' || c == ' ' ||
          c >= 0x80)) {
      return false;
    }
  }
  return true;
}

YamlValue from_node(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Sequence: {
      YamlValue v = YamlValue::sequence();
      for (const auto& item : node) v.items.push_back(from_node(item));
      return v;
    }
    case YAML::NodeType::Map: {
      YamlValue v = YamlValue::map();
      for (const auto& entry : node) v.add(from_node(entry.first), from_node(entry.second));
      return v;
    }
    case YAML::NodeType::Scalar: {
      const bool was_quoted = node.Tag() == "!";
      return YamlValue::scalar(node.Scalar(), was_quoted || !safe_plain(node.Scalar()));
    }
    default:
      return YamlValue::scalar("null");
  }
}

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c == '\n') {
      out += "\\n";
    } else if (c < 0x20) {
      static const char* kHex = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += static_cast<char>(c);  // bytes >= 0x80 stay raw: invalid UTF-8 reaches the parser as is
    }
  }
  return out + "\"";
}

std::string scalar_text(const YamlValue& v) {
  if (v.quoted || v.text.empty()) return quote(v.text);
  return v.text;
}

}  // namespace

YamlValue parse_yaml(const std::string& text) { return from_node(YAML::Load(text)); }

std::string to_flow(const YamlValue& value) {
  switch (value.kind) {
    case YamlValue::Kind::kScalar:
      return scalar_text(value);
    case YamlValue::Kind::kRaw:
      return value.text;
    case YamlValue::Kind::kSequence: {
      std::string out = "[";
      for (size_t i = 0; i < value.items.size(); ++i) {
        if (i > 0) out += ", ";
        out += to_flow(value.items[i]);
      }
      return out + "]";
    }
    case YamlValue::Kind::kMap: {
      std::string out = "{";
      for (size_t i = 0; i < value.items.size(); ++i) {
        if (i > 0) out += ", ";
        out += to_flow(value.keys[i]) + ": " + to_flow(value.items[i]);
      }
      return out + "}";
    }
  }
  return "";
}

std::string to_document(const YamlValue& root) {
  if (root.kind != YamlValue::Kind::kMap || root.items.empty()) return to_flow(root) + "\n";
  std::string out;
  for (size_t i = 0; i < root.items.size(); ++i) {
    out += to_flow(root.keys[i]) + ": " + to_flow(root.items[i]) + "\n";
  }
  return out;
}

bool is_number(const YamlValue& value) {
  if (value.kind != YamlValue::Kind::kScalar || value.quoted) return false;
  static const std::regex kNumber(
      R"([-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?|[-+]?\.(inf|Inf|INF)|\.(nan|NaN|NAN)|0x[0-9a-fA-F]+|0o[0-7]+)");
  return std::regex_match(value.text, kNumber);
}

int bracket_depth(const std::string& text) {
  int depth = 0;
  int deepest = 0;
  for (char c : text) {
    if (c == '[' || c == '{') deepest = std::max(deepest, ++depth);
    if ((c == ']' || c == '}') && depth > 0) --depth;
  }
  return deepest;
}

}  // namespace cmt::fuzz

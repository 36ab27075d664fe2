#include "experiments/fuzz/mutator.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>

namespace cmt::fuzz {

namespace {

using Rng = std::mt19937_64;

size_t below(Rng& rng, size_t n) { return n == 0 ? 0 : std::uniform_int_distribution<size_t>(0, n - 1)(rng); }
bool coin(Rng& rng, double p = 0.5) { return std::uniform_real_distribution<double>(0, 1)(rng) < p; }

template <class T>
const T& one_of(Rng& rng, const std::vector<T>& options) {
  return options[below(rng, options.size())];
}

std::string format_number(double x) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  std::string s = buffer;
  if (s == "inf") return ".inf";
  if (s == "-inf") return "-.inf";
  if (s == "nan" || s == "-nan") return ".nan";
  return s;
}

// A node of the tree with what the mutations need to know about its place.
struct NodeRef {
  YamlValue* node;
  YamlValue* parent;  // nullptr for the root
  size_t index;       // position in parent->items
  std::string key;    // the nearest enclosing map key (angles are recognized by it)
  size_t end;         // one past the last DFS index of the node's subtree
};

void collect(YamlValue& v, YamlValue* parent, size_t index, const std::string& key,
             std::vector<NodeRef>& out) {
  const size_t self = out.size();
  out.push_back({&v, parent, index, key, 0});
  for (size_t i = 0; i < v.items.size(); ++i) {
    const bool is_map = v.kind == YamlValue::Kind::kMap;
    collect(v.items[i], &v, i, is_map ? v.keys[i].text : key, out);
  }
  out[self].end = out.size();
}

std::vector<NodeRef> nodes_where(YamlValue& root, const std::function<bool(const NodeRef&)>& keep) {
  std::vector<NodeRef> all;
  collect(root, nullptr, 0, "", all);
  std::vector<NodeRef> kept;
  for (const auto& ref : all) {
    if (keep(ref)) kept.push_back(ref);
  }
  return kept;
}

bool is_map(const YamlValue& v) { return v.kind == YamlValue::Kind::kMap; }
bool is_sequence(const YamlValue& v) { return v.kind == YamlValue::Kind::kSequence; }

// A point or direction: a sequence of 2 or 3 numbers.
bool is_vector(const YamlValue& v) {
  return is_sequence(v) && (v.items.size() == 2 || v.items.size() == 3) &&
         std::all_of(v.items.begin(), v.items.end(), [](const YamlValue& x) { return is_number(x); });
}

double number_of(const YamlValue& v) {
  const std::string& t = v.text;
  if (t.find("inf") != std::string::npos || t.find("Inf") != std::string::npos)
    return t[0] == '-' ? -HUGE_VAL : HUGE_VAL;
  return std::strtod(t.c_str(), nullptr);
}

bool is_angle_key(const std::string& key) { return key.rfind("theta", 0) == 0 || key == "angle"; }

const std::vector<std::string> kExtremeNumbers = {"0",
                                                  "-0",
                                                  "0.0",
                                                  "-0.0",
                                                  "1e-320",
                                                  "5e-324",
                                                  "-5e-324",
                                                  "1e308",
                                                  "-1e308",
                                                  "1.7976931348623157e308",
                                                  "1e309",
                                                  "-1e309",
                                                  "1e200",
                                                  "-1e200",
                                                  "1e-12",
                                                  "-1e-12",
                                                  "1e-300",
                                                  "9223372036854775807",
                                                  "9223372036854775808",
                                                  "-9223372036854775809",
                                                  "18446744073709551616",
                                                  "123456789012345678901234567890",
                                                  "2147483648",
                                                  "-2147483649",
                                                  "nan",
                                                  ".nan",
                                                  ".NaN",
                                                  ".inf",
                                                  "-.inf",
                                                  "+.inf",
                                                  "inf",
                                                  "0x10",
                                                  "0o17",
                                                  "1_000",
                                                  "+1",
                                                  "1.",
                                                  ".5",
                                                  "1e",
                                                  "1e-400",
                                                  "-",
                                                  "."};
const std::vector<std::string> kAngleNumbers = {"1.5707963267948966",
                                                "1.5707963267948963",
                                                "1.5707963267948968",
                                                "1.5707963",
                                                "1.5707964",
                                                "3.141592653589793",
                                                "3.1415926535897936",
                                                "6.283185307179586",
                                                "-1e-300",
                                                "1e-300",
                                                "-0.0",
                                                "1.57079632679"};
const std::vector<std::string> kInvalidUtf8 = {"\xbc",
                                               "\x80",
                                               "\xff",
                                               "\xfe",
                                               "\xc3",
                                               "\xc0\xaf",
                                               "\xed\xa0\x80",
                                               "\xf4\x90\x80\x80",
                                               "\xe2\x82",
                                               "\xf0\x9f\x98",
                                               std::string("\0", 1),
                                               "\xef\xbb\xbf"};
const std::vector<std::string> kIndicators = {":", "-",  "[", "]", "{", "}", ",", "&",  "*",  "!",  "|", ">",
                                              "'", "\"", "#", "%", "@", "`", "?", "\t", "\r", "\n", "~", " "};

// --- structure-level mutations: each returns false when the tree offers nothing to apply it to ---

bool delete_key(YamlValue& root, Rng& rng) {
  auto maps = nodes_where(root, [](const NodeRef& r) { return is_map(*r.node) && !r.node->items.empty(); });
  if (maps.empty()) return false;
  YamlValue& m = *one_of(rng, maps).node;
  const size_t i = below(rng, m.items.size());
  m.keys.erase(m.keys.begin() + i);
  m.items.erase(m.items.begin() + i);
  return true;
}

bool duplicate_key(YamlValue& root, Rng& rng) {
  auto maps = nodes_where(root, [](const NodeRef& r) { return is_map(*r.node) && !r.node->items.empty(); });
  if (maps.empty()) return false;
  YamlValue& m = *one_of(rng, maps).node;
  const size_t i = below(rng, m.items.size());
  YamlValue key = m.keys[i];
  YamlValue value = coin(rng) ? m.items[i] : m.items[below(rng, m.items.size())];
  const size_t at = coin(rng) ? i + 1 : m.items.size();
  m.keys.insert(m.keys.begin() + at, key);
  m.items.insert(m.items.begin() + at, value);
  return true;
}

bool swap_keys(YamlValue& root, Rng& rng) {
  auto maps =
      nodes_where(root, [](const NodeRef& r) { return is_map(*r.node) && r.node->items.size() >= 2; });
  if (maps.empty()) return false;
  YamlValue& m = *one_of(rng, maps).node;
  const size_t i = below(rng, m.items.size());
  size_t j = below(rng, m.items.size() - 1);
  if (j >= i) ++j;
  if (coin(rng))
    std::swap(m.keys[i], m.keys[j]);  // the values trade keys
  else {
    std::swap(m.keys[i], m.keys[j]);  // the entries trade places
    std::swap(m.items[i], m.items[j]);
  }
  return true;
}

bool change_type(YamlValue& root, Rng& rng) {
  auto refs = nodes_where(root, [](const NodeRef& r) { return r.parent != nullptr; });
  if (refs.empty()) return false;
  YamlValue& v = *one_of(rng, refs).node;
  YamlValue old = v;
  switch (below(rng, 9)) {
    case 0:
      v = YamlValue::scalar(old.kind == YamlValue::Kind::kScalar ? old.text : to_flow(old), true);
      break;
    case 1:
      v = YamlValue::scalar(one_of(rng, std::vector<std::string>{"1", "-2.5", "0", "1e300"}));
      break;
    case 2:
      v = YamlValue::sequence({old});
      break;
    case 3:
      v = YamlValue::map();
      v.add(YamlValue::scalar(coin(rng) ? "box" : "x"), old);
      break;
    case 4:
      v = YamlValue::sequence();
      break;
    case 5:
      v = YamlValue::map();
      break;
    case 6:
      v = YamlValue::scalar(one_of(rng, std::vector<std::string>{"null", "~", "true", "no", "yes"}));
      break;
    case 7:
      v = YamlValue::scalar("");
      break;
    default:  // a vector loses or gains a coordinate
      if (!is_sequence(old)) return false;
      if (coin(rng) && !v.items.empty())
        v.items.pop_back();
      else
        v.items.push_back(YamlValue::scalar("1"));
  }
  return true;
}

bool extreme_number(YamlValue& root, Rng& rng) {
  auto numbers = nodes_where(root, [](const NodeRef& r) { return is_number(*r.node); });
  if (numbers.empty()) return false;
  const NodeRef& ref = one_of(rng, numbers);
  const bool angle = is_angle_key(ref.key) && coin(rng, 0.6);
  *ref.node = YamlValue::scalar(one_of(rng, angle ? kAngleNumbers : kExtremeNumbers));
  return true;
}

bool scale_number(YamlValue& root, Rng& rng) {
  auto numbers = nodes_where(root, [](const NodeRef& r) { return is_number(*r.node); });
  if (numbers.empty()) return false;
  static const std::vector<double> kFactors = {1e-300, 1e-12, 1e-6, 1e-3, 0.5, -1, 2, 1e3, 1e6, 1e12, 1e300};
  const double factor = one_of(rng, kFactors);
  const bool whole_vector = coin(rng);  // scale every number of one vector: the same shape, another size
  const NodeRef& ref = one_of(rng, numbers);
  if (whole_vector && ref.parent && is_vector(*ref.parent)) {
    for (auto& x : ref.parent->items) x = YamlValue::scalar(format_number(number_of(x) * factor));
  } else {
    *ref.node = YamlValue::scalar(format_number(number_of(*ref.node) * factor));
  }
  return true;
}

// Makes a box degenerate: zero size on one or all axes, a sliver, or min and max exchanged.
bool degenerate_box(YamlValue& root, Rng& rng) {
  auto boxes = nodes_where(root, [](const NodeRef& r) {
    if (!is_map(*r.node)) return false;
    int found = 0;
    for (const auto& k : r.node->keys) found += (k.text == "min" || k.text == "max");
    return found == 2;
  });
  if (boxes.empty()) return false;
  YamlValue& box = *one_of(rng, boxes).node;
  YamlValue* lo = nullptr;
  YamlValue* hi = nullptr;
  for (size_t i = 0; i < box.keys.size(); ++i) {
    if (box.keys[i].text == "min") lo = &box.items[i];
    if (box.keys[i].text == "max") hi = &box.items[i];
  }
  if (!is_vector(*lo) || !is_vector(*hi) || lo->items.size() != hi->items.size()) return false;
  const size_t axis = below(rng, lo->items.size());
  switch (below(rng, 4)) {
    case 0:
      hi->items[axis] = lo->items[axis];
      break;
    case 1:
      *hi = *lo;
      break;
    case 2: {
      static const std::vector<double> kThin = {1e-320, 5e-324, 1e-300, 1e-15, 1e-9};
      hi->items[axis] = YamlValue::scalar(format_number(number_of(lo->items[axis]) + one_of(rng, kThin)));
      break;
    }
    default:
      std::swap(lo->items[axis], hi->items[axis]);
  }
  return true;
}

// Moves a coordinate slightly, or makes points coincident or collinear.
bool perturb_geometry(YamlValue& root, Rng& rng) {
  if (coin(rng, 0.3) && degenerate_box(root, rng)) return true;
  auto vectors = nodes_where(root, [](const NodeRef& r) { return is_vector(*r.node); });
  if (vectors.empty()) return false;
  const NodeRef& ref = one_of(rng, vectors);
  YamlValue& v = *ref.node;
  switch (below(rng, 3)) {
    case 0: {  // a tiny relative move of one coordinate
      static const std::vector<double> kEps = {1e-15, 1e-12, 1e-9, 1e-6, 1e-300};
      YamlValue& x = v.items[below(rng, v.items.size())];
      const double value = number_of(x);
      const double scale = value == 0 ? 1 : std::fabs(value);
      x = YamlValue::scalar(format_number(value + (coin(rng) ? 1 : -1) * scale * one_of(rng, kEps)));
      return true;
    }
    case 1: {  // coincident with another vector of the same size
      std::vector<YamlValue*> same;
      for (const auto& other : vectors) {
        if (other.node != &v && other.node->items.size() == v.items.size()) same.push_back(other.node);
      }
      if (same.empty()) return false;
      v = *one_of(rng, same);
      return true;
    }
    default: {  // collinear: a point of a point list moved onto the line through two others
      if (!ref.parent || !is_sequence(*ref.parent) || ref.parent->items.size() < 3) return false;
      const auto& list = ref.parent->items;
      const YamlValue& a = list[(ref.index + 1) % list.size()];
      const YamlValue& b = list[(ref.index + 2) % list.size()];
      if (!is_vector(a) || !is_vector(b) || a.items.size() != v.items.size() ||
          b.items.size() != v.items.size()) {
        return false;
      }
      static const std::vector<double> kT = {0.5, 2, -1, 1e-9, 1 + 1e-12};
      const double t = one_of(rng, kT);
      for (size_t i = 0; i < v.items.size(); ++i) {
        const double p = number_of(a.items[i]) + t * (number_of(b.items[i]) - number_of(a.items[i]));
        v.items[i] = YamlValue::scalar(format_number(p));
      }
      return true;
    }
  }
}

bool duplicate_items(YamlValue& root, Rng& rng) {
  auto lists =
      nodes_where(root, [](const NodeRef& r) { return is_sequence(*r.node) && !r.node->items.empty(); });
  if (lists.empty()) return false;
  YamlValue& list = *one_of(rng, lists).node;
  static const std::vector<size_t> kCopies = {1, 2, 5, 20, 100, 300};
  const size_t i = below(rng, list.items.size());
  const YamlValue item = list.items[i];
  list.items.insert(list.items.begin() + i + 1, one_of(rng, kCopies), item);
  return true;
}

bool nest_deeply(YamlValue& root, Rng& rng) {
  auto refs = nodes_where(root, [](const NodeRef& r) { return r.parent != nullptr; });
  if (refs.empty()) return false;
  YamlValue& v = *one_of(rng, refs).node;
  static const std::vector<size_t> kDepths = {8, 64, 500, 1200, 1999, 2500, 20000};
  const size_t depth = one_of(rng, kDepths);
  const bool maps = coin(rng, 0.3);
  std::string open;
  std::string close;
  for (size_t i = 0; i < depth; ++i) {
    open += maps ? "{a: " : "[";
    close += maps ? "}" : "]";
  }
  v = YamlValue::raw(open + to_flow(v) + close);
  return true;
}

bool invalid_utf8(YamlValue& root, Rng& rng) {
  std::vector<YamlValue*> scalars;
  std::function<void(YamlValue&)> walk = [&](YamlValue& v) {
    if (v.kind == YamlValue::Kind::kScalar) scalars.push_back(&v);
    for (auto& k : v.keys) scalars.push_back(&k);
    for (auto& item : v.items) walk(item);
  };
  walk(root);
  if (scalars.empty()) return false;
  YamlValue& s = *one_of(rng, scalars);
  s.text.insert(below(rng, s.text.size() + 1), one_of(rng, kInvalidUtf8));
  if (coin(rng)) s.quoted = true;
  return true;
}

// An anchor on one value and an alias to it elsewhere, or an exponential alias chain ("billion laughs").
bool anchor_alias(YamlValue& root, Rng& rng) {
  auto refs = nodes_where(root, [](const NodeRef& r) { return r.parent != nullptr; });
  if (refs.size() < 2) return false;
  if (coin(rng, 0.3)) {
    std::string bomb = "[&l0 [1, 2, 3]";
    for (int level = 1; level < 10; ++level) {
      bomb += ", &l" + std::to_string(level) + " [";
      for (int k = 0; k < 9; ++k) bomb += std::string(k ? ", *l" : "*l") + std::to_string(level - 1);
      bomb += "]";
    }
    *one_of(rng, refs).node = YamlValue::raw(bomb + "]");
    return true;
  }
  const size_t j = 1 + below(rng, refs.size() - 1);
  std::vector<size_t> before;
  for (size_t i = 0; i < j; ++i) {
    if (refs[i].end <= j) before.push_back(i);  // not an ancestor of j
  }
  if (before.empty()) return false;
  const size_t i = one_of(rng, before);
  *refs[j].node = YamlValue::raw("*fz");
  *refs[i].node = YamlValue::raw("&fz " + to_flow(*refs[i].node));
  return true;
}

// --- text-level mutations ---

void truncate_text(std::string& text, Rng& rng) { text.resize(below(rng, text.size() + 1)); }

void random_bytes(std::string& text, Rng& rng) {
  const size_t pieces = 1 + below(rng, 8);
  for (size_t p = 0; p < pieces; ++p) {
    std::string piece;
    switch (below(rng, 3)) {
      case 0:
        piece = one_of(rng, kInvalidUtf8);
        break;
      case 1:
        piece = std::string(1, static_cast<char>(below(rng, 256)));
        break;
      default:
        piece = one_of(rng, kIndicators);
    }
    text.insert(below(rng, text.size() + 1), piece);
  }
}

void second_document(std::string& text, Rng& rng) {
  switch (below(rng, 5)) {
    case 0:
      text += "---\n" + text;
      break;
    case 1:
      text += "---\nname: other\n";
      break;
    case 2:
      text += "...\n---\n[1, 2\n";
      break;
    case 3:
      text = "%YAML 1.2\n---\n" + text + "---\n";
      break;
    default:
      text += "--- " + one_of(rng, kInvalidUtf8) + "\n";
  }
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line + "\n");
  return lines;
}

std::string join(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l;
  return out;
}

void byte_edit(std::string& text, Rng& rng) {
  if (text.empty()) {
    text = one_of(rng, kIndicators);
    return;
  }
  const size_t at = below(rng, text.size());
  const size_t span = std::min(text.size() - at, 1 + below(rng, 32));
  auto lines = split_lines(text);
  switch (below(rng, 7)) {
    case 0:
      text[at] = static_cast<char>(text[at] ^ (1 << below(rng, 8)));
      break;
    case 1:
      text.erase(at, span);
      break;
    case 2:
      text.insert(at, text.substr(at, span));
      break;
    case 3:
      text[at] = one_of(rng, kIndicators)[0];
      break;
    case 4: {  // a line repeated: a duplicate key at text level
      const size_t i = below(rng, lines.size());
      lines.insert(lines.begin() + i, lines[i]);
      text = join(lines);
      break;
    }
    case 5: {
      std::swap(lines[below(rng, lines.size())], lines[below(rng, lines.size())]);
      text = join(lines);
      break;
    }
    default: {  // indentation changed
      std::string& line = lines[below(rng, lines.size())];
      if (coin(rng))
        line.insert(0, coin(rng) ? "  " : "\t");
      else if (!line.empty() && line[0] == ' ')
        line.erase(0, 1);
      text = join(lines);
    }
  }
}

using TreeMutation = bool (*)(YamlValue&, Rng&);
using TextMutation = void (*)(std::string&, Rng&);

struct MutationKind {
  const char* name;
  double weight;
  TreeMutation tree;  // exactly one of tree / text
  TextMutation text;
};

const std::vector<MutationKind>& kinds() {
  static const std::vector<MutationKind> kKinds = {
      {"delete_key", 1, delete_key, nullptr},
      {"duplicate_key", 1, duplicate_key, nullptr},
      {"swap_keys", 1, swap_keys, nullptr},
      {"change_type", 1.5, change_type, nullptr},
      {"extreme_number", 3, extreme_number, nullptr},
      {"scale_number", 1, scale_number, nullptr},
      {"perturb_geometry", 2.5, perturb_geometry, nullptr},
      {"duplicate_items", 0.6, duplicate_items, nullptr},
      {"nest_deeply", 0.3, nest_deeply, nullptr},
      {"invalid_utf8", 0.6, invalid_utf8, nullptr},
      {"anchor_alias", 0.3, anchor_alias, nullptr},
      {"truncate", 0.5, nullptr, truncate_text},
      {"random_bytes", 0.7, nullptr, random_bytes},
      {"second_document", 0.4, nullptr, second_document},
      {"byte_edit", 1, nullptr, byte_edit},
  };
  return kKinds;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

SeedTask load_seed(const std::string& path) {
  SeedTask seed;
  seed.path = path;
  seed.text = read_file(path);
  try {
    seed.tree = parse_yaml(seed.text);
  } catch (const std::exception& e) {
    throw std::runtime_error("seed " + path + " is not valid YAML: " + e.what());
  }
  seed.strategies = strategy_names(seed.tree);
  return seed;
}

std::mt19937_64 input_rng(uint64_t seed, uint64_t index) {
  std::seed_seq sequence{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32),
                         static_cast<uint32_t>(index), static_cast<uint32_t>(index >> 32), 0x636d74u};
  return std::mt19937_64(sequence);
}

std::vector<std::string> strategy_names(const YamlValue& root) {
  std::vector<std::string> names;
  if (!is_map(root)) return names;
  for (size_t i = 0; i < root.keys.size(); ++i) {
    if (root.keys[i].text != "strategies" || !is_map(root.items[i])) continue;
    for (const auto& key : root.items[i].keys) {
      if (key.kind == YamlValue::Kind::kScalar && !key.text.empty()) names.push_back(key.text);
    }
  }
  return names;
}

std::string strategy_in_text(const std::string& text) {
  if (bracket_depth(text) > 200) return "";
  try {
    auto names = strategy_names(parse_yaml(text));
    return names.empty() ? "" : names.front();
  } catch (const std::exception&) {
    return "";
  }
}

const std::vector<std::string>& mutation_names() {
  static const std::vector<std::string> kNames = [] {
    std::vector<std::string> names;
    for (const auto& k : kinds()) names.push_back(k.name);
    return names;
  }();
  return kNames;
}

Mutant make_mutant(const std::vector<SeedTask>& seeds, uint64_t seed, uint64_t index,
                   const std::vector<std::string>& allowed, size_t max_mutations) {
  for (const std::string& name : allowed)
    if (std::find(mutation_names().begin(), mutation_names().end(), name) == mutation_names().end())
      throw std::invalid_argument("unknown mutation '" + name + "'");
  Rng rng = input_rng(seed, index);
  Mutant mutant;
  mutant.seed_index = below(rng, seeds.size());
  const SeedTask& base = seeds[mutant.seed_index];

  std::vector<double> weights;
  for (const auto& k : kinds())
    weights.push_back(allowed.empty() || std::find(allowed.begin(), allowed.end(), k.name) != allowed.end()
                          ? k.weight
                          : 0.0);
  std::discrete_distribution<size_t> pick(weights.begin(), weights.end());
  std::vector<size_t> chosen(1 + below(rng, std::max<size_t>(1, max_mutations)));
  for (auto& c : chosen) c = pick(rng);
  // Tree mutations first (on the parsed seed), then text mutations on the written document.
  std::stable_sort(chosen.begin(), chosen.end(), [](size_t a, size_t b) {
    return kinds()[a].tree != nullptr && kinds()[b].tree == nullptr;
  });

  YamlValue tree = base.tree;
  bool tree_changed = false;
  std::string text;
  bool text_started = false;
  for (size_t c : chosen) {
    const MutationKind& kind = kinds()[c];
    if (kind.tree) {
      if (kind.tree(tree, rng)) {
        tree_changed = true;
        mutant.mutations.push_back(kind.name);
      }
      continue;
    }
    if (!text_started) {
      text = tree_changed ? to_document(tree) : base.text;  // untouched seeds keep their comments and layout
      text_started = true;
    }
    kind.text(text, rng);
    mutant.mutations.push_back(kind.name);
  }
  mutant.text = text_started ? text : to_document(tree);

  auto names = strategy_names(tree);
  if (names.empty()) names = base.strategies;
  mutant.strategy = names.empty() ? "s" : one_of(rng, names);
  return mutant;
}

}  // namespace cmt::fuzz

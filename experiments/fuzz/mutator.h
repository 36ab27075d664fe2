// Structure-aware mutation of task files: YAML-level changes to a parsed seed task (keys, types, extreme and
// degenerate numbers, repetition, nesting, aliases, invalid UTF-8) followed by text-level damage (truncation,
// random bytes, extra documents, byte edits). Input i of a run depends only on (seed, i), never on job order.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "experiments/fuzz/yaml_tree.h"

namespace cmt::fuzz {

struct SeedTask {
  std::string path;
  std::string text;
  YamlValue tree;
  std::vector<std::string> strategies;  // strategy names of the seed, for `cmt verify --strategy`
};

// Reads and parses a seed task file. Throws std::runtime_error when it cannot be read or parsed.
SeedTask load_seed(const std::string& path);

struct Mutant {
  std::string text;                    // the mutated task file
  std::vector<std::string> mutations;  // names of the mutations applied, in order
  std::string strategy;                // a strategy name for `cmt verify`: from the mutant if it has one
  size_t seed_index = 0;
};

// The generator of input `index` of a run with seed `seed`.
std::mt19937_64 input_rng(uint64_t seed, uint64_t index);

// Input `index` of the run: a random seed task with 1 to max_mutations mutations, drawn from `allowed`
// (mutation names; empty: all of them). Throws std::invalid_argument for a name that is not a mutation.
Mutant make_mutant(const std::vector<SeedTask>& seeds, uint64_t seed, uint64_t index,
                   const std::vector<std::string>& allowed = {}, size_t max_mutations = 4);

// The names under the top-level `strategies` key(s) of a parsed task.
std::vector<std::string> strategy_names(const YamlValue& root);

// A strategy name read from a task file's text, or "" when there is none (or the text does not parse).
std::string strategy_in_text(const std::string& text);

// Every mutation name, structure-level first (docs/fuzzing.md lists them).
const std::vector<std::string>& mutation_names();

}  // namespace cmt::fuzz

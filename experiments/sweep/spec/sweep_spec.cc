#include "experiments/sweep/spec/sweep_spec.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "controllers/random.h"
#include "experiments/common/json_text.h"
#include "models/input_error.h"
#include "models/task_loader.h"
#include "models/yaml_document.h"
#include "models/yaml_node.h"

namespace cmt {

namespace {

using SpecNode = YamlNode;  // models/yaml_node.h: the task loader's error style (file, key path, reason)

std::string value_text(const ParamValue& p) { return json_text(p.json()); }

class SpecParser {
 public:
  SpecParser(std::string label, std::filesystem::path base_dir)
      : file_(std::move(label)), base_dir_(std::move(base_dir)) {}

  SweepSpec parse(const std::string& text) {
    const YAML::Node root_node = load_yaml_document(text, file_);
    const SpecNode root(root_node, "", &file_);
    if (!root_node.IsDefined() || root_node.IsNull()) root.fail("the file is empty");
    root.require_map({"description", "n", "seeds", "mode", "controller", "sticking_trials",
                      "counterexample_budget", "verify_budget_seconds", "falsify", "tasks"});
    SweepSpec spec;
    spec.path = file_;
    spec.text = text;
    if (root.has("description")) spec.description = root.at("description").string();
    spec.n = static_cast<int>(root.at("n").integer(1, kMaxSweepRollouts));
    spec_n_ = spec.n;
    const SpecNode seeds = root.at("seeds").list();
    for (std::size_t i = 0; i < seeds.size(); ++i) {
      const auto seed = static_cast<std::uint64_t>(seeds.item(i).integer(0, kMaxSweepSeed));
      if (std::find(spec.seeds.begin(), spec.seeds.end(), seed) != spec.seeds.end())
        seeds.item(i).fail("duplicated seed " + std::to_string(seed));
      spec.seeds.push_back(seed);
    }
    if (root.has("mode")) {
      const auto mode = parse_sample_mode(root.at("mode").string());
      if (!mode) root.at("mode").fail("must be uniform or extreme, got '" + root.at("mode").string() + "'");
      spec.mode = *mode;
    }
    if (root.has("controller")) {
      const auto form = parse_controller_form(root.at("controller").string());
      if (!form)
        root.at("controller")
            .fail("must be impedance, admittance or position, got '" + root.at("controller").string() + "'");
      spec.controller = *form;
    }
    controller_ = spec.controller;
    if (root.has("sticking_trials"))
      spec.sticking_trials = static_cast<int>(root.at("sticking_trials").integer(0, kMaxSweepStickingTrials));
    if (root.has("counterexample_budget"))
      spec.counterexample_budget =
          static_cast<int>(root.at("counterexample_budget").integer(0, kMaxSweepCounterexampleBudget));
    if (root.has("verify_budget_seconds")) {
      const SpecNode budget = root.at("verify_budget_seconds");
      spec.verify_budget_seconds = budget.number();
      if (spec.verify_budget_seconds <= 0 || spec.verify_budget_seconds > kMaxSweepVerifyBudgetSeconds)
        budget.fail(
            "must be > 0 and <= " + std::to_string(static_cast<long long>(kMaxSweepVerifyBudgetSeconds)) +
            " seconds (leave it out for no limit), got " + budget.raw().Scalar());
    }
    if (root.has("falsify")) spec.falsify = parse_falsify(root.at("falsify"));
    spec_falsify_ = spec.falsify;
    const SpecNode tasks = root.at("tasks").list();
    for (std::size_t i = 0; i < tasks.size(); ++i) spec.tasks.push_back(parse_task(tasks.item(i)));
    return spec;
  }

 private:
  SweepTaskEntry parse_task(const SpecNode& n) const {
    n.require_map({"file", "strategies", "n", "falsify", "grid", "random"});
    SweepTaskEntry entry;
    entry.n = n.has("n") ? static_cast<int>(n.at("n").integer(1, kMaxSweepRollouts)) : spec_n_;
    entry.falsify = n.has("falsify") ? parse_falsify(n.at("falsify")) : spec_falsify_;
    entry.spec_key = n.path();
    const SpecNode file = n.at("file");
    entry.file = (base_dir_ / file.string()).lexically_normal();
    std::ifstream in(entry.file);
    if (!in) file.fail("cannot open the task file '" + entry.file.string() + "'");
    std::stringstream buffer;
    buffer << in.rdbuf();
    entry.base_yaml = buffer.str();
    try {
      entry.base = parse_task_string(entry.base_yaml, entry.file.string());
    } catch (const InputError& e) {
      file.fail("the task file is invalid: " + std::string(e.what()));
    }
    const SpecNode strategies = n.at("strategies").list();
    for (std::size_t i = 0; i < strategies.size(); ++i) {
      const std::string name = strategies.item(i).string();
      if (entry.base.find_strategy(name) == nullptr)
        strategies.item(i).fail("unknown strategy '" + name +
                                "' (the task has: " + entry.base.strategy_names() + ")");
      if (std::find(entry.strategies.begin(), entry.strategies.end(), name) != entry.strategies.end())
        strategies.item(i).fail("duplicated strategy '" + name + "'");
      // Caught here rather than by the unit that would run it, hours into the sweep.
      if (controller_ == ControllerForm::kPosition)
        for (const std::string& motion : entry.base.find_strategy(name)->motions)
          if (entry.base.find_motion(motion)->kind == Motion::Kind::kDamper)
            strategies.item(i).fail(
                "controller: position implements generalized springs only (Buckley "
                "eq. 3.25); strategy '" +
                name + "' has the damper motion '" + motion + "'");
      entry.strategies.push_back(name);
    }

    std::vector<ParamSet> grid = {ParamSet{}};
    std::set<std::string> grid_keys;
    if (n.has("grid")) grid = parse_grid(n.at("grid"), entry, grid_keys);
    std::vector<ParamSet> draws = {ParamSet{}};
    if (n.has("random")) draws = parse_random(n.at("random"), entry, grid_keys);
    for (const ParamSet& g : grid)
      for (const ParamSet& d : draws) {
        ParamSet set = g;
        set.insert(set.end(), d.begin(), d.end());
        entry.param_sets.push_back(std::move(set));
      }
    return entry;
  }

  // `falsify: {budget: N, coverage_budget: M[, gap_budget: G][, failure_budget: F]}`: the first two
  // required, G and F 0 when missing.
  static SweepFalsify parse_falsify(const SpecNode& n) {
    n.require_map({"budget", "coverage_budget", "gap_budget", "failure_budget"});
    SweepFalsify f;
    f.budget = static_cast<int>(n.at("budget").integer(0, kMaxSweepFalsifyBudget));
    f.coverage_budget = static_cast<int>(n.at("coverage_budget").integer(0, kMaxSweepFalsifyBudget));
    if (n.has("gap_budget"))
      f.gap_budget = static_cast<int>(n.at("gap_budget").integer(0, kMaxSweepFalsifyBudget));
    if (n.has("failure_budget"))
      f.failure_budget = static_cast<int>(n.at("failure_budget").integer(0, kMaxSweepFalsifyBudget));
    return f;
  }

  // One parameter key of a grid or of random.ranges: friction, an uncertainty key, or motions (a mapping of
  // motion names). Calls `each(target, node)` for every parameter.
  template <class F>
  void for_each_param(const SpecNode& n, const SweepTaskEntry& entry, F each) const {
    std::vector<std::string> allowed = {"friction"};
    for (const std::string& k : uncertainty_override_keys()) allowed.push_back(k);
    allowed.push_back("motions");
    n.require_map(allowed);
    for (const std::string& key : n.keys()) {
      const SpecNode value = n.at(key);
      if (key == "motions") {
        for (const std::string& motion : value.keys()) {
          if (entry.base.find_motion(motion) == nullptr) {
            std::string known;
            for (const Motion& m : entry.base.motions) known += (known.empty() ? "" : ", ") + m.name;
            value.at(motion).fail("the task has no motion '" + motion + "' (it has: " + known + ")");
          }
          each(ParamTarget{ParamTarget::Kind::kMotion, motion}, value.at(motion));
        }
      } else if (key == "friction") {
        each(ParamTarget{ParamTarget::Kind::kFriction, ""}, value);
      } else {
        each(ParamTarget{ParamTarget::Kind::kUncertainty, key}, value);
      }
    }
  }

  std::vector<ParamSet> parse_grid(const SpecNode& n, const SweepTaskEntry& entry,
                                   std::set<std::string>& keys) const {
    std::vector<ParamSet> sets = {ParamSet{}};
    for_each_param(n, entry, [&](const ParamTarget& target, const SpecNode& values_node) {
      keys.insert(target.param_key());
      const SpecNode values = values_node.list();
      std::vector<ParamValue> column;
      for (std::size_t i = 0; i < values.size(); ++i) {
        const SpecNode v = values.item(i);
        ParamValue p{target,
                     target.kind == ParamTarget::Kind::kMotion ? v.numbers() : std::vector{v.number()},
                     v.path()};
        check_value(entry, p, p.spec_key);
        column.push_back(std::move(p));
      }
      // Cartesian product, the first grid key outermost.
      std::vector<ParamSet> next;
      for (const ParamSet& s : sets)
        for (const ParamValue& p : column) {
          ParamSet t = s;
          t.push_back(p);
          next.push_back(std::move(t));
        }
      sets = std::move(next);
    });
    return sets;
  }

  struct Range {
    ParamTarget target;
    std::vector<double> lo, hi;
    std::string spec_key;
  };

  std::vector<ParamSet> parse_random(const SpecNode& n, const SweepTaskEntry& entry,
                                     const std::set<std::string>& grid_keys) const {
    n.require_map({"count", "seed", "ranges"});
    const int count = static_cast<int>(n.at("count").integer(1, kMaxSweepRandomDraws));
    const auto seed = static_cast<std::uint64_t>(n.at("seed").integer(0, kMaxSweepSeed));
    std::vector<Range> ranges;
    for_each_param(n.at("ranges"), entry, [&](const ParamTarget& target, const SpecNode& r) {
      if (grid_keys.count(target.param_key()))
        r.fail("'" + target.param_key() + "' is also in the grid; give each parameter in one of them");
      Range range{target, {}, {}, r.path()};
      if (target.kind == ParamTarget::Kind::kMotion) {
        r.require_map({"min", "max"});
        range.lo = r.at("min").numbers();
        range.hi = r.at("max").numbers();
        if (range.lo.size() != range.hi.size()) r.fail("min and max must have the same number of components");
      } else {
        range.lo = range.hi = {};
        const std::vector<double> v = r.numbers();
        if (v.size() != 2) r.fail("expected [low, high], got " + std::to_string(v.size()) + " numbers");
        range.lo = {v[0]};
        range.hi = {v[1]};
      }
      for (std::size_t k = 0; k < range.lo.size(); ++k)
        if (range.lo[k] > range.hi[k]) r.fail("the low end exceeds the high end");
      // Both ends must give a valid task (the draws lie between them).
      check_value(entry, ParamValue{target, range.lo, r.path()}, r.path());
      check_value(entry, ParamValue{target, range.hi, r.path()}, r.path());
      ranges.push_back(std::move(range));
    });
    std::vector<ParamSet> draws;
    for (int j = 0; j < count; ++j) {
      // Draw j has its own stream: adding ranges or draws never changes the earlier draws' streams.
      Rng rng = rollout_stream(seed, static_cast<std::uint64_t>(j));
      ParamSet set;
      for (const Range& r : ranges) {
        ParamValue p{r.target, {}, r.spec_key + " (draw " + std::to_string(j) + ")"};
        for (std::size_t k = 0; k < r.lo.size(); ++k)
          p.value.push_back(r.lo[k] == r.hi[k] ? r.lo[k] : uniform(rng, r.lo[k], r.hi[k]));
        set.push_back(std::move(p));
      }
      draws.push_back(std::move(set));
    }
    return draws;
  }

  // The task with this one value written in must pass the task loader's schema checks.
  void check_value(const SweepTaskEntry& entry, const ParamValue& p, const std::string& spec_key) const {
    try {
      parse_task_string(apply_overrides(entry.base_yaml, entry.base, {p}), entry.file.string());
    } catch (const InputError& e) {
      throw InputError(
          file_, spec_key,
          "the value " + value_text(p) + " makes the task invalid: " + e.key() + ": " + e.reason());
    }
  }

  std::string file_;
  std::filesystem::path base_dir_;
  ControllerForm controller_ = ControllerForm::kImpedance;
  int spec_n_ = 0;             // the spec's `n`, the default of every task entry
  SweepFalsify spec_falsify_;  // the spec's `falsify`, the default of every task entry
};

}  // namespace

SweepSpec parse_sweep_spec(const std::string& text, const std::string& label,
                           const std::filesystem::path& base_dir) {
  try {
    return SpecParser(label, base_dir).parse(text);
  } catch (const YAML::Exception& e) {
    throw InputError(label, "", std::string("malformed YAML: ") + e.what());
  }
}

SweepSpec load_sweep_spec(const std::filesystem::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string(), "", "cannot open the file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse_sweep_spec(buffer.str(), path.string(), path.parent_path());
}

}  // namespace cmt

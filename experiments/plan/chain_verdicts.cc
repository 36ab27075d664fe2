// The planner's memoized, forked chain checks (chain_verdicts.h).
#include "experiments/plan/chain_verdicts.h"

#include <chrono>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "verifier/planner/verifier_check.h"

namespace cmt {
namespace {

std::vector<double> key_of(const std::vector<Vec3>& commanded) {
  std::vector<double> key;
  for (const Vec3& p : commanded) key.insert(key.end(), {p.x(), p.y(), p.z()});
  return key;
}

}  // namespace

ChainVerdicts::ChainVerdicts(const LoadedTask& task, const VerifyOptions& options,
                             const MotionTermination& terminate, int parallel)
    : task_(task), options_(options), terminate_(terminate), parallel_(parallel) {}

planner::ChainVerdict ChainVerdicts::get(const std::vector<Vec3>& commanded) {
  const std::vector<double> key = key_of(commanded);
  const auto known = known_.find(key);
  if (known != known_.end()) return known->second;
  const auto t0 = std::chrono::steady_clock::now();
  std::optional<planner::ChainVerdict> v;
  const auto running = running_.find(key);
  if (running != running_.end()) {
    running->second->poll(true);
    v = collect(*running->second);
    running_.erase(running);
  }
  // Not announced, or its child failed: verified here, as with one process (an error is then this one's).
  if (!v) v = planner::verifier_chain(task_, commanded, options_, terminate_);
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  known_.emplace(key, *v);
  return *v;
}

void ChainVerdicts::prefetch(const std::vector<std::vector<Vec3>>& chains) {
  if (parallel_ <= 1) return;
  for (auto it = running_.begin(); it != running_.end();) {
    if (!it->second->poll(false)) {
      ++it;
      continue;
    }
    if (std::optional<planner::ChainVerdict> v = collect(*it->second))
      known_.emplace(it->first, std::move(*v));
    it = running_.erase(it);
  }
  for (const std::vector<Vec3>& chain : chains) {
    if (static_cast<int>(running_.size()) >= parallel_) break;
    const std::vector<double> key = key_of(chain);
    if (known_.count(key) || running_.count(key)) continue;
    try {
      running_.emplace(key, std::make_unique<ForkedWork>([this, chain] {
                         return verdict_text(planner::verifier_chain(task_, chain, options_, terminate_));
                       }));
    } catch (const std::runtime_error&) {  // no pipe or no fork: the chains are verified here when asked for
      parallel_ = 1;
      return;
    }
  }
}

std::optional<planner::ChainVerdict> ChainVerdicts::collect(const ForkedWork& work) {
  try {
    return verdict_from_text(work.result());
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
}

std::string verdict_text(const planner::ChainVerdict& v) {
  std::ostringstream out;
  out << (v.reliable ? 1 : 0) << "\n";
  for (const auto& ends : v.ends) {
    if (!ends) {
      out << "-\n";
      continue;
    }
    out << "+";
    for (int a : *ends) out << " " << a;
    out << "\n";
  }
  return out.str();
}

planner::ChainVerdict verdict_from_text(const std::string& text) {
  std::istringstream in(text);
  planner::ChainVerdict v;
  int reliable = 0;
  if (!(in >> reliable)) throw std::runtime_error("chain verdict: no reliability in the child's result");
  v.reliable = reliable != 0;
  std::string line;
  std::getline(in, line);  // the rest of the first line
  while (std::getline(in, line)) {
    if (line == "-") {
      v.ends.push_back(std::nullopt);
      continue;
    }
    std::istringstream atoms(line.substr(1));
    std::vector<int> ends;
    for (int a; atoms >> a;) ends.push_back(a);
    v.ends.push_back(std::move(ends));
  }
  return v;
}

}  // namespace cmt

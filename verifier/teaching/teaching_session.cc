// The teaching loop (teaching_session.h).
#include "verifier/teaching/teaching_session.h"

#include <algorithm>
#include <chrono>
#include <set>

#include "models/task_error.h"
#include "verifier/teaching/start_cells.h"

namespace cmt::teaching {
namespace {

double measure(const std::vector<StartCell>& cells) {
  double sum = 0;
  for (const StartCell& c : cells) sum += region_measure(c.region);
  return sum;
}

Strategy chain_strategy(const std::vector<std::string>& motions) {
  return Strategy::sequence("taught", motions);
}

}  // namespace

ReachedSet cells_set(const LoadedTask& task, const std::vector<StartCell>& cells) {
  ReachedSet out(task.cspace);
  for (const StartCell& c : cells) out.unite(ReachedSet::from_region(task, c.region));
  return out;
}

Session::Session(std::shared_ptr<const LoadedTask> task, TeachOptions options)
    : original_(task), task_(std::move(task)), options_(std::move(options)) {
  initial_.push_back({"", task_->task.start, {}});
  cells_[""] = task_->task.start;
}

const std::vector<StartCell>& Session::remaining() const {
  return steps_.empty() ? initial_ : steps_.back().remaining;
}

bool Session::solved() const { return remaining().empty(); }

std::optional<std::vector<std::string>> Session::strategy() const {
  return steps_.empty() ? std::nullopt : steps_.back().strategy;
}

const TeachStep& Session::propose(const std::string& motion_name) {
  if (!task_->task.find_motion(motion_name))
    throw TaskError(task_->task.source_file, "motions",
                    "no motion named '" + motion_name + "' (the task has " +
                        std::to_string(task_->task.motions.size()) + ")");
  step_added_motion_.push_back(false);
  try {
    return run_step(motion_name);
  } catch (...) {
    step_added_motion_.pop_back();
    throw;
  }
}

const TeachStep& Session::propose(Motion motion) {
  if (motion.name.empty()) motion.name = "taught_" + std::to_string(steps_.size() + 1);
  while (task_->task.find_motion(motion.name)) motion.name += "_";
  auto copy = std::make_shared<LoadedTask>(*task_);
  copy->task.motions.push_back(motion);
  const std::shared_ptr<const LoadedTask> before = task_;
  task_ = std::move(copy);
  inline_motions_.push_back(motion);
  step_added_motion_.push_back(true);
  try {
    return run_step(motion.name);
  } catch (...) {  // the teaching session stays as it was (e.g. a cell the loader's region check refuses)
    step_added_motion_.pop_back();
    inline_motions_.pop_back();
    task_ = before;
    throw;
  }
}

bool Session::undo() {
  if (steps_.empty()) return false;
  steps_.pop_back();
  const bool added = step_added_motion_.back();
  step_added_motion_.pop_back();
  if (added) {
    inline_motions_.pop_back();
    auto copy = std::make_shared<LoadedTask>(*original_);
    for (const Motion& m : inline_motions_) copy->task.motions.push_back(m);
    task_ = std::move(copy);
  }
  return true;
}

VerifyResult Session::verify_from(const Strategy& chain, const ReachedSet& start, TeachStep& step) const {
  ++step.verifications;
  return verify_strategy_from(*task_, chain, start, options_.verify);
}

const Session::FirstMotion& Session::first_motion(const std::string& motion, const StartCell& cell,
                                                  TeachStep& step) {
  auto it = first_motions_.find(cell.path);
  if (it != first_motions_.end()) return it->second;
  VerifyResult r = verify_from(chain_strategy({motion}), ReachedSet::from_region(*task_, cell.region), step);
  VerifyStep& s = r.steps.front();
  FirstMotion first{!s.may_not_terminate && s.slide_forever.empty() && !s.free_termination,
                    std::move(s.termination)};
  return first_motions_.emplace(cell.path, std::move(first)).first->second;
}

// The chain is reliable from the cell exactly when verify_strategy_from says so: a sequence is simulated
// motion by motion, each from the termination set of the one before (verify.cc), so the first motion's
// simulation is computed once per cell and each chain continues from its termination set.
bool Session::chain_reliable(const std::vector<std::string>& chain, const StartCell& cell, TeachStep& step) {
  const FirstMotion& first = first_motion(chain.front(), cell, step);
  if (!first.motion_ok) return false;
  if (chain.size() == 1) return pieces_outside_goal(*task_, first.termination).empty();
  const std::vector<std::string> rest(chain.begin() + 1, chain.end());
  return verify_from(chain_strategy(rest), first.termination, step).reliable;
}

// Verifies the chain from the closed cell; halves it while the chain is not reliable from the whole.
void Session::refine(const std::vector<std::string>& chain, const StartCell& cell, int max_depth,
                     TeachStep& step, std::vector<StartCell>& unsolved) {
  if (chain_reliable(chain, cell, step)) {
    step.solved.push_back(cell);
    step.solved.back().chain = chain;
    for (ReachedPiece& p : first_motion(chain.front(), cell, step).termination.pieces())
      step.stops_from_solved.push_back(std::move(p));
    return;
  }
  if (cell.depth() < max_depth) {
    const std::vector<Region> halves = split_region(cell.region);
    if (!halves.empty()) {
      for (std::size_t i = 0; i < halves.size(); ++i) {
        const std::string path = cell.path + (i == 0 ? "0" : "1");
        cells_[path] = halves[i];
        refine(chain, {path, halves[i], {}}, max_depth, step, unsolved);
      }
      return;
    }
  }
  unsolved.push_back(cell);
}

// [m_k] ++ C_{k-1}, [m_k] ++ C_{k-2}, ..., [m_k]: the chains step k tries, without repeats.
std::vector<std::vector<std::string>> Session::candidates(const std::string& motion_name) const {
  std::vector<std::vector<std::string>> out;
  for (std::size_t j = steps_.size() + 1; j-- > 0;) {
    std::vector<std::string> chain = {motion_name};
    if (j > 0) chain.insert(chain.end(), steps_[j - 1].chain.begin(), steps_[j - 1].chain.end());
    if (std::find(out.begin(), out.end(), chain) == out.end()) out.push_back(std::move(chain));
  }
  return out;
}

// Why the remaining cells are not solved: the chain's failure from them, and where the proposed motion may
// stop such that the earlier chain fails from there (Buckley §5.2: "the robot may stick on the way").
void Session::explain(const std::vector<std::string>& motions, TeachStep& step) {
  const Strategy chain = chain_strategy(motions);
  const Strategy rest = chain_strategy(std::vector<std::string>(motions.begin() + 1, motions.end()));
  ReachedSet termination(task_->cspace);
  const auto cached =
      step.remaining.size() == 1 ? first_motions_.find(step.remaining.front().path) : first_motions_.end();
  if (cached != first_motions_.end() && cached->second.motion_ok) {
    // One unsolved cell whose first motion was simulated: the chain's failure is the rest's from its stops.
    termination = cached->second.termination;
    if (motions.size() == 1) {
      step.failure = "termination of motion '" + motions.front() + "' is not inside the goal";
      step.blocking = pieces_outside_goal(*task_, termination);
    } else {
      step.failure = verify_from(rest, termination, step).failure;
    }
  } else {
    VerifyResult r = verify_from(chain, cells_set(*task_, step.remaining), step);
    step.failure = r.reliable ? "every remaining cell fails alone, but the verifier proves the chain from "
                                "their union (a rounding artefact at the cut points)"
                              : r.failure;
    if (r.steps.empty()) return;
    termination = std::move(r.steps.front().termination);
    if (motions.size() == 1) step.blocking = std::move(r.outside_goal);
  }
  step.stops_from_remaining = termination.pieces();
  if (motions.size() == 1) return;
  int checked = 0;
  for (const int atom : termination.atoms()) {  // faces first (atom ids: faces, edges, vertices)
    if (checked == options_.max_reason_atoms) {
      ++step.unchecked_reason_atoms;
      continue;
    }
    ++checked;
    std::vector<bool> keep(static_cast<std::size_t>(task_->cspace.atom_count()), false);
    keep[static_cast<std::size_t>(atom)] = true;
    const ReachedSet part = termination.restricted(keep);
    if (!verify_from(rest, part, step).reliable)
      for (ReachedPiece& p : part.pieces()) step.blocking.push_back(std::move(p));
  }
}

std::vector<StartCell> Session::merged(const std::vector<StartCell>& cells) const {
  std::set<std::string> paths;
  for (const StartCell& c : cells) paths.insert(c.path);
  for (bool changed = true; changed;) {
    changed = false;
    for (const std::string& p : paths) {
      if (p.empty() || p.back() != '0') continue;
      const std::string parent = p.substr(0, p.size() - 1);
      if (!paths.count(parent + "1")) continue;
      paths.erase(parent + "0");
      paths.erase(parent + "1");
      paths.insert(parent);
      changed = true;
      break;
    }
  }
  std::vector<StartCell> out;
  for (const std::string& p : paths) out.push_back({p, cells_.at(p), {}});  // lexicographic: along the start
  return out;
}

const TeachStep& Session::run_step(const std::string& motion_name) {
  const auto t0 = std::chrono::steady_clock::now();
  TeachStep step;
  step.motion = motion_name;
  first_motions_.clear();
  const std::vector<std::vector<std::string>> chains = candidates(motion_name);
  std::vector<StartCell> cells = merged(remaining());
  std::vector<double> solved_by(chains.size(), 0.0);  // measure each candidate solved, over both passes
  // First every chain on the unsolved cells as they are, then the refinement (halvings are the costly part).
  for (std::size_t pass = 0; pass < 2 * chains.size() && !cells.empty(); ++pass) {
    const std::vector<std::string>& chain = chains[pass % chains.size()];
    const bool halve = pass >= chains.size();
    std::vector<StartCell> unsolved;
    const std::size_t before = step.solved.size();
    for (const StartCell& cell : cells)
      refine(chain, cell, halve ? options_.refine_depth : cell.depth(), step, unsolved);
    for (std::size_t i = before; i < step.solved.size(); ++i)
      solved_by[pass % chains.size()] += region_measure(step.solved[i].region);
    cells = merged(unsolved);
  }
  // C_k: the candidate that solved the most (the first on ties; a point start measures 0, so any solved cell
  // counts), else [m_k] ++ C_{k-1}.
  step.chain = chains.front();
  double best = -1;
  for (std::size_t c = 0; c < chains.size(); ++c) {
    const bool solved_some = std::any_of(step.solved.begin(), step.solved.end(),
                                         [&](const StartCell& cell) { return cell.chain == chains[c]; });
    if (solved_some && solved_by[c] > best) {
      best = solved_by[c];
      step.chain = chains[c];
    }
  }
  step.remaining = std::move(cells);
  step.solved_measure = measure(step.solved);
  step.remaining_measure = measure(step.remaining);
  if (!step.remaining.empty()) explain(chains.front(), step);
  steps_.push_back(std::move(step));
  if (solved()) steps_.back().strategy = taught_strategy();
  steps_.back().seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return steps_.back();
}

// One strategy for the whole start: the chains that solved cells, if they agree; else the last of them when
// it is verified from the whole start (the task format cannot branch before the first motion).
std::optional<std::vector<std::string>> Session::taught_strategy() const {
  std::vector<std::vector<std::string>> chains;  // distinct, in the order they solved cells
  for (const TeachStep& s : steps_)
    for (const StartCell& c : s.solved)
      if (std::find(chains.begin(), chains.end(), c.chain) == chains.end()) chains.push_back(c.chain);
  if (chains.size() == 1) return chains.front();
  const ReachedSet start = ReachedSet::from_region(*task_, task_->task.start);
  TeachStep scratch;
  for (auto it = chains.rbegin(); it != chains.rend(); ++it)
    if (verify_from(chain_strategy(*it), start, scratch).reliable) return *it;
  return std::nullopt;
}

}  // namespace cmt::teaching

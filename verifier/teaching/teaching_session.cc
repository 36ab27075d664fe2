// The teaching loop (teaching_session.h).
#include "verifier/teaching/teaching_session.h"

#include <algorithm>
#include <chrono>
#include <set>

#include "models/task_error.h"
#include "models/task_loader.h"
#include "verifier/sensing_termination.h"
#include "verifier/teaching/start_cells.h"

namespace cmt::teaching {
namespace {

double measure(const std::vector<StartCell>& cells) {
  double sum = 0;
  for (const StartCell& c : cells) sum += region_measure(c.region);
  return sum;
}

// How far a dispatch test box reaches beyond eps_s around its points, relative to the scene scale: above the
// verifier's own slack for sensing boxes (kSensingBoxRelativeSlack) and the region grid's rounding (cells of
// 2^-35 scale), so that every point of the part surely passes its test (verify.cc shrinks a test box by
// eps_s and that slack before asking which points surely pass); far below any feature of a task. The verifier
// judges the test as it is either way: the margin decides how often a dispatch verifies, not its soundness.
constexpr double kDispatchBoxRelativeMargin = 1e-6;

// The sensed-position test that every point of `pieces` surely passes (Buckley Def 4.2: a reading lies within
// eps_s of the true position): each piece's bounding box grown by eps_s and the margins above. In a planar
// task the boxes span the clip slab in y, as the loader reads a planar box.
MotionTermination surely_sensed_in(const LoadedTask& task, const std::vector<ReachedPiece>& pieces) {
  MotionTermination test;
  const double grow = task.task.uncertainty.eps_s +
                      (kSensingBoxRelativeSlack + kDispatchBoxRelativeMargin) * task.cspace.scale();
  for (const ReachedPiece& piece : pieces) {
    AxisBox box{piece.polygon.front(), piece.polygon.front()};
    for (const Vec3& q : piece.polygon) {
      box.min = box.min.cwiseMin(q);
      box.max = box.max.cwiseMax(q);
    }
    box.min.array() -= grow;
    box.max.array() += grow;
    if (task.task.dimension == 2) {
      box.min.y() = -kPlanarClipHalfDepth;
      box.max.y() = kPlanarClipHalfDepth;
    }
    test.position.push_back(box);
  }
  return test;
}

bool contains_same(const std::vector<Strategy>& list, const Strategy& s) {
  return std::any_of(list.begin(), list.end(), [&](const Strategy& t) { return same_strategy(t, s); });
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

std::optional<Strategy> Session::strategy() const {
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

// The chain is reliable from the cell exactly when verify_strategy_from says so: a strategy is simulated
// motion by motion, each from the termination set of the one before (verify.cc), so the first motion's
// simulation is computed once per cell and each chain continues from its termination set. A dispatch (a test
// right after the first motion) is verified whole from the cell.
bool Session::chain_reliable(const Strategy& chain, const StartCell& cell, TeachStep& step) {
  const StrategyNode& root = chain.nodes.front();
  if (!root.branches.empty())
    return verify_from(chain, ReachedSet::from_region(*task_, cell.region), step).reliable;
  const FirstMotion& first = first_motion(root.motion, cell, step);
  if (!first.motion_ok) return false;
  if (root.next < 0) return pieces_outside_goal(*task_, first.termination).empty();
  return verify_from(subtree(chain, root.next), first.termination, step).reliable;
}

// Verifies the chain from the closed cell; halves it while the chain is not reliable from the whole.
void Session::refine(const Strategy& chain, const StartCell& cell, int max_depth, TeachStep& step,
                     std::vector<StartCell>& unsolved) {
  if (chain_reliable(chain, cell, step)) {
    step.solved.push_back(cell);
    step.solved.back().chain = chain;
    for (ReachedPiece& p : first_motion(chain.nodes.front().motion, cell, step).termination.pieces())
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
std::vector<Strategy> Session::candidates(const std::string& motion_name) const {
  std::vector<Strategy> out;
  for (std::size_t j = steps_.size() + 1; j-- > 0;) {
    Strategy chain = j > 0 ? followed_by(motion_name, steps_[j - 1].chain) : chain_strategy({motion_name});
    if (!contains_same(out, chain)) out.push_back(std::move(chain));
  }
  return out;
}

// Buckley's table of solved regions (§5.1) with recognizable containment (Defs 5.1-5.4, Alg 5.1): after m_k
// the robot senses which region it is in and runs that region's strategy. The stops of m_k from the unsolved
// cells are split into the part in the goal (the robot stops there) and, atom by atom, the rest, each given
// the first earlier strategy C_{k-1}, ..., C_1 verified reliable from it; parts that need different
// strategies become the branches of one sensing test, each part's test the boxes its points surely read in.
// Points of one part that may read as another's run the other's strategy: the verifier's conditional
// semantics (verify.cc, Buckley §4.2) decides whether that still reaches the goal, so the candidate is only
// as trusted as any chain. One candidate per part taken as the `else` (the order of tests matters when parts
// lie within 2 eps_s of each other). None when one strategy serves every part, or some part has none.
std::vector<Strategy> Session::dispatches(const std::string& motion_name, const std::vector<StartCell>& cells,
                                          TeachStep& step) {
  if (steps_.empty() || cells.empty() || options_.max_dispatch_atoms <= 0) return {};
  std::vector<Strategy> continuations(1);  // stop there (no node), then C_{k-1}, ..., C_1
  for (std::size_t j = steps_.size(); j-- > 0;)
    if (!contains_same(continuations, steps_[j].chain)) continuations.push_back(steps_[j].chain);
  const VerifyResult first = verify_from(chain_strategy({motion_name}), cells_set(*task_, cells), step);
  if (first.steps.empty()) return {};
  const VerifyStep& s = first.steps.front();
  if (s.may_not_terminate || !s.slide_forever.empty() || s.free_termination) return {};
  const ReachedSet goal = ReachedSet::from_regions(*task_, task_->task.goal, /*partial=*/true);
  const ReachedSet outside =
      ReachedSet::from_pieces(task_->cspace, pieces_outside_goal(*task_, s.termination));
  const std::vector<int> atoms = outside.atoms();
  if (static_cast<int>(atoms.size()) > options_.max_dispatch_atoms) return {};
  std::vector<std::vector<ReachedPiece>> parts(continuations.size());
  parts[0] = s.termination.intersected(goal).pieces();
  for (const int atom : atoms) {
    std::vector<bool> keep(static_cast<std::size_t>(task_->cspace.atom_count()), false);
    keep[static_cast<std::size_t>(atom)] = true;
    const ReachedSet part = outside.restricted(keep);
    std::size_t c = 1;
    while (c < continuations.size() && !verify_from(continuations[c], part, step).reliable) ++c;
    if (c == continuations.size()) return {};  // no earlier strategy reaches the goal from these stops
    for (ReachedPiece& p : part.pieces()) parts[c].push_back(std::move(p));
  }
  std::vector<std::size_t> used;
  for (std::size_t c = 0; c < parts.size(); ++c)
    if (!parts[c].empty()) used.push_back(c);
  if (used.size() < 2) return {};
  std::vector<Strategy> out;
  for (const std::size_t otherwise : used) {
    std::vector<DispatchBranch> branches;
    for (const std::size_t c : used)
      if (c != otherwise) branches.push_back({surely_sensed_in(*task_, parts[c]), continuations[c]});
    branches.push_back({{}, continuations[otherwise]});
    out.push_back(dispatch(motion_name, branches));
  }
  step.dispatches += static_cast<int>(out.size());
  return out;
}

// Why the remaining cells are not solved: the chain's failure from them, and where the proposed motion may
// stop such that the earlier chain fails from there (Buckley §5.2: "the robot may stick on the way").
void Session::explain(const Strategy& chain, TeachStep& step) {
  const std::string& motion = chain.nodes.front().motion;
  const bool alone = chain.nodes.size() == 1;
  const Strategy rest = subtree(chain, chain.nodes.front().next);
  ReachedSet termination(task_->cspace);
  const auto cached =
      step.remaining.size() == 1 ? first_motions_.find(step.remaining.front().path) : first_motions_.end();
  if (cached != first_motions_.end() && cached->second.motion_ok) {
    // One unsolved cell whose first motion was simulated: the chain's failure is the rest's from its stops.
    termination = cached->second.termination;
    if (alone) {
      step.failure = "termination of motion '" + motion + "' is not inside the goal";
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
    if (alone) step.blocking = std::move(r.outside_goal);
  }
  step.stops_from_remaining = termination.pieces();
  if (alone) return;
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

// Tries each candidate in turn on the cells (halved up to refine_depth with `halve`); adds what each solved
// to solved_by and returns the cells left unsolved.
std::vector<StartCell> Session::try_candidates(const std::vector<Strategy>& chains,
                                               std::vector<StartCell> cells, bool halve, TeachStep& step,
                                               std::vector<double>& solved_by) {
  for (std::size_t c = 0; c < chains.size() && !cells.empty(); ++c) {
    std::vector<StartCell> unsolved;
    const std::size_t before = step.solved.size();
    for (const StartCell& cell : cells)
      refine(chains[c], cell, halve ? options_.refine_depth : cell.depth(), step, unsolved);
    for (std::size_t i = before; i < step.solved.size(); ++i)
      solved_by[c] += region_measure(step.solved[i].region);
    cells = merged(unsolved);
  }
  return cells;
}

// The chains on the cells as they are, then (when cells remain) the sensed dispatches built from those, then
// every candidate again with halving (the costly part).
const TeachStep& Session::run_step(const std::string& motion_name) {
  const auto t0 = std::chrono::steady_clock::now();
  TeachStep step;
  step.motion = motion_name;
  first_motions_.clear();
  std::vector<Strategy> chains = candidates(motion_name);
  std::vector<double> solved_by(chains.size(), 0.0);  // measure each candidate solved, over both passes
  std::vector<StartCell> cells = try_candidates(chains, merged(remaining()), false, step, solved_by);
  const std::vector<Strategy> dispatched = dispatches(motion_name, cells, step);
  if (!dispatched.empty()) {
    std::vector<double> dispatch_solved(dispatched.size(), 0.0);
    cells = try_candidates(dispatched, std::move(cells), false, step, dispatch_solved);
    chains.insert(chains.end(), dispatched.begin(), dispatched.end());
    solved_by.insert(solved_by.end(), dispatch_solved.begin(), dispatch_solved.end());
  }
  cells = try_candidates(chains, std::move(cells), true, step, solved_by);
  // C_k: the candidate that solved the most (the first on ties; a point start measures 0, so any solved cell
  // counts), else [m_k] ++ C_{k-1}.
  step.chain = chains.front();
  double best = -1;
  for (std::size_t c = 0; c < chains.size(); ++c) {
    const bool solved_some = std::any_of(step.solved.begin(), step.solved.end(), [&](const StartCell& cell) {
      return same_strategy(cell.chain, chains[c]);
    });
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

// One strategy for the whole start: the strategies that solved cells, if they agree; else the last of them
// when it is verified from the whole start (the task format cannot branch before the first motion).
std::optional<Strategy> Session::taught_strategy() const {
  std::vector<Strategy> chains;  // distinct, in the order they solved cells
  for (const TeachStep& s : steps_)
    for (const StartCell& c : s.solved)
      if (!contains_same(chains, c.chain)) chains.push_back(c.chain);
  if (chains.size() == 1) return chains.front();
  const ReachedSet start = ReachedSet::from_region(*task_, task_->task.start);
  TeachStep scratch;
  for (auto it = chains.rbegin(); it != chains.rend(); ++it)
    if (verify_from(*it, start, scratch).reliable) return *it;
  return std::nullopt;
}

}  // namespace cmt::teaching

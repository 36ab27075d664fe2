// Buckley's planner search over sticking arcs (search.h, §6.5, §6.6).
#include "verifier/planner/search.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <set>

#include "verifier/sensing.h"

namespace cmt::planner {
namespace {

// Two face normals closer than this (the sine of their angle) make a flat edge: no edge seeds.
constexpr double kParallelNormals = 1e-9;
// The seed grid's points per axis, and the seeds whose cells are built per target set.
constexpr int kSeedGrid = 12;
constexpr int kSeedsPerTargetSet = 8;
// Goal distances of faces that differ by less than this times the scene's scale count as equal when the
// projection seeds are ordered (rounding of the distance computation must not decide the order).
constexpr double kSeedDistanceTie = 1e-9;

class Search {
 public:
  Search(AtomSimulation& simulation, const CSpace& cspace, const PlanRequest& request)
      : sim_(simulation),
        cspace_(cspace),
        req_(request),
        confusable_(cspace, request.eps_s, request.theta_f) {}

  PlanResult run() {
    PlanResult out;
    out.start_states = start_states();
    if (out.start_states.empty()) {
      out.reason = "the start lies on no atom";
      return out;
    }
    while (true) {
      if (all_succeed(out.start_states)) {
        extract(out);
        if (accept_chain(out)) break;
        out.found = false;
        out.steps.clear();
        out.decision_free = false;
        if (out.chains_checked >= req_.max_chain_checks) {
          out.reason = "the check limit (" + std::to_string(req_.max_chain_checks) +
                       " candidate strategies refuted by the verifier) was reached";
          break;
        }
        add_start_projection_arc(out);  // refutations do not hold the projections back
        add_chain_projection_arc(out);
        continue;  // the refuted arc changed: evaluate again
      }
      // One state expanded, one start projection arc and one continuation added per round, so the
      // projections (verifier calls) are spread over the search rather than paid for before it. A round
      // that expands the start is evaluated before any projection is paid for.
      const bool may_project = start_expanded();
      const auto next = pick();
      const bool expands = next && out.expanded < req_.max_expansions;
      if (expands) {
        expand(*next);
        ++out.expanded;
      }
      const bool projected = may_project && add_start_projection_arc(out);
      const bool chained = may_project && add_chain_projection_arc(out);
      if (!projected && !chained && !expands) {
        out.reason =
            next ? "the expansion limit (" + std::to_string(req_.max_expansions) + " states) was reached"
                 : "no strategy of at most " + std::to_string(req_.max_motions) +
                       " motions: every reachable state was expanded";
        break;
      }
    }
    out.expanded = static_cast<int>(graph_.size());
    for (const auto& [state, arcs] : graph_) out.arcs += static_cast<int>(arcs.size());
    out.confirmed = confirmed_;
    out.rejected = rejected_;
    out.widened = widened_;
    return out;
  }

 private:
  bool near_goal(int a) const {
    return a < static_cast<int>(req_.goal_near.size()) && req_.goal_near[static_cast<std::size_t>(a)];
  }
  bool goal_atom(int a) const {
    return a == sim_.goal_stop_atom() || (a < static_cast<int>(req_.goal_atom.size()) && req_.goal_atom[a]);
  }
  bool is_goal(const State& s) const {
    return std::all_of(s.begin(), s.end(), [&](int a) { return goal_atom(a); });
  }
  // Whether a motion with these targets may come to rest in free space.
  bool ends_in_free(const std::vector<int>& targets) const {
    return std::find(targets.begin(), targets.end(), sim_.free_atom()) != targets.end();
  }

  // §6.6.2: the state's arcs, one per target set met at the seeds (seeds()): the cell of the seed whose cell
  // is deepest among the first kSeedsPerTargetSet with those targets, commanded at the cell's interior point;
  // arcs that may end in free space, or whose heads are too big, are left out.
  void expand(const State& state) {
    std::map<std::vector<int>, std::vector<Vec3>> by_targets;
    for (const Vec3& p : seeds()) {
      std::vector<int> targets = sim_.targets_at(state, p);
      if (targets.empty() || ends_in_free(targets)) continue;
      auto& list = by_targets[targets];
      if (static_cast<int>(list.size()) < kSeedsPerTargetSet) list.push_back(p);
    }
    // Smallest target sets first: a set that holds the targets of an arc already built is skipped.
    std::vector<const std::pair<const std::vector<int>, std::vector<Vec3>>*> by_size;
    for (const auto& entry : by_targets) by_size.push_back(&entry);
    std::stable_sort(by_size.begin(), by_size.end(),
                     [](const auto* a, const auto* b) { return a->first.size() < b->first.size(); });
    std::vector<GraphArc> out;
    for (const auto* entry : by_size) {
      const std::vector<int>& targets = entry->first;
      if (dominated(targets, out)) continue;
      std::optional<GraphArc> arc = arc_for(state, targets, entry->second);
      if (arc && usable(*arc)) out.push_back(std::move(*arc));
    }
    // Best first: the arcs whose targets are nearest the goal are tried first.
    std::vector<std::pair<double, std::size_t>> order;
    for (std::size_t i = 0; i < out.size(); ++i) order.push_back({goal_distance(out[i].arc.targets), i});
    std::stable_sort(order.begin(), order.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<GraphArc>& arcs = graph_[state];
    for (const auto& entry : order) arcs.push_back(std::move(out[entry.second]));
  }

  const std::vector<State>& start_states() {
    if (start_states_.empty()) start_states_ = confusable_sets(confusable_, req_.start_atoms);
    return start_states_;
  }

  // The contact seeds (contact_seeds()) behind the goal's faces first, then behind the faces nearest the
  // goal; at equal distance, faces the pull from the start meets most squarely first
  // (projection_seed_order(), with PlanRequest::start_point), then by id.
  const std::vector<Vec3>& projection_seeds() {
    if (!projection_seeds_.empty()) return projection_seeds_;
    struct Entry {
      long long distance;  // in units of kSeedDistanceTie x scale: equal distances tie however computed
      double squareness;
      Vec3 seed;
    };
    const double tie = kSeedDistanceTie * cspace_.scale();
    std::vector<Entry> entries;
    for (const Face& f : cspace_.faces()) {
      const long long distance = is_goal({f.id}) ? -1 : std::llround(goal_distance({f.id}) / tie);
      const double squareness = req_.start_point ? projection_seed_order(f, *req_.start_point) : 0.0;
      for (const Vec3& p : contact_seeds(f, req_.eps_s)) entries.push_back({distance, squareness, p});
    }
    std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
      if (a.distance != b.distance) return a.distance < b.distance;
      return a.squareness > b.squareness;
    });
    for (const Entry& entry : entries) projection_seeds_.push_back(entry.seed);
    return projection_seeds_;
  }

  // Whether every start state that is not a goal has its arcs.
  bool start_expanded() {
    return std::all_of(start_states().begin(), start_states().end(),
                       [&](const State& s) { return is_goal(s) || graph_.count(s) > 0; });
  }

  // PlanRequest::start_targets at the next projection seeds in turn, to the first target set not met before:
  // its arc is added to every start state that is not a goal. A seed whose target set was met before becomes
  // the next alternative of that set's arc (tried when the chain check rejects it). Motions that may fail,
  // stop in free space or have too big heads make no arc. False when the seeds are used up, or before the
  // start is expanded. Projections go on after the last expansion: an arc whose heads are goals or expanded
  // states may still complete a plan.
  bool add_start_projection_arc(PlanResult& out) {
    if (!req_.start_targets || !start_expanded()) return false;
    while (next_projection_seed_ < projection_seeds().size()) {
      announce(projection_seeds(), next_projection_seed_, {});
      const Vec3 p = projection_seeds()[next_projection_seed_++];
      ++out.start_projections;
      const std::optional<std::vector<int>> targets = req_.start_targets(p);
      if (!targets || targets->empty() || ends_in_free(*targets)) continue;
      if (!projected_targets_.insert(*targets).second) {
        if (add_projection_alternative(*targets, p)) return true;
        continue;
      }
      GraphArc arc = point_arc(*targets, p);
      arc.from_start_projection = true;
      if (!usable(arc)) continue;
      // After the arcs at the same or a smaller goal distance: the simulation's arcs are cells of commanded
      // positions (any of them will do, with a margin), a projection holds at one commanded position.
      const double distance = goal_distance(arc.arc.targets);
      for (const State& s : start_states()) {
        if (is_goal(s)) continue;
        std::vector<GraphArc>& arcs = graph_.at(s);
        const auto at = std::find_if(arcs.begin(), arcs.end(), [&](const GraphArc& a) {
          return goal_distance(a.arc.targets) > distance;
        });
        arcs.insert(at, arc);
      }
      return true;
    }
    return false;
  }

  // Another commanded position for the start projection's arcs with these targets: their next alternative,
  // or, for an arc the chain check rejected, its command again (true: the graph changed).
  bool add_projection_alternative(const std::vector<int>& targets, const Vec3& p) {
    bool revived = false;
    for (const State& s : start_states()) {
      if (is_goal(s)) continue;
      for (GraphArc& arc : graph_.at(s)) {
        if (!arc.from_start_projection || arc.arc.targets != targets) continue;
        if (arc.rejected) {
          arc.commanded = p;
          arc.rejected = false;
          arc.continuations.clear();  // they hold after the old command only
          arc.next_chain_seed = 0;
          revived = true;
        } else {
          arc.alternatives.push_back({CPositionSet::none(sim_.domain()), CPositionSet::InteriorPoint{p, 0}});
        }
      }
    }
    return revived;
  }

  // One continuation per call (GraphArc::continuations): PlanRequest::confirm_chain of (a start projection's
  // command, its next chain seed), for the first start projection arc in the start state's order whose one
  // head is not a goal and that has seeds left; the second motion's verified stops make the continuation's
  // targets. Motions that may fail, rest in free space or stop where an earlier continuation of the arc
  // (not rejected) stops make none. False when no arc has seeds left.
  bool add_chain_projection_arc(PlanResult& out) {
    if (!req_.chain_projections || !req_.confirm_chain || !req_.start_targets || req_.max_motions < 2 ||
        start_states().size() != 1)
      return false;
    const auto it = graph_.find(start_states().front());
    if (it == graph_.end()) return false;
    for (GraphArc& arc : it->second) {
      if (!arc.from_start_projection || arc.rejected || arc.heads.size() != 1 || is_goal(arc.heads[0]))
        continue;
      const std::vector<Vec3>& seeds = chain_seeds_from(arc.heads[0]);
      while (arc.next_chain_seed < seeds.size()) {
        announce(seeds, arc.next_chain_seed, {arc.commanded});
        const Vec3 q = seeds[arc.next_chain_seed++];
        const ChainVerdict& verdict = chain_verdict({arc.commanded, q}, &out.chain_projections);
        if (verdict.ends.size() < 2 || !verdict.ends[1]) continue;
        const std::vector<int>& targets = *verdict.ends[1];
        if (targets.empty() || ends_in_free(targets)) continue;
        if (std::any_of(arc.continuations.begin(), arc.continuations.end(),
                        [&](const GraphArc& c) { return !c.rejected && c.arc.targets == targets; }))
          continue;
        GraphArc next = point_arc(targets, q);
        next.from_chain_projection = true;
        if (!usable(next)) continue;
        // Nearest the goal first, as a state's arcs.
        const double distance = goal_distance(targets);
        const auto at =
            std::find_if(arc.continuations.begin(), arc.continuations.end(),
                         [&](const GraphArc& c) { return goal_distance(c.arc.targets) > distance; });
        arc.continuations.insert(at, std::move(next));
        return true;
      }
    }
    return false;
  }

  // The chain seeds (chain_seeds()) for continuations from `head`: with PlanRequest::start_point, those
  // the pull from the head's atoms meets most squarely first.
  const std::vector<Vec3>& chain_seeds_from(const State& head) {
    const State key = req_.start_point ? head : State{};
    auto it = chain_seeds_.find(key);
    if (it != chain_seeds_.end()) return it->second;
    std::vector<bool> goal_or_near(static_cast<std::size_t>(cspace_.atom_count()));
    for (int a = 0; a < cspace_.atom_count(); ++a)
      goal_or_near[static_cast<std::size_t>(a)] = goal_atom(a) || near_goal(a);
    std::optional<Vec3> from;
    if (req_.start_point) from = atoms_centroid(cspace_, head);  // none: id order
    return chain_seeds_.emplace(key, chain_seeds(cspace_, goal_or_near, req_.eps_s, from)).first->second;
  }

  // PlanRequest::prefetch of the chains `before` + (seed) for the next lookahead seeds from `first`.
  void announce(const std::vector<Vec3>& seeds, std::size_t first, const std::vector<Vec3>& before) const {
    if (!req_.prefetch || req_.lookahead <= 1) return;
    std::vector<std::vector<Vec3>> chains;
    for (std::size_t k = first; k < seeds.size() && chains.size() < static_cast<std::size_t>(req_.lookahead);
         ++k) {
      chains.push_back(before);
      chains.back().push_back(seeds[k]);
    }
    req_.prefetch(chains);
  }

  // An arc that claims no cell: one commanded position and the targets the verifier found for it.
  GraphArc point_arc(const std::vector<int>& targets, const Vec3& p) const {
    GraphArc arc;
    arc.arc = Arc{targets, CPositionSet::none(sim_.domain())};
    arc.commanded = p;
    arc.heads = confusable_sets(confusable_, targets);
    return arc;
  }

  // PlanRequest::confirm_chain, each chain verified once (a continuation's chain is checked again as a
  // candidate when it completes a plan); `calls` counts the verifications made.
  const ChainVerdict& chain_verdict(const std::vector<Vec3>& commanded, int* calls = nullptr) {
    std::vector<double> key;
    for (const Vec3& p : commanded) key.insert(key.end(), {p.x(), p.y(), p.z()});
    const auto known = chain_verdicts_.find(key);
    if (known != chain_verdicts_.end()) return known->second;
    if (calls) ++*calls;
    return chain_verdicts_.emplace(std::move(key), req_.confirm_chain(commanded)).first->second;
  }

  // The arc of one target set: the deepest of the cells of its seeds, the others its alternatives; nothing
  // when no seed's cell has an interior point inside it.
  std::optional<GraphArc> arc_for(const State& state, const std::vector<int>& targets,
                                  const std::vector<Vec3>& points) {
    std::vector<std::pair<CPositionSet, CPositionSet::InteriorPoint>> cells;
    for (const Vec3& p : points) {
      CPositionSet cell = sim_.cell_at(state, p);
      const auto interior = cell.interior_point();
      if (!interior) continue;
      const std::vector<int> at = sim_.targets_at(state, interior->point);
      if (!std::includes(targets.begin(), targets.end(), at.begin(), at.end())) continue;  // not p's cell
      cells.emplace_back(std::move(cell), *interior);
    }
    if (cells.empty()) return std::nullopt;
    std::stable_sort(cells.begin(), cells.end(),
                     [](const auto& a, const auto& b) { return a.second.depth > b.second.depth; });
    GraphArc arc;
    arc.arc = Arc{targets, cells[0].first};
    arc.commanded = cells[0].second.point;
    arc.depth = cells[0].second.depth;
    arc.heads = confusable_sets(confusable_, targets);
    arc.alternatives.assign(std::make_move_iterator(cells.begin() + 1), std::make_move_iterator(cells.end()));
    return arc;
  }

  // Whether `targets` holds the targets of one of `arcs`. Such a set is not built: where an arc may stop in
  // a subset of its atoms, each head of that arc lies inside one of its heads, so the smaller arc leaves the
  // robot no less certain where it is. This keeps a state's arcs to the minimal target sets (a few dozen
  // instead of hundreds from a state of many atoms). It is a pruning heuristic: a larger set's cells are
  // never tried, even when the verifier later refutes the smaller one.
  static bool dominated(const std::vector<int>& targets, const std::vector<GraphArc>& arcs) {
    return std::any_of(arcs.begin(), arcs.end(), [&](const GraphArc& arc) {
      return std::includes(targets.begin(), targets.end(), arc.arc.targets.begin(), arc.arc.targets.end());
    });
  }

  // Commanded positions the arrangement is explored at: the centres of a kSeedGrid^3 grid over the domain,
  // a finer one over the atoms' box grown by a quarter of its diagonal (commands near the contacts, where
  // the arrangement's cells are small: the hole's p1 lies 2 eps_p below the bottom), the contact seeds behind
  // every face (contact_seeds()), and the vertex centroids of the pieces of the goal atoms' sticking regions
  // (where sticking in the goal is possible or sure).
  const std::vector<Vec3>& seeds() {
    if (!seeds_.empty()) return seeds_;
    const auto add_grid = [&](const AxisBox& box) {
      const Vec3 step = (box.max - box.min) / kSeedGrid;
      for (int i = 0; i < kSeedGrid; ++i)
        for (int j = 0; j < kSeedGrid; ++j)
          for (int k = 0; k < kSeedGrid; ++k)
            seeds_.push_back(box.min +
                             Vec3((i + 0.5) * step.x(), (j + 0.5) * step.y(), (k + 0.5) * step.z()));
    };
    add_grid(sim_.domain());
    AxisBox near = atoms_box(cspace_);
    const double grow = (near.max - near.min).norm() / 4;
    near.min.array() -= grow;
    near.max.array() += grow;
    add_grid(near);
    for (const Face& f : cspace_.faces())
      for (const Vec3& p : contact_seeds(f, req_.eps_s)) seeds_.push_back(p);
    for (int g = 0; g < cspace_.atom_count(); ++g) {
      if (!goal_atom(g) && !near_goal(g)) continue;
      for (const CPositionSet* set :
           {&sim_.strong_sticking(g), &sim_.weak_sticking(g), &sim_.goal_sticking(g)})
        for (const ConvexPiece& piece : set->pieces()) {
          Vec3 c = Vec3::Zero();
          for (const Vec3& v : piece.vertices) c += v;
          seeds_.push_back(c / static_cast<double>(piece.vertices.size()));
        }
    }
    return seeds_;
  }

  double goal_distance(const std::vector<int>& atoms) const {
    double worst = 0;
    for (int a : atoms) {
      double best = std::numeric_limits<double>::infinity();
      if (goal_atom(a) || near_goal(a)) best = 0;
      for (int g = 0; g < cspace_.atom_count() && best > 0; ++g)
        if (goal_atom(g) || near_goal(g)) best = std::min(best, atom_distance(cspace_, a, g));
      worst = std::max(worst, best);
    }
    return worst;
  }

  // §6.5.1: a state succeeds if it is a goal or one of its arcs succeeds; an arc succeeds if all its heads
  // do. Depth bounds the motions, so the recursion ends without Buckley's check for states met again while
  // active: a state met again with fewer motions left is a new node of the tree the strategy unrolls to
  // (extract()), never a loop. Memoized per evaluation by (state, depth): the graph does not change
  // during an evaluation (checks, expansions and projections come between evaluations). Arcs not yet
  // refuted count as usable, so a false stays false when checks later reject or widen them.
  bool success(const State& s, int depth) {
    if (is_goal(s)) return true;
    if (depth == 0) return false;
    const auto known = memo_.find({s, depth});
    if (known != memo_.end()) return known->second;
    memo_[{s, depth}] = false;  // guards nothing (depth decreases) but keeps the entry's place
    const auto it = graph_.find(s);
    if (it == graph_.end()) return false;
    bool ok = false;
    for (std::size_t i = 0; i < it->second.size() && !ok; ++i) {
      GraphArc& arc = it->second[i];  // stays in place: arcs are only added between evaluations
      if (arc.rejected) continue;
      // A start projection holds from the start region only, not from the start atoms met again later.
      if (arc.from_start_projection && depth != req_.max_motions) continue;
      ok = std::all_of(arc.heads.begin(), arc.heads.end(),
                       [&](const State& h) { return success(h, depth - 1); });
      int via = -1;  // the continuation taken after a start projection (one head, not a goal), if any
      const bool continues = arc.heads.size() == 1 && !is_goal(arc.heads[0]) && depth >= 2;
      for (std::size_t c = 0; !ok && continues && c < arc.continuations.size(); ++c) {
        const GraphArc& next = arc.continuations[c];
        ok = !next.rejected && std::all_of(next.heads.begin(), next.heads.end(),
                                           [&](const State& h) { return success(h, depth - 2); });
        if (ok) via = static_cast<int>(c);
      }
      if (ok) choice_[{s, depth}] = {i, via};
    }
    memo_[{s, depth}] = ok;
    return ok;
  }

  // PlanRequest::confirm_chain on the extracted candidate: true when it holds, or when it cannot be one chain
  // (several start states: the plan branches at once; returned unverified, as every branching plan); false
  // after widening, moving or rejecting the arc of the first motion the verifier refutes, or after rejecting
  // the first branching arc of a candidate that is not one chain.
  bool accept_chain(PlanResult& out) {
    if (!req_.confirm_chain || out.steps.empty() || out.start_states.size() > 1) return true;
    if (!out.decision_free) {  // no chain to verify: its first branching arc goes, and the search goes on
      for (const PlanStep& step : out.steps)
        if (std::any_of(step.arc.heads.begin(), step.arc.heads.end(),
                        [&](const State& h) { return !is_goal(h); }) &&
            step.arc.heads.size() > 1) {
          step_arcs_[static_cast<std::size_t>(&step - out.steps.data())]->rejected = true;
          return false;
        }
      return true;  // no arc branches to a non-goal head: returned unverified, as a branching plan
    }
    std::vector<Vec3> commanded;
    for (const PlanStep& step : out.steps) commanded.push_back(step.arc.commanded);
    ++out.chains_checked;
    const ChainVerdict verdict = chain_verdict(commanded);
    if (verdict.reliable) {
      ++confirmed_;
      out.chain_verified = true;
      return true;
    }
    ++rejected_;
    for (std::size_t i = 0; i < out.steps.size() && i < verdict.ends.size(); ++i) {
      GraphArc& arc = *step_arcs_[i];
      if (!verdict.ends[i]) {
        next_cell_or_reject(arc);
        return false;
      }
      const std::vector<int> widened = target_union(arc.arc.targets, *verdict.ends[i]);
      if (widened != arc.arc.targets) {
        ++widened_;
        arc.arc.targets = widened;
        arc.heads = confusable_sets(confusable_, widened);
        arc.continuations.clear();  // they continue from the one head it had
        arc.next_chain_seed = 0;
        if (!usable(arc)) arc.rejected = true;
        return false;
      }
    }
    // Every motion the verifier reports stopped within its arc's targets, yet the chain is unreliable: the
    // first motion it does not report (or the last one) goes.
    next_cell_or_reject(*step_arcs_[std::min(verdict.ends.size(), out.steps.size() - 1)]);
    return false;
  }

  // The arc's next cell with the same simulated targets, or rejection when none is left.
  void next_cell_or_reject(GraphArc& arc) {
    if (arc.alternatives.empty()) {
      arc.rejected = true;
      return;
    }
    auto& [cell, interior] = arc.alternatives.front();
    arc.continuations.clear();  // they hold after the old command only
    arc.next_chain_seed = 0;
    arc.arc.cpositions = std::move(cell);
    arc.commanded = interior.point;
    arc.depth = interior.depth;
    arc.alternatives.erase(arc.alternatives.begin());
  }

  bool usable(const GraphArc& arc) const {
    return std::all_of(arc.heads.begin(), arc.heads.end(), [&](const State& h) {
      return is_goal(h) || static_cast<int>(h.size()) <= req_.max_atoms;
    });
  }

  bool all_succeed(const std::vector<State>& states) {
    choice_.clear();
    memo_.clear();
    return std::all_of(states.begin(), states.end(),
                       [&](const State& s) { return success(s, req_.max_motions); });
  }

  // The unexpanded non-goal state nearest the goal among those reachable from the start in fewer than
  // max_motions arcs (start projections and their continuations followed from the root only).
  std::optional<State> pick() const {
    std::optional<State> best;
    double best_distance = std::numeric_limits<double>::infinity();
    // A continuation's heads are two motions on, so the queue is not in depth order: a state is walked
    // again when met at a smaller depth.
    std::map<State, int> seen;  // the smallest depth each state was walked at
    std::vector<std::pair<State, int>> queue;
    for (const State& s : start_states_) queue.push_back({s, 0});  // set by run()
    for (std::size_t i = 0; i < queue.size(); ++i) {
      const auto [s, depth] = queue[i];
      if (is_goal(s) || depth >= req_.max_motions) continue;
      const auto walked = seen.find(s);
      if (walked != seen.end() && walked->second <= depth) continue;
      seen[s] = depth;
      const auto it = graph_.find(s);
      if (it == graph_.end()) {
        const double d = goal_distance(s);
        if (d < best_distance) best_distance = d, best = s;
        continue;
      }
      for (const GraphArc& arc : it->second) {
        // A start projection (and so its continuations) holds at the root only, as in success().
        if (arc.rejected || (arc.from_start_projection && depth != 0)) continue;
        for (const State& h : arc.heads) queue.push_back({h, depth + 1});
        for (const GraphArc& next : arc.continuations)
          if (!next.rejected)
            for (const State& h : next.heads) queue.push_back({h, depth + 2});
      }
    }
    return best;
  }

  // The solution tree by motions left: every recorded choice at depth d is an arc whose heads succeeded at
  // d - 1 (and recorded their own choices), so the walk ends in goals after at most max_motions arcs. Keying
  // by state alone could join choices made at different depths into a loop.
  // A continuation is the step after its start projection, from the projection's head (step_arcs_: the
  // graph's arc of each step, for the chain check to change).
  void extract(PlanResult& out) {
    std::set<std::pair<State, int>> listed;
    step_arcs_.clear();
    std::function<void(const State&, int)> walk = [&](const State& s, int depth) {
      if (is_goal(s) || !listed.insert({s, depth}).second) return;
      const auto [index, via] = choice_.at({s, depth});
      GraphArc& arc = graph_.at(s)[index];
      out.steps.push_back({s, depth, arc, index});
      step_arcs_.push_back(&arc);
      if (via < 0) {
        for (const State& h : arc.heads) walk(h, depth - 1);
        return;
      }
      GraphArc& next = arc.continuations[static_cast<std::size_t>(via)];
      out.steps.push_back({arc.heads[0], depth - 1, next, index});
      step_arcs_.push_back(&next);
      for (const State& h : next.heads) walk(h, depth - 2);
    };
    for (const State& s : out.start_states) walk(s, req_.max_motions);
    out.found = true;
    out.decision_free = out.start_states.size() == 1;
    for (std::size_t i = 0; i < out.steps.size() && out.decision_free; ++i) {
      const auto& heads = out.steps[i].arc.heads;
      const bool last = i + 1 == out.steps.size();
      out.decision_free =
          last ? std::all_of(heads.begin(), heads.end(), [&](const State& h) { return is_goal(h); })
               : heads.size() == 1 && heads[0] == out.steps[i + 1].state;
    }
  }

  AtomSimulation& sim_;
  const CSpace& cspace_;
  const PlanRequest& req_;
  const Confusability confusable_;
  std::map<State, std::vector<GraphArc>> graph_;
  // Per (state, motions left): the chosen arc's index, and the continuation taken after it (-1: none).
  std::map<std::pair<State, int>, std::pair<std::size_t, int>> choice_;
  std::vector<GraphArc*> step_arcs_;  // extract(): the graph's arc of each step
  std::map<std::vector<double>, ChainVerdict> chain_verdicts_;
  std::map<std::pair<State, int>, bool> memo_;
  std::vector<Vec3> seeds_;
  std::vector<State> start_states_;
  std::vector<Vec3> projection_seeds_;
  std::map<State, std::vector<Vec3>> chain_seeds_;  // by head (one entry, {}, without a start point)
  std::size_t next_projection_seed_ = 0;
  std::set<std::vector<int>> projected_targets_;
  int confirmed_ = 0, rejected_ = 0, widened_ = 0;
};

// The cosine between the pull from `start` to `target` and the unit vector `inward` (0 for no pull).
double pull_cosine(const Vec3& start, const Vec3& target, const Vec3& inward) {
  const Vec3 pull = target - start;
  const double length = pull.norm();
  if (length == 0) return 0;
  return inward.dot(pull) / length;
}

Vec3 vertex_centroid(const Face& face) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : face.polygon) c += v;
  return c / static_cast<double>(face.polygon.size());
}

}  // namespace

std::vector<State> confusable_sets(const Confusability& confusable, const std::vector<int>& all_atoms) {
  // Bron–Kerbosch without pivoting: the sets are small (the targets of one arc). Ids past the table (the
  // free-space and goal-stop atoms) are states of their own.
  std::vector<State> out;
  std::vector<int> atoms;
  for (int a : all_atoms)
    if (a < confusable.atoms())
      atoms.push_back(a);
    else
      out.push_back({a});
  std::function<void(State, std::vector<int>, std::vector<int>)> grow = [&](State r, std::vector<int> p,
                                                                            std::vector<int> x) {
    if (p.empty() && x.empty()) {
      std::sort(r.begin(), r.end());
      out.push_back(r);
      return;
    }
    while (!p.empty()) {
      const int v = p.back();
      p.pop_back();
      std::vector<int> np, nx;
      for (int w : p)
        if (confusable(v, w)) np.push_back(w);
      for (int w : x)
        if (confusable(v, w)) nx.push_back(w);
      State nr = r;
      nr.push_back(v);
      grow(nr, np, nx);
      x.push_back(v);
    }
  };
  if (!atoms.empty()) grow({}, atoms, {});
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<Vec3> contact_seeds(const Face& face, double unit) {
  const Vec3 c = vertex_centroid(face);
  std::vector<Vec3> out;
  for (double depth : kContactSeedDepths) out.push_back(c - depth * unit * face.normal);
  return out;
}

double projection_seed_order(const Face& face, const Vec3& start) {
  return pull_cosine(start, vertex_centroid(face), -face.normal);
}

std::vector<Vec3> edge_seeds(const CSpace& cspace, const Edge& edge, double unit) {
  if (edge.faces.size() < 2) return {};
  const Vec3 middle = (edge.a + edge.b) / 2;
  const Vec3 n1 = cspace.faces()[static_cast<std::size_t>(edge.faces[0])].normal;
  const Vec3 n2 = cspace.faces()[static_cast<std::size_t>(edge.faces[1])].normal;
  if (n1.cross(n2).norm() < kParallelNormals) return {};  // a flat edge: the faces' contact seeds
  std::vector<Vec3> out;
  for (const auto& depths : kEdgeSeedDepths) out.push_back(middle - unit * (depths[0] * n1 + depths[1] * n2));
  return out;
}

double edge_seed_order(const CSpace& cspace, const Edge& edge, const Vec3& start) {
  if (edge.faces.size() < 2) return 0;
  const Vec3 n1 = cspace.faces()[static_cast<std::size_t>(edge.faces[0])].normal;
  const Vec3 n2 = cspace.faces()[static_cast<std::size_t>(edge.faces[1])].normal;
  if (n1.cross(n2).norm() < kParallelNormals) return 0;
  return pull_cosine(start, (edge.a + edge.b) / 2, -(n1 + n2).normalized());
}

std::vector<Vec3> chain_seeds(const CSpace& cspace, const std::vector<bool>& goal_atom, double unit,
                              const std::optional<Vec3>& from) {
  const auto goal = [&](int atom) { return atom < static_cast<int>(goal_atom.size()) && goal_atom[atom]; };
  std::vector<const Face*> faces;
  std::vector<int> edges;  // atom ids
  const auto add_edge = [&](int e) {
    if (std::find(edges.begin(), edges.end(), e) == edges.end()) edges.push_back(e);
  };
  for (const Face& f : cspace.faces()) {
    if (!goal(f.id)) continue;
    faces.push_back(&f);
    for (int e : f.edges) add_edge(e);
  }
  for (const Edge& e : cspace.edges())
    if (goal(e.id)) add_edge(e.id);
  const int first_edge = static_cast<int>(cspace.faces().size());
  const auto edge_of = [&](int e) -> const Edge& {
    return cspace.edges()[static_cast<std::size_t>(e - first_edge)];
  };
  std::vector<Vec3> out;
  if (!from) {
    for (const Face* f : faces)
      for (const Vec3& p : contact_seeds(*f, unit)) out.push_back(p);
    for (std::size_t k = 0; k < std::size(kEdgeSeedDepths); ++k)
      for (int e : edges) {
        const std::vector<Vec3> behind = edge_seeds(cspace, edge_of(e), unit);
        if (!behind.empty()) out.push_back(behind[k]);
      }
    return out;
  }
  std::stable_sort(faces.begin(), faces.end(), [&](const Face* a, const Face* b) {
    return projection_seed_order(*a, *from) > projection_seed_order(*b, *from);
  });
  std::stable_sort(edges.begin(), edges.end(), [&](int a, int b) {
    return edge_seed_order(cspace, edge_of(a), *from) > edge_seed_order(cspace, edge_of(b), *from);
  });
  for (const Face* f : faces)
    for (const Vec3& p : contact_seeds(*f, unit)) out.push_back(p);
  for (int e : edges)
    for (const Vec3& p : edge_seeds(cspace, edge_of(e), unit)) out.push_back(p);
  return out;
}

std::optional<Vec3> atoms_centroid(const CSpace& cspace, const std::vector<int>& atoms) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (int a : atoms) {
    if (a < 0 || a >= cspace.atom_count()) continue;  // free space, goal stops
    ++n;
    const std::size_t i = static_cast<std::size_t>(cspace.atom_index(a));
    switch (cspace.atom_kind(a)) {
      case AtomKind::kFace:
        sum += vertex_centroid(cspace.faces()[i]);
        break;
      case AtomKind::kEdge:
        sum += (cspace.edges()[i].a + cspace.edges()[i].b) / 2;
        break;
      default:
        sum += cspace.vertices()[i].point;
    }
  }
  if (n == 0) return std::nullopt;
  return Vec3(sum / n);
}

PlanResult plan_sticking(AtomSimulation& simulation, const CSpace& cspace, const PlanRequest& request) {
  return Search(simulation, cspace, request).run();
}

}  // namespace cmt::planner

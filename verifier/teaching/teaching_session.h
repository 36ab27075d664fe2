// The teaching system's teaching loop (Buckley §5.1; verifier/teaching/README.md). The teacher proposes
// commanded motions, the strategy's last motion first. Each motion m_k gets a pre-image: the start cells
// from which m_k followed by the strategy of an earlier step (C_{k-1} first, then C_{k-2}, ..., then m_k
// alone) is verified reliable by the forward projection (verify.h), and, when those leave cells unsolved, m_k
// followed by a sensed dispatch between them (Buckley Alg 5.1: after m_k the robot senses which solved region
// it is in; dispatches() below). Step k's strategy C_k is the candidate that solved the most, or
// [m_k] ++ C_{k-1} when it solved nothing (its pre-image lies off the start, where later motions may land).
// Solved cells leave the start; when the start is empty, the strategy that solved it is the taught strategy.
// A step starts from the unsolved cells with halves that are both unsolved merged back: the forward
// projection of a cell can be looser than that of a larger set (its fixpoint widening is not monotone), so a
// step first tries the largest unsolved cells.
//
// Soundness: a cell counts as solved only when the verifier proves the chain reliable from the whole closed
// cell, so a solved region is a sound under-approximation of the strong pre-image of the goal under the
// chain (Buckley §5.4: every trajectory reaches the goal), as sound as the forward projection itself.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/reached_set.h"
#include "verifier/teaching/taught_strategy.h"
#include "verifier/verify.h"

namespace cmt::teaching {

struct TeachOptions {
  VerifyOptions verify;
  // How often a start cell may be halved (verifier/teaching/start_cells.h) before it is left unsolved: up to
  // 2^refine_depth cells per start region, and 2^(refine_depth + 1) - 1 verifications of one chain.
  int refine_depth = 2;
  // Atoms of the motion's own termination set checked one by one when explaining an unsolved start.
  int max_reason_atoms = 12;
  // The sensed dispatch (Alg 5.1) is built only when the motion's termination set from the unsolved cells
  // meets at most this many atoms (each is checked against every earlier strategy); 0 turns it off.
  int max_dispatch_atoms = 12;
};

// A start cell: its place in the tree of halvings ("" the start, then '0'/'1' per halving) and its region.
struct StartCell {
  std::string path;
  Region region;
  Strategy chain;  // for a solved cell: the strategy verified reliable from it (no node otherwise)
  int depth() const { return static_cast<int>(path.size()); }
};

// One proposed motion and what it solved (a row of Buckley's table of solved regions, §5.1).
struct TeachStep {
  std::string motion;
  Strategy chain;                    // C_k: the candidate that solved the most, else [m_k] ++ C_{k-1}
  std::vector<StartCell> solved;     // start cells the chain is verified reliable from
  std::vector<StartCell> remaining;  // start cells unsolved after this step
  double solved_measure = 0;         // length or area of the solved cells (0 for a point start)
  double remaining_measure = 0;
  // Why cells stayed unsolved: the verifier's failure for the chain from the remaining cells, and the
  // pieces where m_k may terminate from which C_{k-1} does not reach the goal (for the first step, the
  // termination pieces outside the goal). Atoms beyond TeachOptions::max_reason_atoms are not checked.
  std::string failure;
  std::vector<ReachedPiece> blocking;
  int unchecked_reason_atoms = 0;
  // Where m_k may stop (its termination set, the first motion of the chain): from the cells it solved (one
  // piece list per verification that solved a cell), and from the cells that remain (when explained).
  // Buckley's Figs 5.4 and 5.7 draw the non-goal part of these: the weak sticking points to avoid.
  std::vector<ReachedPiece> stops_from_solved, stops_from_remaining;
  int verifications = 0;  // verifier runs: the motion once per cell tried, each chain's rest from its stops
  int dispatches = 0;     // sensed-dispatch candidates tried (dispatches())
  double seconds = 0;
  // The taught strategy once this step leaves the start empty (Session::strategy).
  std::optional<Strategy> strategy;
};

class Session {
 public:
  Session(std::shared_ptr<const LoadedTask> task, TeachOptions options);

  // Proposes a motion of the task by name (TaskError when unknown), or an inline motion; an inline motion
  // without a name is named taught_<k> for step k (1-based), and the task copy this teaching session verifies
  // gains it.
  const TeachStep& propose(const std::string& motion_name);
  const TeachStep& propose(Motion motion);
  // Removes the last step (and an inline motion it added). False when there is no step.
  bool undo();

  bool solved() const;
  const std::vector<TeachStep>& steps() const { return steps_; }
  const std::vector<StartCell>& remaining() const;
  // The task with the inline motions added.
  const LoadedTask& task() const { return *task_; }
  std::shared_ptr<const LoadedTask> task_ptr() const { return task_; }
  // The taught strategy once solved: the chain that solved every cell, or, when cells were solved by
  // different chains, the latest of them that is verified reliable from the whole start; nullopt otherwise.
  std::optional<Strategy> strategy() const;
  // The inline motions added so far (in step order).
  const std::vector<Motion>& inline_motions() const { return inline_motions_; }

 private:
  const TeachStep& run_step(const std::string& motion_name);
  void refine(const Strategy& chain, const StartCell& cell, int max_depth, TeachStep& step,
              std::vector<StartCell>& unsolved);
  std::vector<Strategy> candidates(const std::string& motion_name) const;
  std::vector<Strategy> dispatches(const std::string& motion_name, const std::vector<StartCell>& cells,
                                   TeachStep& step);
  std::vector<StartCell> try_candidates(const std::vector<Strategy>& chains, std::vector<StartCell> cells,
                                        bool halve, TeachStep& step, std::vector<double>& solved_by);
  std::vector<StartCell> merged(const std::vector<StartCell>& cells) const;
  VerifyResult verify_from(const Strategy& chain, const ReachedSet& start, TeachStep& step) const;
  // The proposed motion's simulation from a cell, shared by the chains a step tries on it.
  struct FirstMotion {
    bool motion_ok = false;  // no failure of the motion itself (verify.cc: may not terminate, may slide
                             // forever, may rest in free space)
    ReachedSet termination;
  };
  const FirstMotion& first_motion(const std::string& motion, const StartCell& cell, TeachStep& step);
  bool chain_reliable(const Strategy& chain, const StartCell& cell, TeachStep& step);
  void explain(const Strategy& chain, TeachStep& step);
  std::optional<Strategy> taught_strategy() const;

  std::shared_ptr<const LoadedTask> original_;
  std::shared_ptr<const LoadedTask> task_;
  TeachOptions options_;
  std::vector<TeachStep> steps_;
  std::vector<Motion> inline_motions_;
  std::vector<bool> step_added_motion_;  // per step: it added the last inline motion
  std::vector<StartCell> initial_;
  std::map<std::string, Region> cells_;               // every cell made so far, by path
  std::map<std::string, FirstMotion> first_motions_;  // of the step being run, by cell path
};

// The union of the cells' start sets (ReachedSet::from_region, rounded outward).
ReachedSet cells_set(const LoadedTask& task, const std::vector<StartCell>& cells);

}  // namespace cmt::teaching

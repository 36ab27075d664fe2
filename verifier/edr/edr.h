// One-step error detection and recovery under model error (Donald 1987 §1.3, §2 "1EDR", l.1456-1556,
// l.1858-1919) on slices of the generalized configuration space C x J (models/model_error.h).
//
// Per slice alpha, with the strategy's motions run from the start under sticking termination (our motions end
// where they stick or slide slower than the stop rule's kappa; Donald l.2547-2677):
//  - F: the contact points the last motion may pass through (its forward projection), T ⊆ F its termination
//  set;
//  - P (strong) and P~ (weak) preimages of the slice's goal G under the last motion, with the history F:
//    P = S_m(G) ∩ F, P~ = W_m(G) ∩ F (Alg 5.2; damper motions, the only ones with backprojections);
//  - H = (F − P~) ∪ H_s (Donald eq. 2/6), H_s the points of P~ − P where the robot may stick, restricted to
//  where
//    the motion may terminate: H = T − G (a termination point in P lies in G, since P avoids every stop
//    outside G), which is what we compute, under the verifier's goal containment (verify.h
//    pieces_outside_goal); H_s = H ∩ P~. Where G vanishes, H = T.
// The EDR termination predicate signals success when the sensed position and force are consistent with a
// termination point in G of some slice, failure otherwise. The strategy is EDR-reliable when
//  (a) in every slice the motions terminate (no slide forever, no fallback of a fixpoint),
//  (b) the goal is reached in some slice (Donald's search drops a motion whose F misses G everywhere),
//  (c) no termination point in G of any slice is confusable with a point of H of any slice (distinguish.h):
//      then "success" is never signalled outside G, and where P covers the start (success guaranteed)
//      every termination is in G and is recognized, so failure is never signalled there (the EDR axioms,
//      Donald l.1361-1374);
//  (d) a multi-motion strategy is linked (Donald §12.5, l.5081-5085): where the push-forward of the first k
//      motions meets G, the remaining motions are guaranteed to end in G, i.e. (L0) G ∩ push ⊆ R2 with R2 the
//      push-forward's part in the strong preimage of G under the rest; (L0) is equivalent to (L1)
//      G ∩ push = R2* and to (L2) H ∩ push = push − R2*. A robot that reached the goal early is not led out
//      of it into a failure signal.
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "models/loaded_task.h"
#include "verifier/edr/distinguish.h"
#include "verifier/verify.h"

namespace cmt {

struct EdrSlice {
  std::vector<double> values;              // the model parameters' values
  VerifyOptions options;                   // the verifier's options in this slice
  std::shared_ptr<const LoadedTask> task;  // the slice
  bool goal_empty = false;                 // the goal is on no face of this slice
  bool terminates = true;                  // (a) holds in this slice
  std::string termination_problem;         // the verifier's reason when (a) fails
  bool reliable = false;                   // every termination lies in G: success guaranteed here
  bool distinguishable = true;             // no confusable pair involves this slice
  bool linked = true;                      // (d) holds in this slice
  std::string linking_problem;             // which push-forward meets G and where the rest may lead
  // F, T and T ∩ G (null when the motions may not terminate).
  std::shared_ptr<const ReachedSet> reached, termination, success;
  std::vector<ReachedPiece> failure_pieces;  // H = T − G
  std::optional<ReachedSet> strong;          // P (damper last motion)
  std::optional<ReachedSet> weak;            // P~
  double failure_sticking_area = 0;          // area of H_s = H ∩ P~ (damper)
  double failure_area = 0;                   // area of H's face pieces
};

struct EdrOptions {
  // The verifier's options and the strong preimage's margin (backproject_damper) for a slice; the CLI takes
  // the rollouts' model of each slice (experiments/validation/verifier_model.h). Default: first order.
  std::function<VerifyOptions(const LoadedTask&)> verify = [](const LoadedTask&) { return VerifyOptions{}; };
  std::function<double(const LoadedTask&)> backprojection_margin = [](const LoadedTask&) { return 0.0; };
  std::size_t confusion_limit = 20;  // confusable pairs listed (the verdict counts them all)
  // The preimages P and P~ (reported, not needed by the verdict (a)-(c)); the planner's search skips them.
  bool preimages = true;
  // Slicing-gap refinement (docs/edr.md "Between slices"), for a task with one continuous model parameter:
  // each pair of adjacent slices is bisected, up to this many times, where exactly one of the two has a goal
  // or the midpoint's terminations in G or H are not covered by the pair's sweep (a stop region whose extent
  // has a kink between them). The midpoint joins the slices only then. 0: the given slices only.
  int refine_depth = 0;
};

struct EdrConfusion {
  int success_slice = -1, failure_slice = -1;
  ReachedPiece success_piece, failure_piece;
  double distance = 0, force_angle = 0;
};

struct EdrResult {
  std::vector<EdrSlice> slices;
  // Between adjacent slices (differing in one continuous parameter, at consecutive values) the terminations
  // in G and in H sweep: per atom that both slices' pieces lie on, the convex hull of the two pieces when
  // they are coplanar (a face or edge that translates with the parameter, e.g. a hole's bottom edge as its
  // width grows). The verdict's test (c) and the EDR predicate (experiments/edr/edr_check.h) use the swept
  // pieces beside the slices' own, so that a world between two slices is judged too (its terminations lie in
  // the sweep when its pieces move affinely and keep their atoms; docs/edr.md "Between slices"). Only along
  // one parameter at a time (grid edges, not the inside of a cell of several parameters), and none for more
  // than 2000 slices.
  std::vector<SlicePiece> swept_success, swept_failure;
  int refine_depth = 0;       // the refinement applied (EdrOptions::refine_depth; 0 where it does not apply)
  bool terminates = true;     // (a)
  bool reaches_goal = false;  // (b)
  bool distinguishable = true;  // (c)
  bool linked = true;           // (d)
  bool edr_reliable = false;
  std::vector<EdrConfusion> confusions;  // the first EdrOptions::confusion_limit of them
  int confusion_count = 0;
  std::string reason;  // why not EDR-reliable
};

// `slices`: model parameter values (models/model_error.h model_slices). Throws TaskError when a slice's
// geometry is not accepted or its start leaves the contact surface.
EdrResult verify_edr(const Task& task, const std::vector<std::string>& motions,
                     const std::vector<std::vector<double>>& slices, const EdrOptions& options);

}  // namespace cmt

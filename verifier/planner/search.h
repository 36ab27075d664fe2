// Buckley's planner search (§6.5, §6.6) over the simulation's arcs (type 1, sticking, or type 2 with the
// goal's sensed positions: the simulation's GoalStops decide): states are sets of atoms sensing cannot tell
// apart; a state's arcs are the cells of the simulation's arrangement (simulation.h) met at seed commanded
// positions, one per target set; a best-first expansion with AND/OR evaluation returns the first strategy
// that reaches goal states in every branch.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "models/cspace.h"
#include "verifier/planner/confusability.h"
#include "verifier/planner/simulation.h"

namespace cmt::planner {

using State = std::vector<int>;  // ascending atom ids

// The verdict on a chain of motions verified from the task's start (verifier_check.h): whether it is
// reliable, and per motion in order the atoms where it may stop, or nothing where it may fail otherwise
// (ending at the first such motion).
struct ChainVerdict {
  bool reliable = false;
  std::vector<std::optional<std::vector<int>>> ends;
};

struct PlanRequest {
  std::vector<int> start_atoms;  // the atoms the robot may start in
  std::vector<bool> goal_atom;   // per atom: its closure lies in the goal
  // Per atom: a face partly in the goal (goal_stops.h), at goal distance 0 for the search's order and seeds.
  // Stops surely inside the goal are the simulation's goal-stop atom, a goal state.
  std::vector<bool> goal_near;
  double eps_s = 0, theta_f = 0;
  int max_atoms = 3;         // states of more atoms (that are not goal states) are not expanded
  int max_motions = 3;       // the longest branch of a strategy
  int max_expansions = 200;  // states expanded before the search gives up
  // The lazy check of a whole candidate (the planner's usual one): a decision-free strategy the search
  // found is accepted only when its chain of commanded positions, verified from the task's start, is
  // reliable. Otherwise the first motion whose verified stops leave its arc's targets widens that arc (or,
  // where it may fail otherwise, moves the arc to its next cell or rejects it), and the search goes on.
  // Each motion is verified from the previous one's actual termination set, so arcs whose sources are
  // whole atoms (open, as Buckley's states) need not be reliable from the atoms' closures. With the check
  // set, a candidate that branches on sensed states loses its first branching arc instead (strategies with
  // tests are not written yet), so the search returns chains only. Unset: no check.
  std::function<ChainVerdict(const std::vector<Vec3>& commanded)> confirm_chain;
  // Direct reaching from the start region itself (§6.7.5): the atoms where a motion commanded to p,
  // started anywhere in the task's start region, may stop, or nothing when it may fail otherwise (the
  // verifier's forward projection, verifier_check.h). Set, the start states also get one arc per target set
  // met at the contact seeds (contact_seeds(), behind the goal's faces first, then the faces nearest the
  // goal), with these targets: the simulation starts from whole atoms, and a start region that touches a
  // large atom's edge (the hole's start segment reaches the flat edges of the top face) may then leave the
  // start face wherever it is, while the projection follows the actual path. The seeds are taken in turn, one
  // new target set per round of the search. Unset: the start states' arcs are the simulation's only.
  std::function<std::optional<std::vector<int>>(const Vec3& commanded)> start_targets;
  // A point of the start region (its vertex centroid). Set, the projection seeds' faces at equal goal
  // distance come in the order the pull from the start meets them, most squarely first
  // (projection_seed_order()), and the chain seeds of a start projection's continuations in the order the
  // pull from the projection's head (where the continuations start: atoms_centroid()) meets their faces and
  // edges (chain_seeds()). Seeds only: the order changes which plan is found first and how many verifier
  // calls it takes, never what an arc claims.
  std::optional<Vec3> start_point;
  // With both checks set and one start state, chains of projections: a start projection's arc whose one head
  // is not a goal also gets continuations (GraphArc::continuations), verified by confirm_chain from the
  // projection's own termination set at the chain seeds (chain_seeds()), one new continuation per round.
  // The simulation starts the second motion from the whole head atom, which may include places the first
  // motion never stops at (a wall's rim).
  bool chain_projections = true;
  int max_chain_checks = 40;  // candidates checked before the search gives up
  // Announces the next `lookahead` chains the projections will ask confirm_chain (start_targets: one-motion
  // chains) for, in the order they will be asked, so that they can be verified ahead several at once. The
  // answers must not depend on it. Unset, or lookahead <= 1: nothing is announced.
  std::function<void(const std::vector<std::vector<Vec3>>& chains)> prefetch;
  int lookahead = 1;
};

// An arc of the state graph: a cell of commanded positions from the source state with the atoms they may
// stop in, the commanded position chosen in it (CPositionSet::interior_point) and its target states (heads).
struct GraphArc {
  Arc arc;
  Vec3 commanded = Vec3::Zero();
  double depth = 0;          // of `commanded` inside its piece
  std::vector<State> heads;  // the maximal confusable sets of the targets
  // Other cells with the same simulated targets, deepest first, tried in turn when `confirm_chain` finds
  // the motion may fail.
  std::vector<std::pair<CPositionSet, CPositionSet::InteriorPoint>> alternatives;
  bool rejected = false;  // refuted by confirm_chain (or its heads grew too big): never chosen
  // Targets from PlanRequest::start_targets at `commanded` alone (arc.cpositions is empty: no cell is
  // claimed), instead of the simulation's cell.
  bool from_start_projection = false;
  // A start projection's continuations: arcs from its one head (not a goal) that hold only after it, each
  // commanded at one chain seed with the second motion's stops of PlanRequest::confirm_chain(this
  // arc's command, that seed) as targets (from_chain_projection; no cell claimed). Cleared when the
  // projection's command or heads change; next_chain_seed is the next seed to try.
  std::vector<GraphArc> continuations;
  bool from_chain_projection = false;
  std::size_t next_chain_seed = 0;
};

// A step of the found strategy: in `state`, with at most `motions_left` motions to go, command `arc`. The
// solution is a tree unrolled by motions left, so a state may appear at several depths (never in a loop).
struct PlanStep {
  State state;
  int motions_left = 0;
  GraphArc arc;
  // Of `arc` among the state's arcs; for a continuation (from_chain_projection), of its start projection
  // among the start state's arcs.
  std::size_t arc_index = 0;
};

struct PlanResult {
  bool found = false;
  std::string reason;  // why nothing was found (limits, or the graph was exhausted)
  std::vector<State> start_states;
  std::vector<PlanStep> steps;  // the solution, every state of it with its chosen arc (start states first)
  int expanded = 0;             // states expanded
  int arcs = 0;                 // arcs built
  int confirmed = 0, rejected = 0;  // candidate chains confirm_chain accepted, refuted
  int widened = 0;                  // arcs whose targets a refutation widened
  // Candidates checked (the last accepted when found): by confirm_chain, or by the verdict of a chain
  // projection of the same chain.
  int chains_checked = 0;
  bool chain_verified = false;  // the returned strategy is a chain confirm_chain found reliable
  int start_projections = 0;    // calls of start_targets
  int chain_projections = 0;    // confirm_chain calls made for continuations of start projections
  bool decision_free = false;   // the solution is one chain of motions (each step but the last has one head)
};

// The maximal subsets of `atoms` whose atoms are pairwise confusable (Def 6.1): the states the robot may
// find itself in after terminating somewhere in `atoms`. Ids past the table (free space, goal stops) are
// states of their own: the robot knows it came to rest or stopped by sensing.
std::vector<State> confusable_sets(const Confusability& confusable, const std::vector<int>& atoms);

// Commanded positions behind a face (Buckley's motions that stick on a face, such as the hole's p2
// "behind the far wall" and p1 "beneath the hole"): the face's vertex centroid moved against its normal by
// each of kContactSeedDepths times `unit` (the planner uses eps_s). Seeds, not claims: the simulation or
// the verifier decides what each motion does.
constexpr double kContactSeedDepths[] = {2, 5, 10};
std::vector<Vec3> contact_seeds(const Face& face, double unit);
// Commanded positions behind an edge (the T-slot's second motion, beyond the goal face and below the
// second hole's floor): the edge's midpoint moved against its first face's normal by a and its second's by b,
// for each (a, b) of kEdgeSeedDepths times `unit`. None for an edge without two faces of different normals
// (a flat edge: the faces' contact seeds stand for it).
constexpr double kEdgeSeedDepths[][2] = {{2.5, 2.5}, {5, 2.5}, {2.5, 5}, {5, 5}, {7.5, 5}, {5, 7.5}};
std::vector<Vec3> edge_seeds(const CSpace& cspace, const Edge& edge, double unit);
// How squarely a pull from `start` toward `face` meets it: the cosine between start -> the face's vertex
// centroid and the face's inward direction, -normal (1: head on; <= 0: the face looks away from the start,
// so a robot coming from there meets it only after another contact). A motion that reaches its face at a
// steep angle sticks there (Buckley §3.2: tangential over normal pull below tan phi), so the contact seeds
// behind such faces are the likelier single-face arcs and are projected first.
double projection_seed_order(const Face& face, const Vec3& start);
// The same for an edge: the cosine between start -> the edge's midpoint and the inward bisector of its two
// faces, -(n1 + n2) / |n1 + n2| (0 for an edge without two faces of different normals).
double edge_seed_order(const CSpace& cspace, const Edge& edge, const Vec3& start);
// The chain projections' seeds: the contact seeds behind the goal's faces, then the edge seeds behind the
// edges that bound a goal face or are goal atoms. Without `from`, by face id and shallow pairs first over all
// those edges; with `from` (where the chain's second motion starts), faces and edges the pull from there
// meets most squarely first (projection_seed_order(), edge_seed_order()), each edge's pairs together.
std::vector<Vec3> chain_seeds(const CSpace& cspace, const std::vector<bool>& goal_atom, double unit,
                              const std::optional<Vec3>& from = std::nullopt);
// The mean of the vertex centroids of `atoms` (faces' polygons, edges' ends, vertices), ids past the table
// (free space, goal stops) skipped; nothing when none is left.
std::optional<Vec3> atoms_centroid(const CSpace& cspace, const std::vector<int>& atoms);

PlanResult plan_sticking(AtomSimulation& simulation, const CSpace& cspace, const PlanRequest& request);

}  // namespace cmt::planner

// The physics check of the damper's stick/slide classification (verifier/damper.h): the simulated robot is
// put at rest on an atom of the task and driven with an actual velocity direction sampled inside the velocity
// cone of a commanded direction; the verifier's class for that command must agree: a must-stick atom never
// slides and a never-sticks atom never sticks. May-stick cases report the observed stick fraction.
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "models/loaded_task.h"
#include "sim/rollout.h"
#include "verifier/damper.h"

namespace cmt {

// Drive window: the robot is driven for kDriveSeconds and its tangential speed measured over the second half
// (the servo time constant is 10 ms: the first half lets the transient decay below 1e-3, e^-8).
inline constexpr double kCheckDriveSeconds = 0.16;
// Observed "stuck" when the speed over the measuring window is below this fraction of the commanded speed:
// the same threshold as the friction calibration (sim/calibration.h kSlideThreshold): far above MuJoCo's
// creep while sticking (<= 4e-5) and far below the slowest sliding the grid produces (1.2 %).
inline constexpr double kCheckStuckSpeed = 1e-3;
// ... and when its distance from the start over the whole drive, per second, is below this fraction of the
// commanded speed (10x the speed threshold: room for the contact settling in the first milliseconds).
inline constexpr double kCheckStuckTravel = 1e-2;

// One trial, for curves of the stick fraction against the command angle (reports).
struct StickingTrialRecord {
  int atom = 0;
  AtomKind kind = AtomKind::kFace;
  StickClass cls = StickClass::kMay;
  double command_angle =
      0;           // angle of the command from the atom's inward direction (sum of face normals), rad
  double phi = 0;  // friction angle atan(mu), rad
  bool stuck = false;
  double speed = 0;  // observed speed / commanded speed over the measuring window
};

struct StickingCheckResult {
  int trials = 0;
  int disagreements = 0;
  int must = 0, may = 0, never = 0;
  int may_stuck = 0;                               // may-stick cases that stuck
  nlohmann::json worst = nlohmann::json::array();  // the disagreeing trials (first 20)
  std::vector<StickingTrialRecord> records;        // every classified trial, in trial order
  int unstable = 0;  // trials whose simulation became unstable: not classified (not in must/may/never)
  nlohmann::json unstable_trials = nlohmann::json::array();  // the first 20, with the failure message
  double seconds = 0;
};

// {"trials", "disagreements", "classes": {must, may, never}, "may_stick_fraction", "disagreeing_trials",
//  "unstable", "unstable_trials", "records": [{atom, kind, class, command_angle, phi, stuck, speed}],
//  "seconds"}
nlohmann::json sticking_check_json(const LoadedTask& task, const StickingCheckResult& result);

// Which atoms the trials are drawn from.
struct AtomKindFilter {
  bool faces = true, edges = true, vertices = true;
};

// n trials with the task's theta_v, from trial streams derived from (seed, i), in the MuJoCo scene of `sim`
// (the rollouts' by default). threads >= 1; the result is the same for every thread count.
// `sim` defaults to the rollouts' own scene (SimOptions{}, sim/rollout.h calibrated_scene()): the one that
// passes the Coulomb calibration, at concave edges too (docs/rollouts.md; the stiff scene, stiff_scene(),
// is 73 % off Coulomb's sliding speed there), and a check of Coulomb stick/slide classes needs Coulomb
// contacts at every atom kind it tests.
StickingCheckResult check_sticking(std::shared_ptr<const LoadedTask> task, int n, std::uint64_t seed,
                                   int threads, AtomKindFilter kinds = {}, const SimOptions& sim = {});

}  // namespace cmt

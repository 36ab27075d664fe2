// The SQL schema of the results database (docs/sweeps.md "Results database"). The five tables and their
// first columns are an interface (report generators query them); columns after the interface ones are
// additions. Column lists are kept here once, for the merge and the CSV export.
#pragma once

namespace cmt::results_schema {

inline constexpr const char* kCreate = R"sql(
CREATE TABLE runs(
  run_id INTEGER PRIMARY KEY,
  spec_path TEXT,
  spec_text TEXT,
  created TEXT,
  shard TEXT                        -- addition: "i/N" of --shard, "rank i/K" under MPI, NULL for all units
);
CREATE TABLE configs(
  config_id INTEGER PRIMARY KEY,
  run_id INTEGER,
  unit_key TEXT UNIQUE NOT NULL,
  task TEXT NOT NULL,
  task_file TEXT,
  task_yaml TEXT NOT NULL,
  strategy TEXT NOT NULL,
  params TEXT NOT NULL,             -- JSON object of the overrides
  n INTEGER,
  seed INTEGER,
  mode TEXT,
  status TEXT NOT NULL DEFAULT 'pending',  -- pending | done
  finished TEXT,
  unit_index INTEGER,               -- addition: position in the spec's expansion
  sticking_trials INTEGER,          -- addition
  counterexample_budget INTEGER,    -- addition
  controller TEXT,                  -- addition: impedance | admittance | position (cmt validate --controller)
  falsify_budget INTEGER,           -- addition (v3): the adversarial search's budgets, 0 = no search
  falsify_coverage_budget INTEGER   -- addition (v3)
);
CREATE TABLE predictions(
  config_id INTEGER PRIMARY KEY,
  reliable INTEGER,
  failure TEXT,
  verify_seconds REAL,
  verify_json TEXT,
  verifier_theta_v REAL,            -- addition: the theta_v the verifier used (widened for admittance)
  verifier_model TEXT               -- addition: JSON, that theta_v and why (experiments/validation/verifier_model.h)
);
CREATE TABLE rollouts(
  config_id INTEGER,
  rollout INTEGER,
  motion INTEGER,                   -- the prediction step scoring it (verify_json steps; = the motion's
                                    -- index in a decision-free strategy; steps + its position in the
                                    -- rollout when nothing predicts it), -1: a rollout row without motions
  start_x REAL, start_y REAL, start_z REAL,
  end_x REAL, end_y REAL, end_z REAL,
  atom INTEGER,
  termination TEXT,
  inside INTEGER,
  distance REAL,
  success INTEGER,
  unstable INTEGER,
  PRIMARY KEY(config_id, rollout, motion)
);
CREATE TABLE metrics(
  config_id INTEGER PRIMARY KEY,
  rollouts INTEGER,
  successes INTEGER,
  unstable INTEGER,
  ends INTEGER,
  outside INTEGER,
  soundness REAL,
  coverage REAL,
  coverage_radius REAL,
  contact_tolerance REAL,
  soundness_bug INTEGER,
  counterexample TEXT,
  sticking TEXT,
  rollout_seconds REAL,
  verify_seconds REAL,
  falsify TEXT                      -- addition (v3): the cmt falsify --json object (without threads) or NULL
);
CREATE INDEX configs_status ON configs(status);
CREATE INDEX configs_task_strategy ON configs(task, strategy);
)sql";

// Version 2 -> 3 (ResultsStore migrates a version-2 file in place): the falsify columns. The units a
// version-2 database holds ran no search: their budgets are 0.
inline constexpr const char* kMigrate2To3 = R"sql(
ALTER TABLE configs ADD COLUMN falsify_budget INTEGER;
ALTER TABLE configs ADD COLUMN falsify_coverage_budget INTEGER;
ALTER TABLE metrics ADD COLUMN falsify TEXT;
UPDATE configs SET falsify_budget = 0, falsify_coverage_budget = 0;
)sql";

// Every column after the primary key config_id, in table order (merge copies them by name).
inline constexpr const char* kConfigColumns =
    "run_id, unit_key, task, task_file, task_yaml, strategy, params, n, seed, mode, status, finished, "
    "unit_index, sticking_trials, counterexample_budget, controller, falsify_budget, falsify_coverage_budget";
inline constexpr const char* kPredictionColumns =
    "reliable, failure, verify_seconds, verify_json, verifier_theta_v, verifier_model";
inline constexpr const char* kRolloutColumns =
    "rollout, motion, start_x, start_y, start_z, end_x, end_y, end_z, atom, termination, inside, distance, "
    "success, unstable";
inline constexpr const char* kMetricColumns =
    "rollouts, successes, unstable, ends, outside, soundness, coverage, coverage_radius, contact_tolerance, "
    "soundness_bug, counterexample, sticking, rollout_seconds, verify_seconds, falsify";

// UTC time as ISO 8601 with milliseconds, computed by SQLite.
inline constexpr const char* kNow = "strftime('%Y-%m-%dT%H:%M:%fZ', 'now')";

}  // namespace cmt::results_schema

#!/usr/bin/env bash
# The built-in planner runs of the main job (docs/planner.md "In the main job"): each `cmt plan --json`
# result written to DIR (default out/plan) for `cmt report --plan`, with the planned task (-o) and the
# planned strategy's physics check (MuJoCo rollouts, seed 1). Exit status 1 from cmt plan (no plan, not
# reliable under the verifier, or a failed rollout) is recorded in the JSON; 2 (bad input) stops.
set -uo pipefail
cd "$(dirname "$0")/.."
dir="${1:-out/plan}"
mkdir -p "$dir"

plan() {  # plan TASK LABEL [cmt plan options...]: writes LABEL.json and LABEL_planned.yaml
  local task="$1" label="$2"
  shift 2
  build/bin/cmt plan "models/tasks/$task.yaml" --json -o "$dir/${label}_planned.yaml" "$@" >"$dir/${label}.json" ||
    {
      status=$?
      echo "cmt plan $task failed with status $status" >&2
      [ "$status" -eq 2 ] && exit 2
    }
}

plan cube cube --check 100 --threads 2 --seed 1  # Buckley Sec 6.3.1: one motion that sticks on the cube bottom
plan hole hole --check 100 --threads 2 --seed 1  # Sec 6.3.3: stick on the far wall, then on the bottom
# Sec 6.3.2: stop by sensed position
plan cube_sensing cube_sensing --termination position --check 100 --threads 2 --seed 1
# Type 3 (Sec 6.7.6): stop by sensed position and force, anywhere on the cube bottom
plan cube cube_force --termination force --check 100 --threads 2 --seed 1
exit 0

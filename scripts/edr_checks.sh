#!/usr/bin/env bash
# The built-in EDR checks of the main job (docs/edr.md): each `cmt edr --json` result written to
# DIR/<task>_<strategy>.json (the report's Error detection and recovery section), the EDR-reliable ones with
# their physics check (1000 rollouts in 25 worlds drawn over the model parameters, extreme mode, seed 1). Exit status
# 1 from cmt edr (not EDR-reliable, or a forbidden outcome) is recorded in the JSON; 2 (bad input) stops.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-out/edr}
mkdir -p "$dir"
edr() {  # edr TASK STRATEGY [cmt edr options...]
  local task=$1 strategy=$2
  shift 2
  local status=0
  build/bin/cmt edr "models/tasks/$task.yaml" --strategy "$strategy" --json "$@" >"$dir/${task}_$strategy.json" ||
    status=$?
  if [ "$status" -gt 1 ]; then
    echo "cmt edr $task $strategy failed with status $status" >&2
    exit "$status"
  fi
  echo "edr $task $strategy: exit $status" >&2
}
edr step_offset edr --check 25 --per-world 40 --threads 2 --seed 1  # Donald's Example (1): EDR-reliable
edr step_offset steep   # may stop on the gap floor beside the goal: not EDR-reliable
edr hole_width edr --check 25 --per-world 40 --threads 2 --seed 1  # Donald's Example (6), the width: two motions

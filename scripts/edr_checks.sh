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
# LIMITED's planner (cmt plan-edr) on hole_width, two-motion plans (Algorithm Multi), then the plan's physics
# check (cmt validate --edr, 200 rollouts in 5 worlds: its rollouts slide the whole top where the hole is
# missing, 0.25 s each; docs/edr.md gives a 1000-rollout check), which the report reads like a cmt edr result.
mkdir -p "$dir/plans"
rm -f "$dir/hole_width_plan_edr.json"
status=0
build/bin/cmt plan-edr models/tasks/hole_width.yaml --min-motions 2 --json -o "$dir/plans/hole_width_planned.yaml" \
  >"$dir/plans/hole_width_plan.json" || status=$?
if [ "$status" -ne 0 ]; then
  echo "cmt plan-edr hole_width found no plan (status $status): see $dir/plans/hole_width_plan.json" >&2
  [ "$status" -eq 1 ] && exit 0
  exit "$status"
fi
build/bin/cmt validate "$dir/plans/hole_width_planned.yaml" --strategy plan_edr --edr -n 200 --per-world 40 \
  --mode extreme --threads 2 --seed 1 --json >"$dir/hole_width_plan_edr.json" || status=$?
if [ "$status" -gt 1 ]; then
  echo "cmt validate --edr on the planned hole_width failed with status $status" >&2
  exit "$status"
fi
echo "plan-edr hole_width, validate --edr: exit $status" >&2

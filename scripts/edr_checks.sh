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
edr twin_universe edr --check 25 --per-world 40 --threads 2 --seed 1  # Donald's Example (3): two steps
edr twin_universe one_step  # not EDR-reliable: no one-step EDR strategy
# LIMITED's planner (cmt plan-edr), two-motion plans (Algorithm Multi), then each plan's physics check (cmt
# validate --edr, 100 rollouts in 10 worlds: the planned rollouts slide long ways, 0.25 s each; docs/edr.md
# gives 1000-rollout checks), which the report reads like a cmt edr result.
mkdir -p "$dir/plans"
plan() {  # plan TASK [cmt plan-edr options...]
  local task=$1 status=0
  shift
  rm -f "$dir/${task}_plan_edr.json"
  build/bin/cmt plan-edr "models/tasks/$task.yaml" --min-motions 2 "$@" --json \
    -o "$dir/plans/${task}_planned.yaml" >"$dir/plans/${task}_plan.json" || status=$?
  if [ "$status" -ne 0 ]; then
    echo "cmt plan-edr $task found no plan (status $status): see $dir/plans/${task}_plan.json" >&2
    [ "$status" -eq 1 ] && return 0
    exit "$status"
  fi
  build/bin/cmt validate "$dir/plans/${task}_planned.yaml" --strategy plan_edr --edr -n 100 --per-world 10 \
    --mode extreme --threads 2 --seed 1 --json >"$dir/${task}_plan_edr.json" || status=$?
  if [ "$status" -gt 1 ]; then
    echo "cmt validate --edr on the planned $task failed with status $status" >&2
    exit "$status"
  fi
  echo "plan-edr $task, validate --edr: exit $status" >&2
}
plan hole_width
# twin_universe: its first EDR-reliable plan mostly signals failure in universe 1, so a guaranteed one; the
# first-order search takes 3 s (82 s under the rollouts' model), and the physics check tests the plan.
plan twin_universe --guaranteed --first-order

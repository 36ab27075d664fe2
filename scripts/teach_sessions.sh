#!/usr/bin/env bash
# The built-in teaching sessions of the main job (docs/teaching.md), each `cmt teach --json` result written to
# DIR/<session>.json (the report's Teaching sessions section) and each taught task to DIR/<session>.yaml; the
# solved teaching sessions' pre-images are checked by MuJoCo rollouts from their solved cells (extreme mode, seed 1).
# Then a damper chain's strong backprojection (`cmt backproject`), checked the same way from points of it, and a
# spring's (the via-point model; no rollout check: no controller form is bounded by that model yet).
# Exit status 1 from cmt teach (not solved, or a check failure) is recorded in the JSON; 2 (bad input) stops.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-out/teach}
mkdir -p "$dir"
teach() {  # teach NAME TASK [cmt teach options...]
  local name=$1 task=$2
  shift 2
  local status=0
  build/bin/cmt teach "models/tasks/$task.yaml" --session "models/sessions/$name.yaml" --json \
    -o "$dir/$name.yaml" --check-dir "$dir/${name}_cells" --view "$dir/${name}_view" --threads 2 --seed 1 "$@" \
    >"$dir/$name.json" || status=$?
  if [ "$status" -gt 1 ]; then
    echo "cmt teach $name failed with status $status" >&2
    exit "$status"
  fi
  echo "teach $name: exit $status" >&2
}
teach hole_teach hole --check 1000                # Buckley §5.2: (p2, p1)
teach hole_too_deep hole --depth 1                # p2 too deep: not solved, names the top face
teach tslot_teach tslot --depth 1 --check 300     # beyond the thesis: (m1, m2)
teach peg_in_hole_real_teach peg_in_hole_real --check 300  # §6.3.4's scaled hole: (p2, p1)
teach ridge_dispatch ridge --check 300            # Alg 5.1: down, then sense: right or stop
# Buckley Alg 5.2 for dampers: two_blocks' (v3, v2) backprojected from the goal, rollouts from 10 points of S.
status=0
build/bin/cmt backproject models/tasks/two_blocks.yaml --motions v3,v2 --check 10 --points 10 --seed 1 \
  --threads 2 --check-dir "$dir/two_blocks_backproject_points" --view "$dir/two_blocks_backproject_view" --json \
  >"$dir/two_blocks_backproject.json" || status=$?
if [ "$status" -gt 1 ]; then
  echo "cmt backproject failed with status $status" >&2
  exit "$status"
fi
echo "backproject two_blocks (v3, v2): exit $status" >&2
# Buckley §5.4.4 for a spring: block_shadow's spring below the floor, backprojected from the goal (3-D page).
status=0
build/bin/cmt backproject models/tasks/geometry/block_shadow.yaml --motions down \
  --view "$dir/block_shadow_backproject_view" --json >"$dir/block_shadow_backproject.json" || status=$?
if [ "$status" -gt 1 ]; then
  echo "cmt backproject failed with status $status" >&2
  exit "$status"
fi
echo "backproject block_shadow (down): exit $status" >&2

#!/usr/bin/env bash
# Set up, build and run the main job (README quick start, command 1): the default validation suite
# (experiments/sweeps/default.yaml: every built-in task and strategy, the verifier against 1000 MuJoCo
# rollouts each) into out/results.sqlite, then the report out/report/index.html. Rerunning resumes: units
# already in the database are skipped (docs/sweeps.md). The built-in teaching sessions (scripts/teach_sessions.sh,
# docs/teaching.md), EDR checks (scripts/edr_checks.sh, docs/edr.md) and planner runs (scripts/plan_checks.sh,
# docs/planner.md) join the report.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
start=$(date +%s)
build/bin/cmt sweep experiments/sweeps/default.yaml --db out/results.sqlite
bash scripts/teach_sessions.sh out/teach
bash scripts/edr_checks.sh out/edr
bash scripts/plan_checks.sh out/plan
build/bin/cmt report out/results.sqlite -o out/report --teach out/teach/*.json --edr out/edr/*.json \
  --plan out/plan/*.json
echo "Main job done in $(($(date +%s) - start)) s (sweep + report)." >&2
echo "Report: $(pwd)/out/report/index.html" >&2

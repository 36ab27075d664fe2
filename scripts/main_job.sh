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
# The teaching sessions and the EDR checks are independent and partly single-threaded: side by side they
# keep both cores busy. Each writes its own folder and runs in its own process group, which is killed if the
# job stops early (a rerun must not meet a writer left over); the larger exit status of the two is the job's.
set -m
bash scripts/teach_sessions.sh out/teach &
teach_pid=$!
bash scripts/edr_checks.sh out/edr &
edr_pid=$!
set +m
trap 'kill -- -"$teach_pid" -"$edr_pid" 2>/dev/null || true' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
teach_status=0 edr_status=0
wait "$teach_pid" || teach_status=$?
wait "$edr_pid" || edr_status=$?
trap - EXIT INT TERM
if [ "$teach_status" -ne 0 ] || [ "$edr_status" -ne 0 ]; then
  echo "main job: teaching sessions exit $teach_status, EDR checks exit $edr_status" >&2
  exit $((teach_status > edr_status ? teach_status : edr_status))
fi
bash scripts/plan_checks.sh out/plan
build/bin/cmt report out/results.sqlite -o out/report --teach out/teach/*.json --edr out/edr/*.json \
  --plan out/plan/*.json
echo "Main job done in $(($(date +%s) - start)) s (sweep + report)." >&2
echo "Report: $(pwd)/out/report/index.html" >&2

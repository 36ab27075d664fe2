#!/usr/bin/env bash
# Set up, build and run the main job (README quick start, command 1): `cmt info` on every built-in task.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
for task in models/tasks/*.yaml; do
  echo "== $task" >&2
  build/bin/cmt info "$task" --json | tee "out/info_$(basename "$task" .yaml).json"
done
echo "Results written to out/info_*.json" >&2

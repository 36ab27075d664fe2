#!/usr/bin/env bash
# Set up, build and run every test (README quick start, command 2).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j2

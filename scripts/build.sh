#!/usr/bin/env bash
# Configures and builds cmt in ./build (Release). Extra arguments are passed to the configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build -j2

#!/usr/bin/env bash
# Configures and builds tissuemesh (Release) into build/ with 2 parallel jobs.
#   bash scripts/build.sh              everything: libraries, program, tests, examples, benchmarks
#   bash scripts/build.sh tissuemesh   only the program and the libraries it links (no test compiled)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
JOBS=${JOBS:-2}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release
if [ $# -gt 0 ]; then
  cmake --build "$BUILD_DIR" -j "$JOBS" --target "$@"
else
  cmake --build "$BUILD_DIR" -j "$JOBS"
fi

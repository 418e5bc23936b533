#!/usr/bin/env bash
# Quick start 2: install what is missing, build, run the whole test suite (unit, examples,
# black-box CLI, slow meshing tests included).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
cd build
ctest --output-on-failure -j 2 --timeout 900

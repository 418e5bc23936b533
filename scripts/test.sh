#!/usr/bin/env bash
# Quick start 2: install what is missing, build, run the whole test suite (unit, examples,
# black-box CLI, slow meshing tests included).
#   bash scripts/test.sh              Release build in build/, every test
#   bash scripts/test.sh --sanitize   AddressSanitizer + UndefinedBehaviorSanitizer build in
#                                     build-asan/, the tests labelled for it (docs/reliability.md)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if [ "${1:-}" = "--sanitize" ]; then
  exec bash scripts/sanitize.sh
fi
bash scripts/build.sh
cd build
ctest --output-on-failure -j 2 --timeout 900

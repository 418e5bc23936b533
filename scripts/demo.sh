#!/usr/bin/env bash
# Quick start 1: install what is missing, build the program (no tests), run `tissuemesh demo` on the
# built-in phantom. Output goes to ./tissuemesh-demo (or the folder given as first argument).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh tissuemesh
./build/app/tissuemesh demo --out "${1:-tissuemesh-demo}"

#!/bin/sh
# Checks that scripts/demo.sh builds only the program: the targets it hands to scripts/build.sh
# must need no test source, no GoogleTest and no example (ninja lists every command they need).
# Usage: check_demo_build.sh SOURCE_DIR BUILD_DIR
set -eu
src=$1; build=$2
line=$(grep -E '^[^#]*scripts/build\.sh' "$src/scripts/demo.sh") || { echo "demo.sh does not call scripts/build.sh"; exit 1; }
targets=$(echo "$line" | sed -E 's/.*scripts\/build\.sh//')
[ -n "$(echo "$targets" | tr -d ' ')" ] || { echo "demo.sh builds everything (no target given to build.sh)"; exit 1; }
commands=$(ninja -C "$build" -t commands $targets)
[ -n "$commands" ] || { echo "ninja lists no command for: $targets"; exit 1; }
if echo "$commands" | grep -E '/tests/|gtest|/examples/' > /dev/null; then
  echo "demo.sh's build ($targets) compiles or links tests:"
  echo "$commands" | grep -E '/tests/|gtest|/examples/' | head -5
  exit 1
fi
echo "demo.sh builds $targets: $(echo "$commands" | wc -l) commands, none for a test"

#!/bin/sh
# The input class that once crashed the surface pipeline (a segmentation fault after the last
# remeshing round): a fragmented label map (tests/cli/inputs/fragmented_labels.py, 64^3 voxels of
# 0.5 mm, thousands of fgt islands, a two-voxel skin) meshed by the surface pipeline at two vertex
# budgets. Each run must end by itself: exit 0 with a mesh, or exit 1 or 2 with a message that
# names what to change, its reports written and no mesh; never a signal. Labelled cli only, so not
# in the sanitizer run: instrumented, its two surface-pipeline runs take several minutes.
# Usage: surface_on_fragmented_map.sh TISSUEMESH PYTHON3 SOURCE_DIR WORK_DIR
set -u
exe=$1; py=$2; src=$3; work=$4
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
"$py" "$src/tests/cli/inputs/fragmented_labels.py" 64 0.5 labels.nii.gz 1 > /dev/null || fail "generator"
for budget in 6000 21000; do
  sed "s/@BUDGET@/$budget/" "$src/tests/cli/inputs/fragmented-surface.yaml" > "surface_$budget.yaml"
  "$exe" mesh labels.nii.gz -c "surface_$budget.yaml" -o "out_$budget" --no-html > "log_$budget.txt" 2> "err_$budget.txt"
  rc=$?
  [ "$rc" -lt 128 ] || fail "budget $budget: killed by signal $((rc - 128)): $(tail -5 "log_$budget.txt")"
  case "$rc" in
    0) [ -f "out_$budget/mesh.vtu" ] || fail "budget $budget: exit 0 without mesh.vtu";;
    1|2)
      [ ! -e "out_$budget/mesh.vtu" ] || fail "budget $budget: exit $rc but mesh.vtu written"
      grep -q "surface\.\(target_vertices\|min_island_voxels\)" "err_$budget.txt" ||
        fail "budget $budget: exit $rc without naming what to change: $(cat "err_$budget.txt")";;
    *) fail "budget $budget: exit $rc: $(cat "err_$budget.txt")";;
  esac
  if [ "$rc" = 1 ]; then
    [ -f "out_$budget/report.json" ] || fail "budget $budget: exit 1 and no report.json"
  fi
  echo "budget $budget: exit $rc: $(cat "err_$budget.txt")"
done

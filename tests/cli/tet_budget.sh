#!/bin/sh
# `tissuemesh mesh` with direct.target_tets on a fragmented label map (tests/cli/inputs/
# fragmented_labels.py, 64^3 voxels of 0.5 mm, seed 1): a budget the map can meet is met within
# 10 % (report.json's sizes_from_image agrees with the mesh), the run conforms and exits 0; a
# budget below what its components need exits 2 with a message naming direct.target_tets and a
# larger budget, and leaves no output folder behind.
# Usage: tet_budget.sh TISSUEMESH PYTHON3 SOURCE_DIR WORK_DIR
set -u
exe=$1; py=$2; src=$3; work=$4
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
"$py" "$src/tests/cli/inputs/fragmented_labels.py" 64 0.5 labels.nii.gz 1 > /dev/null || fail "generator"
for budget in 150000 2000; do
  sed "s/BUDGET/$budget/" "$src/tests/cli/inputs/fragmented-budget.yaml" > "budget_$budget.yaml"
  "$exe" mesh labels.nii.gz -c "budget_$budget.yaml" -o "out_$budget" > "log_$budget.txt" 2> "err_$budget.txt"
  rc=$?
  case "$budget:$rc" in
    150000:0)
      "$py" - "out_$budget/report.json" "$budget" <<'PY' || fail "budget $budget: report"
import json, sys
r = json.load(open(sys.argv[1]))['result']
budget = int(sys.argv[2])
z = r['sizes_from_image']
assert z['target_tets'] == budget, z
assert z['tets'] == r['tets'], (z['tets'], r['tets'])
assert abs(r['tets'] / budget - 1) <= 0.10, r['tets']
assert 1 <= len(z['refinements']) <= 4, z['refinements']
assert r['conforming'], r['conformity']
print(f"budget {budget}: {r['tets']} tets ({100 * (r['tets'] / budget - 1):+.1f} %) in {len(z['refinements'])} refinement(s)")
PY
      ;;
    2000:2)
      [ ! -e "out_$budget" ] || fail "budget $budget: refused but out_$budget exists"
      grep -q "direct.target_tets: a budget of 2000 tets cannot be met" "err_$budget.txt" || fail "message: $(cat "err_$budget.txt")"
      grep -q "raise direct.target_tets to at least" "err_$budget.txt" || fail "message: $(cat "err_$budget.txt")"
      echo "budget $budget: refused, exit 2: $(cat "err_$budget.txt")";;
    *) fail "budget $budget: exit $rc: $(cat "err_$budget.txt")";;
  esac
done

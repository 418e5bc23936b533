#!/bin/sh
# A run either writes a conforming mesh and exits 0, or writes no mesh, keeps its reports (which
# name the failed counts and where the defects are) and exits 1. Never "conforming: NO" with
# exit 0. Input: fragmented label maps (tests/cli/inputs/fragmented_labels.py) for a few seeds,
# whose raw meshes pinch the outer boundary at edges: with the default repair every run must
# write a conforming mesh; with the repair off (fragmented-unrepaired.yaml) every run must fail.
# Usage: never_a_bad_mesh.sh TISSUEMESH PYTHON3 SOURCE_DIR WORK_DIR
set -u
exe=$1; py=$2; src=$3; work=$4
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
for item in 1:fragmented 2:fragmented 3:fragmented 1:fragmented-unrepaired; do
  seed=${item%%:*}; cfg=${item#*:}
  [ -f "labels_$seed.nii.gz" ] ||
    "$py" "$src/tests/cli/inputs/fragmented_labels.py" 64 0.5 "labels_$seed.nii.gz" "$seed" > /dev/null || fail "generator"
  run=$seed-$cfg
  "$exe" mesh "labels_$seed.nii.gz" -c "$src/tests/cli/inputs/$cfg.yaml" -o "out_$run" > "log_$run.txt" 2> "err_$run.txt"
  rc=$?
  case "$cfg:$rc" in
    fragmented:0|fragmented-unrepaired:1) ;;
    *) fail "run $run: exit $rc: $(cat "err_$run.txt")";;
  esac
  [ -f "out_$run/report.json" ] || fail "run $run: exit $rc and no report.json"
  conforming=$("$py" -c "import json,sys; print(json.load(open(sys.argv[1]))['result']['conformity']['conforming'])" "out_$run/report.json")
  defects=$("$py" -c "import json,sys; print(len(json.load(open(sys.argv[1]))['result']['conformity']['defects']))" "out_$run/report.json")
  case "$rc:$conforming" in
    0:True)
      [ -f "out_$run/mesh.vtu" ] || fail "run $run: exit 0 without mesh.vtu"
      opened=$("$py" -c "import json,sys; print(json.load(open(sys.argv[1]))['result']['boundary_pinches_opened']['edges'])" "out_$run/report.json")
      [ "$opened" -gt 0 ] || fail "run $run: the input no longer pinches; the test needs a harder one"
      [ "$defects" = 0 ] || fail "run $run: conforming with $defects defects listed";;
    1:False)
      [ ! -e "out_$run/mesh.vtu" ] || fail "run $run: a non-conforming mesh.vtu was written"
      [ "$defects" -gt 0 ] || fail "run $run: non-conforming but no defect located"
      grep -q "where (first" "out_$run/report.txt" || fail "run $run: report.txt does not say where"
      grep -q "meshing failed: the tet mesh does not conform" "err_$run.txt" || fail "run $run: message: $(cat err_$run.txt)";;
    *) fail "run $run: exit $rc with conforming=$conforming";;
  esac
  echo "run $run: exit $rc, conforming $conforming, $defects defects located, ${opened:-0} pinched edges opened"
  opened=
done

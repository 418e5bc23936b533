#!/bin/sh
# A junction curve on a face of the image (tests/cli/inputs/face-junction-surface.yaml): a split
# whose midpoint, projected onto the curve, passed the far side of its triangle once left two
# triangles of one patch folded flat onto each other there; TetGen read the pair as intersecting,
# stopped, and crashed while it unwound (exit 139; exit 1 once TetGen ran in a child process).
# The run must end with exit 0 and a conforming mesh with no dihedral angle under 10 degrees.
# Labelled cli only (not in the sanitizer run).
# Usage: surface_on_face_junction.sh TISSUEMESH PYTHON3 SOURCE_DIR WORK_DIR
set -u
exe=$1; py=$2; src=$3; work=$4
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
"$exe" phantom -c "$src/configs/hard-breast.yaml" --seed 2 --out breast.nii.gz > /dev/null || fail "phantom"
"$py" "$src/tests/cli/inputs/crop_labels.py" breast.nii.gz piece.nii.gz 2.7 -39 -31.3 14 || fail "crop"
"$exe" mesh piece.nii.gz -c "$src/tests/cli/inputs/face-junction-surface.yaml" -o out --no-html > log.txt 2> err.txt
rc=$?
[ "$rc" = 0 ] || fail "exit $rc: $(cat err.txt)"
grep -q "^conforming: yes" out/report.txt || fail "not conforming: $(grep -A3 'where (first' out/report.txt)"
"$py" - out/report.json <<'PY' || fail "angles"
import json, sys
r = json.load(open(sys.argv[1]))["result"]["volume_mesh"]
worst = min(t["min_dihedral_deg"] for t in r["quality"]["tissues"])
print(f"min dihedral {worst:.2f} deg")
sys.exit(1 if worst < 10 else 0)
PY
echo "ok: $(grep -E '^all tissues' out/report.txt)"

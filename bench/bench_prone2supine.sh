#!/usr/bin/env bash
# Benchmark of `tissuemesh prone2supine` on the default phantom against a known truth, and its cost
# as a ratio to one forward prone solve of the same mesh measured in the same run.
#
# Truth: the default phantom meshed with configs/phantom.yaml (tet4, node order of the mesh) is
# taken as the unloaded state X*; `solve` under prone gravity gives x = phi(X*) (prone.vtu, made
# by bench/vtu_points.cpp) and `solve` under supine gravity the true supine shape. prone2supine on
# prone.vtu must give X* back (reference.vtu) and the true supine shape (supine.vtu). Naive
# reversal is the same command stopped after its first iterate (max_iterations: 1).
# Cost: RUNS alternating runs of `solve prone.vtu` and `prone2supine prone.vtu` (OMP_NUM_THREADS=2),
# wall time and peak memory by GNU time; the ratio of the medians.
# Usage: bench/bench_prone2supine.sh [runs] (default 5; after scripts/build.sh). Prints a Markdown
# table for bench/RESULTS.md.
set -euo pipefail
source "$(dirname "$0")/common.sh"
RUNS=${1:-5}
POINTS=./build/bench/vtu_points
export OMP_NUM_THREADS=2
log() { echo "[bench_prone2supine] $*" >&2; }
measure() { local out=$1; shift; /usr/bin/time -f "%e %M" -o "$out" "$@"; }

sed -e "s#preset: materials/#preset: $PWD/configs/materials/#" -e "s#node_order: rcm#node_order: mesh#" \
  configs/phantom.yaml > "$WORK/prone.yaml"
sed -e "s#gravity: {direction: prone#gravity: {direction: supine#" "$WORK/prone.yaml" > "$WORK/supine.yaml"
{ cat "$WORK/prone.yaml"; echo "prone2supine: {max_iterations: 1}"; } > "$WORK/naive.yaml"

log "truth: mesh, prone and supine solves ..."
$EXE mesh "$WORK/phantom.nii.gz" -c "$WORK/prone.yaml" -o "$WORK/truth" > /dev/null
$EXE solve "$WORK/truth/mesh.vtu" -c "$WORK/prone.yaml" -o "$WORK/truth_prone" > /dev/null
$EXE solve "$WORK/truth/mesh.vtu" -c "$WORK/supine.yaml" -o "$WORK/truth_supine" > /dev/null
$POINTS deform "$WORK/truth/mesh.vtu" "$WORK/truth_prone/solution.vtu" "$WORK/prone.vtu"
$EXE prone2supine "$WORK/prone.vtu" -c "$WORK/naive.yaml" -o "$WORK/naive" > /dev/null 2>&1 || true

: > "$WORK/solve.times"; : > "$WORK/p2s.times"
run_solve() {
  rm -rf "$WORK/solve"
  measure "$WORK/t" $EXE solve "$WORK/prone.vtu" -c "$WORK/prone.yaml" -o "$WORK/solve" > /dev/null
  cat "$WORK/t" >> "$WORK/solve.times"; log "run $1: solve        $(cut -d' ' -f1 "$WORK/t") s"
}
run_p2s() {
  rm -rf "$WORK/p2s"
  measure "$WORK/t" $EXE prone2supine "$WORK/prone.vtu" -c "$WORK/prone.yaml" -o "$WORK/p2s" > /dev/null
  cat "$WORK/t" >> "$WORK/p2s.times"; log "run $1: prone2supine $(cut -d' ' -f1 "$WORK/t") s"
}
for i in $(seq "$RUNS"); do
  if (( i % 2 )); then run_solve "$i"; run_p2s "$i"; else run_p2s "$i"; run_solve "$i"; fi
done

ref_err=$($POINTS distance "$WORK/truth/mesh.vtu" "$WORK/p2s/reference.vtu")
sup_err=$($POINTS distance "$WORK/truth_supine/solution.vtu:displacement" "$WORK/p2s/supine.vtu")
naive_ref=$($POINTS distance "$WORK/truth/mesh.vtu" "$WORK/naive/reference.vtu")
naive_sup=$($POINTS distance "$WORK/truth_supine/solution.vtu:displacement" "$WORK/naive/supine.vtu")
sag=$($POINTS distance "$WORK/truth/mesh.vtu" "$WORK/prone.vtu")
motion=$($POINTS distance "$WORK/prone.vtu" "$WORK/truth_supine/solution.vtu:displacement")
col() { awk -v c="$2" '{print $c}' "$1"; }
s_med=$(col "$WORK/solve.times" 1 | median); p_med=$(col "$WORK/p2s.times" 1 | median)
s_mem=$(col "$WORK/solve.times" 2 | median); p_mem=$(col "$WORK/p2s.times" 2 | median)
read -r tets solves mismatch naive_mismatch < <(python3 -c "
import json; j = json.load(open('$WORK/p2s/prone2supine.json')); r = j['reference_state']
print(j['model']['elements'], r['forward_solves'], r['mismatch_mm'], r['naive_reversal']['mismatch_mm'])")

echo "runs: $RUNS; load average after: $(uptime | sed 's/.*load average: //')"
echo
echo "| mesh | prone sag / prone-to-supine motion, max [mm] | reference error, max [mm] | supine error, max [mm] | naive reversal: reference / supine error [mm] | forward solves (mismatch [mm]) | solve median [s] | prone2supine median [s] | ratio | peak memory solve / prone2supine [MiB] |"
echo "|---|---|---|---|---|---|---|---|---|---|"
printf "| default phantom, %s tet4 | %.2f / %.2f | %.4f | %.4f | %.3f / %.3f | %s (%.4f; naive %.3f) | %.2f | %.2f | %.2f | %.0f / %.0f |\n" \
  "$tets" "$sag" "$motion" "$ref_err" "$sup_err" "$naive_ref" "$naive_sup" "$solves" "$mismatch" "$naive_mismatch" \
  "$s_med" "$p_med" "$(awk -v a="$p_med" -v b="$s_med" 'BEGIN {print a / b}')" \
  "$(awk -v k="$s_mem" 'BEGIN {print k / 1024}')" "$(awk -v k="$p_mem" 'BEGIN {print k / 1024}')"

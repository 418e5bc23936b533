#!/usr/bin/env bash
# Benchmark of `tissuemesh mesh` on the default phantom at three resolutions: median wall time and
# peak memory over N runs (default 5), each after one run of the fixed machine reference
# (bench/machine_reference.cpp), whose median is given with the wall time's ratio to it.
# Usage: bench/bench_mesh.sh [runs] (after scripts/build.sh). Prints a Markdown table for
# bench/RESULTS.md. Needs python3 (reads report.json).
set -euo pipefail
RUNS=${1:-5}
source "$(dirname "$0")/common.sh"

echo "| config | tets | nodes | wall time median [s] (min-max) | peak memory median [MiB] | min dihedral [deg] | tets < 10 deg | machine reference median [s] | wall time / reference |"
echo "|---|---|---|---|---|---|---|---|---|"
for cfg in bench/configs/coarse-3tissues.yaml configs/phantom.yaml bench/configs/fine.yaml; do
  : > "$WORK/times"; : > "$WORK/mem"; : > "$WORK/ref"
  for i in $(seq "$RUNS"); do
    reference_timed "$WORK/ref"
    mesh_timed "$cfg" "$WORK/times"
    python3 -c "import json,sys; print(json.load(open('$WORK/out/report.json'))['peak_memory_mib'])" >> "$WORK/mem"
  done
  read -r tets nodes mind below < <(python3 -c "
import json; r=json.load(open('$WORK/out/report.json'))['result']; t=r['quality']['total']
print(r['tets'], r['nodes'], round(t['min_dihedral_deg'],2), t['tets_below_10deg'])")
  t_med=$(median < "$WORK/times"); t_min=$(sort -g "$WORK/times" | head -1); t_max=$(sort -g "$WORK/times" | tail -1)
  m_med=$(median < "$WORK/mem"); r_med=$(median < "$WORK/ref")
  printf "| %s | %s | %s | %.2f (%.2f-%.2f) | %.0f | %s | %s (%.3f%%) | %.3f | %.2f |\n" "$cfg" "$tets" "$nodes" "$t_med" "$t_min" \
    "$t_max" "$m_med" "$mind" "$below" "$(awk -v b="$below" -v t="$tets" "BEGIN {print 100 * b / t}")" "$r_med" \
    "$(awk -v t="$t_med" -v r="$r_med" "BEGIN {print t / r}")"
done

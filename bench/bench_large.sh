#!/usr/bin/env bash
# Benchmark of the direct pipeline on a large fragmented label map: the fragmented breast at
# 0.25 mm in an 80 mm cube (32.8 M voxels, ~3,600 components; bench/configs/large-fragmented.yaml)
# meshed to a budget of 300,000 tets with sizes from the image. Median wall time and peak memory
# over N runs (default 3), each after one run of the machine reference; tets against the budget,
# min dihedral and per-tissue volume error of the last run.
# Usage: bench/bench_large.sh [runs] (after scripts/build.sh). Prints Markdown for bench/RESULTS.md.
set -euo pipefail
RUNS=${1:-3}
source "$(dirname "$0")/common.sh"
CFG=bench/configs/large-fragmented.yaml
$EXE phantom -c "$CFG" --out "$WORK/large.nii.gz" > /dev/null
: > "$WORK/times"; : > "$WORK/mem"; : > "$WORK/ref"
for i in $(seq "$RUNS"); do
  reference_timed "$WORK/ref"
  rm -rf "$WORK/out"
  start=$(date +%s.%N)
  $EXE mesh "$WORK/large.nii.gz" -c "$CFG" -o "$WORK/out" > /dev/null
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" "BEGIN {print b - a}" >> "$WORK/times"
  python3 -c "import json; print(json.load(open('$WORK/out/report.json'))['peak_memory_mib'])" >> "$WORK/mem"
done
t_med=$(median < "$WORK/times"); m_med=$(median < "$WORK/mem"); r_med=$(median < "$WORK/ref")
python3 - "$WORK/out/report.json" "$t_med" "$m_med" "$r_med" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))['result']
t, m, ref = float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
z = r['sizes_from_image']
q = r['quality']
print("| voxels | components kept | tets (budget 300,000) | wall time median [s] | / reference | peak memory [MiB] | min dihedral [deg] | tets < 10 deg |")
print("|---|---|---|---|---|---|---|---|")
print(f"| 32,768,000 | {r['components_meshed']} | {r['tets']:,} ({z['off_target_percent']:+.1f} %) | {t:.1f} | {t / ref:.1f} | {m:.0f} | "
      f"{q['total']['min_dihedral_deg']:.2f} | {q['total']['tets_below_10deg']} |")
print()
print("| tissue | volume error [%] |")
print("|---|---|")
for s in q['tissues']:
    print(f"| {s['name']} | {100 * (s['volume_mm3'] / s['reference_volume_mm3'] - 1):+.2f} |")
PY

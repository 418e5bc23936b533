#!/usr/bin/env bash
# Benchmark of `tissuemesh sweep`: 32 Latin-hypercube samples over three parameters (the fat's
# shear modulus, log scale; the tumour's Young's modulus; the FGT's shear modulus as a ratio to the
# fat's) on the default demo mesh (configs/phantom.yaml, 100,081 tet4), against one cold
# `tissuemesh solve` of the same mesh, measured in the same run: the mean wall time per sample as a
# ratio to the cold solve. RUNS repetitions (median), each: one cold solve, the sweep with --jobs 1,
# the sweep with --jobs 2 (one assembly thread each). OMP_NUM_THREADS=2.
# Usage: bench/bench_sweep.sh [runs] (default 3; after scripts/build.sh). Prints a Markdown table.
set -euo pipefail
source "$(dirname "$0")/common.sh"
RUNS=${1:-3}
export OMP_NUM_THREADS=2
log() { echo "[bench_sweep] $*" >&2; }
sed -e "s#preset: materials/#preset: $PWD/configs/materials/#" configs/phantom.yaml > "$WORK/phantom.yaml"
cat > "$WORK/lhs.yaml" <<'YAML'
parameters:
  materials.fat.mu: {range: [100 Pa, 300 Pa], scale: log}
  materials.tumor.E: {range: [5 kPa, 50 kPa], scale: log}
  materials.fgt.mu: {ratio_to: materials.fat.mu, range: [1, 4]}
design: {type: lhs, samples: 32, seed: 1}
YAML
log "mesh ..."
$EXE mesh "$WORK/phantom.nii.gz" -c "$WORK/phantom.yaml" -o "$WORK/mesh" > /dev/null
elapsed() { local s e; s=$(date +%s.%N); "$@" > /dev/null; e=$(date +%s.%N); awk -v a="$s" -v b="$e" 'BEGIN {print b - a}'; }
: > "$WORK/cold"; : > "$WORK/j1"; : > "$WORK/j2"
for i in $(seq "$RUNS"); do
  rm -rf "$WORK/solve" "$WORK/s1" "$WORK/s2"
  t=$(elapsed $EXE solve "$WORK/mesh/mesh.vtu" -c "$WORK/phantom.yaml" -o "$WORK/solve"); echo "$t" >> "$WORK/cold"
  log "run $i: cold solve $t s"
  t=$(elapsed $EXE sweep "$WORK/mesh/mesh.vtu" -c "$WORK/phantom.yaml" --sweep "$WORK/lhs.yaml" -o "$WORK/s1" --jobs 1)
  echo "$t" >> "$WORK/j1"; log "run $i: sweep --jobs 1: $t s"
  t=$(elapsed $EXE sweep "$WORK/mesh/mesh.vtu" -c "$WORK/phantom.yaml" --sweep "$WORK/lhs.yaml" -o "$WORK/s2" --jobs 2 --threads 1)
  echo "$t" >> "$WORK/j2"; log "run $i: sweep --jobs 2: $t s"
done
cold=$(median < "$WORK/cold"); j1=$(median < "$WORK/j1"); j2=$(median < "$WORK/j2")
read -r conv iters warm < <(python3 -c "
import json
rows = [json.loads(l) for l in open('$WORK/s1/results.jsonl')]
print(sum(r['converged'] for r in rows), sum(r['newton_iterations'] for r in rows) / len(rows),
      sum(r['warm_from'] >= 0 for r in rows))")
cold_iters=$(python3 -c "import json; print(json.load(open('$WORK/solve/solve.json'))['solver']['total_iterations'])")
echo "runs: $RUNS; load average after: $(uptime | sed 's/.*load average: //')"
echo
echo "| mesh | cold solve median [s] | 32 samples, --jobs 1 [s] | per sample / cold | 32 samples, --jobs 2 x 1 thread [s] | per sample / cold | converged | Newton iterations per sample (cold solve) | warm-started samples |"
echo "|---|---|---|---|---|---|---|---|---|"
printf "| default phantom, 100,081 tet4 | %.2f | %.1f | %.3f | %.1f | %.3f | %s / 32 | %.1f (%s) | %s |\n" "$cold" "$j1" \
  "$(awk -v a="$j1" -v c="$cold" 'BEGIN {print a / 32 / c}')" "$j2" "$(awk -v a="$j2" -v c="$cold" 'BEGIN {print a / 32 / c}')" \
  "$conv" "$iters" "$cold_iters" "$warm"

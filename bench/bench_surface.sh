#!/usr/bin/env bash
# Benchmark of the surface pipeline (issue #5) on the default phantom with configs/paper-21k.yaml and paper-2k.yaml:
# median over N runs (default 5) of the extraction (label check + repair + surface nets) and of the
# remeshing stage, from each run's report.json timings, and of the whole command's wall time (which
# also includes reading, the Hausdorff measurement and writing). The issue's target: extraction +
# remeshing under 5 s. Usage: bench/bench_surface.sh [runs] (after scripts/build.sh). Prints a
# Markdown table for bench/RESULTS.md. Needs python3.
set -euo pipefail
RUNS=${1:-5}
source "$(dirname "$0")/common.sh"

echo "| config | vertices | extraction median [s] | remeshing median [s] | extraction + remeshing median [s] (min-max) | whole command median [s] | peak memory median [MiB] |"
echo "|---|---|---|---|---|---|---|"
for cfg in configs/paper-21k.yaml configs/paper-2k.yaml; do
  : > "$WORK/ext"; : > "$WORK/rem"; : > "$WORK/sum"; : > "$WORK/wall"; : > "$WORK/mem"
  for i in $(seq "$RUNS"); do
    mesh_timed "$cfg" "$WORK/wall"
    python3 - "$WORK" <<'PY'
import json, sys
w = sys.argv[1]
r = json.load(open(w + "/out/report.json"))
t = {s["stage"]: s["seconds"] for s in r["timings"]}
ext = sum(v for k, v in t.items() if k in ("check labels", "repair non-manifold voxel configurations", "surface nets"))
rem = t["surface remeshing"]
for name, v in (("ext", ext), ("rem", rem), ("sum", ext + rem), ("mem", r["peak_memory_mib"])):
    open(w + "/" + name, "a").write(f"{v}\n")
open(w + "/vertices", "w").write(str(r["result"]["vertices"]))
PY
  done
  printf "| %s | %s | %.2f | %.2f | %.2f (%.2f-%.2f) | %.2f | %.0f |\n" "$cfg" "$(cat "$WORK/vertices")" \
    "$(median < "$WORK/ext")" "$(median < "$WORK/rem")" "$(median < "$WORK/sum")" \
    "$(sort -g "$WORK/sum" | head -1)" "$(sort -g "$WORK/sum" | tail -1)" "$(median < "$WORK/wall")" "$(median < "$WORK/mem")"
done

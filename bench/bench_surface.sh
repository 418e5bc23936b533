#!/usr/bin/env bash
# Benchmark of the surface pipeline (docs/surface-pipeline.md) on the default phantom with
# configs/paper-21k.yaml, paper-21k-tetgen.yaml (the surface kept by TetGen, with its volumes
# restored), paper-21k-budget.yaml (CGAL to 42,000 tets, volumes restored), paper-2k.yaml and
# paper-2k-budget.yaml (TetGen to 20,000 tets): median over N runs (default 5) of the extraction
# (label check + island absorption and repair + surface nets), of the remeshing (the stages
# "projection onto the extracted surface" and "surface remeshing") and of the volume meshing
# (CGAL Mesh_3 from the surface: pieces, protection, refinement and optimisation of every budget
# round, extraction, sliver repair, tet volume restoration; or volume restoration, TetGen and the
# sliver repair that keeps the surface), from each run's report.json timings (a stage run several
# times is summed), and of the whole command's wall time (which also includes reading, quality and
# Hausdorff measurements and writing). Speed goals: extraction + remeshing under 5 s;
# extraction + remeshing + volume under 10 s at 21K.
# Before each run the fixed machine reference (bench/machine_reference.cpp, about 1 s) runs once;
# the table gives its median, and extraction + remeshing and the whole command (labels to written
# mesh) as ratios to it (ratios of the medians), which compare runs on machines of different
# speed. Usage:
# bench/bench_surface.sh [runs] (after scripts/build.sh); CONFIGS="<config files>" runs only
# those. Prints a Markdown table for bench/RESULTS.md. Needs python3.
set -euo pipefail
RUNS=${1:-5}
source "$(dirname "$0")/common.sh"

echo "| config | vertices | tets | extraction median [s] | remeshing median [s] | extraction + remeshing median [s] (min-max) | volume median [s] | extraction + remeshing + volume median [s] | whole command median [s] | peak memory median [MiB] | machine reference median [s] | extraction + remeshing / reference | whole command / reference |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
for cfg in ${CONFIGS:-configs/paper-21k.yaml configs/paper-21k-tetgen.yaml configs/paper-21k-budget.yaml configs/paper-2k.yaml configs/paper-2k-budget.yaml}; do
  : > "$WORK/ext"; : > "$WORK/rem"; : > "$WORK/sum"; : > "$WORK/vol"; : > "$WORK/all"; : > "$WORK/wall"; : > "$WORK/mem"; : > "$WORK/ref"
  for i in $(seq "$RUNS"); do
    reference_timed "$WORK/ref"
    mesh_timed "$cfg" "$WORK/wall"
    python3 - "$WORK" <<'PY'
import json, sys
w = sys.argv[1]
r = json.load(open(w + "/out/report.json"))
t = {}
for s in r["timings"]:
    t[s["stage"]] = t.get(s["stage"], 0.0) + s["seconds"]
ext = sum(v for k, v in t.items() if k in ("check labels", "surface nets") or k.startswith("absorb islands"))
rem = t["surface remeshing"] + t.get("projection onto the extracted surface", 0.0)
vol = sum(v for k, v in t.items() if k in ("patch pieces", "domain and junction features", "protect junctions, seed pieces",
                                           "refine (CGAL Mesh_3)", "Lloyd", "ODT", "perturb slivers", "exude slivers",
                                           "extract mesh", "sliver repair", "tet volume restoration",
                                           "volume restoration", "TetGen volume mesh",
                                           "sliver repair inside the tissues"))
for name, v in (("ext", ext), ("rem", rem), ("sum", ext + rem), ("vol", vol), ("all", ext + rem + vol),
                ("mem", r["peak_memory_mib"])):
    open(w + "/" + name, "a").write(f"{v}\n")
open(w + "/vertices", "w").write(str(r["result"]["vertices"]))
open(w + "/tets", "w").write(str(r["result"]["volume_mesh"]["tets"]))
PY
  done
  printf "| %s | %s | %s | %.2f | %.2f | %.2f (%.2f-%.2f) | %.2f | %.2f | %.2f | %.0f | %.3f | %.2f | %.2f |\n" "$cfg" "$(cat "$WORK/vertices")" \
    "$(cat "$WORK/tets")" "$(median < "$WORK/ext")" "$(median < "$WORK/rem")" "$(median < "$WORK/sum")" \
    "$(sort -g "$WORK/sum" | head -1)" "$(sort -g "$WORK/sum" | tail -1)" "$(median < "$WORK/vol")" \
    "$(median < "$WORK/all")" "$(median < "$WORK/wall")" "$(median < "$WORK/mem")" "$(median < "$WORK/ref")" \
    "$(awk -v s="$(median < "$WORK/sum")" -v r="$(median < "$WORK/ref")" 'BEGIN {print s / r}')" \
    "$(awk -v s="$(median < "$WORK/wall")" -v r="$(median < "$WORK/ref")" 'BEGIN {print s / r}')"
done

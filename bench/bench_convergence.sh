#!/usr/bin/env bash
# Convergence study of the prone gravity solution on the default phantom (docs/convergence.md).
# For each surface vertex budget: `tissuemesh mesh` with configs/paper-21k-tetgen.yaml and
# `surface.target_vertices` replaced (TetGen keeps every surface triangle, so the budget sets the
# element count), then `tissuemesh solve` of that mesh twice with configs/phantom.yaml's
# `materials:` and `model:` (prone gravity, chest wall fixed): `model.element: tet10`, and tet4 with
# `model.analysis.tet4_pressure: nodal`. Per budget and element it reports tets, nodes, the solve's
# time (solve.json `solver.seconds`) and peak memory, max |u| and the tumour's centroid displacement
# (volume mean of u over the tumour, solve.json), each against the finest level of the same element
# and against a Richardson extrapolation of the three finest (bench/convergence_report.py).
#
# Usage: bench/bench_convergence.sh [budgets...]   (default 2100 5000 10000 21000 42000; after
#        scripts/build.sh)
# Environment:
#   EXE, REFERENCE       executable and machine reference (bench/common.sh; absolute paths)
#   TET10_MAX_VERTICES   tet10 is solved only at budgets up to this (default 21000: tet10 at 21K
#                        takes about half an hour and 7.5 GB on a 2-core machine, the factor's cost
#                        grows about as the square of the unknowns); 0 = every budget
#   THREADS              solve threads (default 2)
#   SVG                  where the plot goes (default docs/images/convergence.svg; empty: no plot)
#   PYTHON               Python 3 with PyYAML (default /usr/bin/python3)
#   KEEP=1               keep the work directory (its path is printed on stderr)
# Outputs: progress on stderr; on stdout the run's figures, a Markdown table of the solves and one
# of the meshes (for docs/convergence.md and bench/RESULTS.md); the SVG plot. The default budgets
# took 53 minutes on a loaded 2-core machine, 27 of them the tet10 solve at 21K. Exits 1 when a
# mesh or a solve fails (a solve that does not converge exits 1), naming it and showing the end
# of its log.
set -euo pipefail
BUDGETS=("$@")
[[ ${#BUDGETS[@]} -gt 0 ]] || BUDGETS=(2100 5000 10000 21000 42000)
TET10_MAX_VERTICES=${TET10_MAX_VERTICES:-21000}
THREADS=${THREADS:-2}
PYTHON=${PYTHON:-/usr/bin/python3}
source "$(dirname "$0")/common.sh"   # cd to the repository root, $EXE, $WORK with phantom.nii.gz
SVG=${SVG-docs/images/convergence.svg}
if [[ ${KEEP:-0} == 1 ]]; then trap - EXIT; echo "work directory: $WORK" >&2; fi
log() { echo "[bench_convergence] $*" >&2; }
now() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now)" 'BEGIN {printf "%.2f", b - a}'; }

# run LOG CMD...: CMD with its output in LOG; on failure the end of LOG and exit 1.
run() {
  local logfile=$1; shift
  "$@" > "$logfile" 2>&1 || { log "FAILED (exit $?): $*"; tail -20 "$logfile" >&2; exit 1; }
}

# derive_config OUT BUDGET [ELEMENT]: configs/paper-21k-tetgen.yaml with surface.target_vertices =
# BUDGET; with ELEMENT (tet10 | tet4-nodal) also configs/phantom.yaml's materials and model, the
# element set.
derive_config() {
  "$PYTHON" - "$@" <<'PY'
import sys, yaml
out, budget = sys.argv[1], int(sys.argv[2])
c = yaml.safe_load(open("configs/paper-21k-tetgen.yaml"))
c["surface"]["target_vertices"] = budget
if len(sys.argv) > 3:
    p = yaml.safe_load(open("configs/phantom.yaml"))
    c["materials"], c["model"] = p["materials"], p["model"]
    element = sys.argv[3]
    c["model"]["element"] = "tet10" if element == "tet10" else "tet4"
    c["model"]["analysis"]["tet4_pressure"] = "nodal" if element == "tet4-nodal" else "element"
yaml.safe_dump(c, open(out, "w"), sort_keys=False)
PY
}

start_all=$(now)
load_before=$(uptime | sed 's/.*load average: //')
exe_sum=$(sha1sum "$EXE" | cut -c1-12)
: > "$WORK/ref"
reference_timed "$WORK/ref"
: > "$WORK/records.jsonl"
for b in "${BUDGETS[@]}"; do
  d=$WORK/b$b
  mkdir -p "$d"
  derive_config "$d/mesh.yaml" "$b"
  log "budget $b: mesh ..."
  t0=$(now)
  run "$d/mesh.log" "$EXE" mesh "$WORK/phantom.nii.gz" -c "$d/mesh.yaml" -o "$d/mesh" --no-html
  mesh_s=$(elapsed "$t0")
  elements=(tet4-nodal)
  if [[ $TET10_MAX_VERTICES == 0 || $b -le $TET10_MAX_VERTICES ]]; then elements=(tet10 tet4-nodal); fi
  for el in "${elements[@]}"; do
    derive_config "$d/$el.yaml" "$b" "$el"
    log "budget $b: solve $el ..."
    t0=$(now)
    run "$d/$el.log" "$EXE" solve "$d/mesh/mesh.vtu" -c "$d/$el.yaml" -o "$d/$el" --threads "$THREADS" --no-html
    wall_s=$(elapsed "$t0")
    "$PYTHON" bench/convergence_report.py record "$d" "$b" "$el" "$mesh_s" "$wall_s" >> "$WORK/records.jsonl"
    log "budget $b: $el done in $wall_s s ($(tail -1 "$WORK/records.jsonl" | "$PYTHON" -c \
      'import json,sys; r=json.loads(sys.stdin.read()); print(r["tets"], "tets,", "tumour", round(r["tumor_u_magnitude_mm"], 4), "mm")'))"
  done
done
reference_timed "$WORK/ref"
load_after=$(uptime | sed 's/.*load average: //')
[[ $(sha1sum "$EXE" | cut -c1-12) == "$exe_sum" ]] || log "WARNING: $EXE changed during the study: rerun"

echo "tissuemesh binary sha1 $exe_sum; threads $THREADS; load average before: $load_before; after: $load_after;" \
  "machine reference $(head -1 "$WORK/ref") s before, $(tail -1 "$WORK/ref") s after; whole study $(elapsed "$start_all") s"
echo
"$PYTHON" bench/convergence_report.py table "$WORK/records.jsonl" ${SVG:+--svg "$SVG"}

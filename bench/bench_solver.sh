#!/usr/bin/env bash
# Benchmark of the built-in solver (`tissuemesh solve`) against CalculiX (`ccx`, 2 threads) on the
# same model: the default phantom meshed with bench/configs/solver-60k.yaml (~60K tet4), exported
# once as an Abaqus deck (uncoupled neo-Hookean tissues, chest wall fixed, prone gravity: the
# energy the built-in minimises). Each run executes both, one after the other, alternating which
# goes first; wall time and peak RSS are measured per process with GNU time (`/usr/bin/time -f`).
# Usage: bench/bench_solver.sh [runs] (default 3; after scripts/build.sh). Needs ccx and python3.
# Prints the load average before/after, then a Markdown table for bench/RESULTS.md (medians).
# KEEP=1 keeps the work directory (its path is printed on stderr).
set -euo pipefail
cd "$(dirname "$0")/.."
RUNS=${1:-3}
EXE=./build/app/tissuemesh
CFG=bench/configs/solver-60k.yaml
export OMP_NUM_THREADS=2
command -v ccx > /dev/null || { echo "ccx (CalculiX) not found" >&2; exit 1; }
WORK=$(mktemp -d)
if [[ ${KEEP:-0} == 1 ]]; then echo "work directory: $WORK" >&2; else trap 'rm -rf "$WORK"' EXIT; fi
log() { echo "[bench_solver] $*" >&2; }

# measure OUT CMD...: run CMD, write "wall_s peak_rss_KiB user_s sys_s" to OUT, return CMD's status.
if [[ -x /usr/bin/time ]]; then
  measure() { local out=$1; shift; /usr/bin/time -f "%e %M %U %S" -o "$out" "$@"; }
else
  log "/usr/bin/time (Debian package 'time') not found: measuring with python3 getrusage(RUSAGE_CHILDREN)"
  measure() {
    local out=$1; shift
    python3 - "$out" "$@" <<'EOF'
import resource, subprocess, sys, time
t = time.perf_counter(); rc = subprocess.call(sys.argv[2:]); wall = time.perf_counter() - t
r = resource.getrusage(resource.RUSAGE_CHILDREN)
open(sys.argv[1], "w").write("%.2f %d %.2f %.2f\n" % (wall, r.ru_maxrss, r.ru_utime, r.ru_stime))
sys.exit(rc)
EOF
  }
fi

load_before=$(uptime | sed 's/.*load average: //')
exe_sum=$(sha1sum "$EXE" | cut -c1-12)

log "phantom, mesh ($CFG), abaqus export ..."
$EXE phantom --out "$WORK/phantom.nii.gz" > /dev/null
$EXE mesh "$WORK/phantom.nii.gz" -c "$CFG" -o "$WORK/mesh" > /dev/null
$EXE export "$WORK/mesh/mesh.vtu" -c "$CFG" -o "$WORK/export" --format abaqus > /dev/null
MESH=$WORK/mesh/mesh.vtu

run_ccx() {
  rm -rf "$WORK/ccx"; mkdir "$WORK/ccx"; cp "$WORK/export/model.inp" "$WORK/ccx/"
  (cd "$WORK/ccx" && measure "$WORK/ccx.time" ccx -i model > ccx.log 2>&1) \
    || { log "ccx failed (run $1), see ccx.log:"; tail -20 "$WORK/ccx/ccx.log" >&2; exit 1; }
  grep -q "Job finished" "$WORK/ccx/ccx.log" || { log "ccx did not finish (run $1)"; exit 1; }
  cat "$WORK/ccx.time" >> "$WORK/ccx.times"
  log "run $1: ccx      $(cut -d' ' -f1 "$WORK/ccx.time") s, $(awk '{printf "%.0f", $2 / 1024}' "$WORK/ccx.time") MiB"
}
run_builtin() {
  rm -rf "$WORK/solve"
  measure "$WORK/solve.time" $EXE solve "$MESH" -c "$CFG" -o "$WORK/solve" > "$WORK/solve.log" 2>&1 \
    || { log "tissuemesh solve failed (run $1):"; tail -20 "$WORK/solve.log" >&2; exit 1; }
  cat "$WORK/solve.time" >> "$WORK/solve.times"
  python3 -c "
import json; s = json.load(open('$WORK/solve/solve.json'))
v = s['solver']
print(v['seconds'], v['increments_attempted'], v['total_iterations'], s['results']['max_displacement_mm'],
      v.get('assembly_seconds', 'n/a'), v.get('linear_solve_seconds', 'n/a'))" >> "$WORK/solve.stats"
  log "run $1: built-in $(cut -d' ' -f1 "$WORK/solve.time") s, $(awk '{printf "%.0f", $2 / 1024}' "$WORK/solve.time") MiB"
}

: > "$WORK/ccx.times"; : > "$WORK/solve.times"; : > "$WORK/solve.stats"
for i in $(seq "$RUNS"); do
  if (( i % 2 )); then run_ccx "$i"; run_builtin "$i"; else run_builtin "$i"; run_ccx "$i"; fi
done

# Both solutions of the last run: CalculiX's last displacement block of model.dat (node id =
# model node index + 1) against solution.vtu's point data `displacement` (same order).
compare() {
  python3 - "$WORK/ccx/model.dat" "$WORK/solve/solution.vtu" <<'EOF'
import base64, math, re, struct, sys, zlib
uc, cur = None, None
for line in open(sys.argv[1]):
    if line.lstrip().startswith("displacements"):
        cur = {}; uc = cur; continue
    f = line.split()
    if cur is not None and len(f) == 4 and f[0].isdigit():
        cur[int(f[0])] = [float(x) for x in f[1:]]
    elif cur is not None and f:
        cur = None
txt = open(sys.argv[2], "rb").read()   # appended data, base64, zlib blocks, UInt32 header
off = int(re.search(rb'<DataArray[^>]*Name="displacement"[^>]*offset="\s*(\d+)', txt).group(1))
npts = int(re.search(rb'NumberOfPoints="\s*(\d+)', txt).group(1))
data = txt[txt.index(b"_", txt.index(b"<AppendedData")) + 1 + off:]
nb = struct.unpack("<I", base64.b64decode(data[:16])[:4])[0]
hb = 4 * math.ceil(4 * (3 + nb) / 3)
sizes = struct.unpack("<%dI" % (3 + nb), base64.b64decode(data[:hb]))[3:]
body = base64.b64decode(data[hb:hb + 4 * math.ceil(sum(sizes) / 3)])
raw, p = b"", 0
for c in sizes:
    raw += zlib.decompress(body[p:p + c]); p += c
v = struct.unpack("<%dd" % (3 * npts), raw[:24 * npts])
assert len(uc) == npts, (len(uc), npts)
norm = lambda a: math.sqrt(sum(x * x for x in a))
mc = max(norm(u) for u in uc.values())
mb = max(norm(v[3 * i:3 * i + 3]) for i in range(npts))
d = [norm([a - b for a, b in zip(uc[i + 1], v[3 * i:3 * i + 3])]) for i in range(npts)]
print(mc, mb, max(d) / mc, sum(d) / npts / mc)
EOF
}
read -r ccx_umax own_bumax own_maxrel own_meanrel < <(compare)

log "tissuemesh check --calculix (once) ..."
$EXE check "$MESH" -c "$CFG" -o "$WORK/check" --calculix > "$WORK/check.log" 2>&1 \
  || { log "tissuemesh check failed:"; tail -20 "$WORK/check.log" >&2; exit 1; }
load_after=$(uptime | sed 's/.*load average: //')
[[ $(sha1sum "$EXE" | cut -c1-12) == "$exe_sum" ]] || log "WARNING: $EXE changed during the benchmark: rerun"

median() { sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}'; }
col() { awk -v c="$2" '{print $c}' "$1"; }   # column c of a times file
stat3() { local m; m=$(col "$1" "$2" | median); printf "%.2f (%.2f-%.2f)" "$m" "$(col "$1" "$2" | sort -g | head -1)" \
  "$(col "$1" "$2" | sort -g | tail -1)"; }
c_med=$(col "$WORK/ccx.times" 1 | median); b_med=$(col "$WORK/solve.times" 1 | median)
c_mem=$(col "$WORK/ccx.times" 2 | median); b_mem=$(col "$WORK/solve.times" 2 | median)
c_cpu=$(awk '{print $3 + $4}' "$WORK/ccx.times" | median); b_cpu=$(awk '{print $3 + $4}' "$WORK/solve.times" | median)
read -r tets nodes free threads lsolver incs iters fact shifted cg < <(python3 -c "
import json; s = json.load(open('$WORK/solve/solve.json')); v = s['solver']
print(s['model']['elements'], s['model']['nodes'], v['free_dofs'], v['threads'], v['linear_solver'].replace(' ', '_'),
      v['increments_attempted'], v['total_iterations'], v.get('factorisations', 'n/a'),
      v.get('shifted_factorisations', 'n/a'), v.get('preconditioned_cg_iterations', 'n/a'))")
read -r ck_c ck_b ck_maxrel ck_meanrel ck_ct ck_bt < <(python3 -c "
import json; c = json.load(open('$WORK/check/check.json'))['comparison']
print(c['max_u_mm_calculix'], c['max_u_mm_builtin'], c['max_diff_rel'], c['mean_diff_rel'], c['seconds_calculix'], c['seconds_builtin'])")
read -r ccx_incs ccx_iters < <(awk '$1 == 1 && NF == 7 {n++; it += $4} END {print n, it}' "$WORK/ccx/model.sta")
b_umax_all=$(awk '{print $4}' "$WORK/solve.stats" | sort -u | tr '\n' ' ')
b_solver_med=$(awk '{print $1}' "$WORK/solve.stats" | median | xargs printf "%.2f")
fmt2() { local m; m=$(median); if [[ $m =~ ^[0-9.eE+-]+$ ]]; then printf "%.2f" "$m"; else echo n/a; fi; }
b_asm_med=$(awk '{print $5}' "$WORK/solve.stats" | fmt2)
b_lin_med=$(awk '{print $6}' "$WORK/solve.stats" | fmt2)

echo "load average before: $load_before; after: $load_after; runs: $RUNS; tissuemesh binary sha1 $exe_sum; $(ccx -v 2>/dev/null | grep -i version | head -1 | sed 's/^ *//')"
echo
echo "| model (tets, nodes, dofs) | ccx wall median [s] (min-max) | ccx peak [MiB] | built-in wall median [s] (min-max) | built-in peak [MiB] | ratio ccx / built-in | max \|u\| ccx [mm] | max \|u\| built-in [mm] | max (mean) nodal diff / max \|u\| |"
echo "|---|---|---|---|---|---|---|---|---|"
printf "| %s tets, %s nodes, %s dofs (%s free) | %s | %.0f | %s | %.0f | %.2f | %.4f | %.4f | %.2e (%.2e) |\n" \
  "$tets" "$nodes" "$((3 * nodes))" "$free" "$(stat3 "$WORK/ccx.times" 1)" "$(awk -v k="$c_mem" 'BEGIN {print k / 1024}')" \
  "$(stat3 "$WORK/solve.times" 1)" "$(awk -v k="$b_mem" 'BEGIN {print k / 1024}')" \
  "$(awk -v a="$c_med" -v b="$b_med" 'BEGIN {print a / b}')" "$ccx_umax" "$own_bumax" "$own_maxrel" "$own_meanrel"
echo
echo "- CPU time (user + sys) median: ccx $c_cpu s, built-in $b_cpu s (2 threads each: OMP_NUM_THREADS=2)."
echo "- Built-in (solve.json; n/a = not reported): ${lsolver//_/ }, $threads threads; $incs load increments," \
  "$iters Newton iterations; $fact factorisations ($shifted shifted), $cg preconditioned CG iterations;" \
  "solver.seconds median $b_solver_med s (assembly $b_asm_med s, linear solves $b_lin_med s);" \
  "max |u| over the runs: ${b_umax_all% } mm."
echo "- CalculiX: $ccx_incs increments, $ccx_iters iterations (model.sta)."
printf -- "- \`tissuemesh check --calculix\` (one more run of each): max |u| %.4f / %.4f mm (ccx / built-in), max nodal diff %.2e, mean %.2e of max |u|; its own timings ccx %.1f s, built-in %.1f s.\n" \
  "$ck_c" "$ck_b" "$ck_maxrel" "$ck_meanrel" "$ck_ct" "$ck_bt"

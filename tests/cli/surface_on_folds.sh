#!/bin/sh
# The folded layers (seed 2) through the shipped surface config (configs/folded-layers-surface.yaml:
# 21,000 vertices, restored volumes, TetGen): coarsening layers that fold about as fast as the
# edges are long flattens some folds of the grey|white interface almost completely, and TetGen,
# which keeps every surface triangle, fills them with tets as flat, some still under 10 degrees
# after the sliver repair. The run must then remesh and mesh again with the fold guard and keep
# that: exit 0, a conforming mesh with no dihedral under 10 degrees, the budget met, no fold of
# the surface under the guard's 25.8 degrees, every tissue at its voxel volume, and the report
# saying so. The config's mean-quality smoothing must lift the averages of Table 1 to at least
# the default phantom's 21K figures (README: mean smallest angle 51.59 deg, Q_av 0.900; this seed
# had 50.65 and 0.887 without it), and Q_min with them (0.488).
# Labelled cli only (not in the sanitizer run).
# Usage: surface_on_folds.sh TISSUEMESH PYTHON3 SOURCE_DIR WORK_DIR
set -u
exe=$1; py=$2; src=$3; work=$4
rm -rf "$work"; mkdir -p "$work"; cd "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
"$exe" phantom -c "$src/configs/folded-layers.yaml" --seed 2 --out labels.nii.gz > /dev/null || fail "phantom"
"$exe" mesh labels.nii.gz -c "$src/configs/folded-layers-surface.yaml" -o out --no-html > log.txt 2> err.txt
rc=$?
[ "$rc" = 0 ] || fail "exit $rc: $(cat err.txt)"
grep -q "^conforming: yes" out/report.txt || fail "not conforming"
grep -q "remeshed and meshed again with the fold guard: .*: kept" out/report.txt || fail "no guarded rerun kept"
"$py" - out/report.json <<'PY' || fail "figures"
import json, sys
r = json.load(open(sys.argv[1]))["result"]
v = r["volume_mesh"]
bad = []
if r["vertices"] != 21000: bad.append(f"{r['vertices']} vertices")
if r["sharpest_fold_deg"] < 25.8: bad.append(f"fold of {r['sharpest_fold_deg']:.2f} deg")
rerun = r["remesh"]["fold_guard_rerun"]
if not (rerun["kept"] and rerun["tets_under_10deg_before"] > 0 and rerun["tets_under_10deg_guarded"] == 0):
    bad.append(f"rerun {rerun}")
t1 = r["table1_quality"]
if t1["average_min_angle_deg"] < 51.59 or t1["q_average"] < 0.900 or t1["q_min"] < 0.488:
    bad.append(f"Table 1 {t1}")
if r["remesh"]["mean_quality_smoothing_moves"] == 0: bad.append("no mean-quality moves")
for t in v["quality"]["tissues"]:
    err = 100 * (t["volume_mm3"] / t["reference_volume_mm3"] - 1)
    if abs(err) > 0.5: bad.append(f"{t['name']} {err:+.2f} %")
if v["quality"]["total"]["min_dihedral_deg"] < 10: bad.append("a tet under 10 deg")
print(f"sharpest fold {r['sharpest_fold_deg']:.2f} deg, min dihedral {v['quality']['total']['min_dihedral_deg']:.2f} deg, "
      f"Table 1 {t1['average_min_angle_deg']:.2f} / {t1['min_angle_deg']:.2f} / {t1['p30_percent']:.4f} / "
      f"{t1['q_average']:.4f} / {t1['q_min']:.4f}; rerun {rerun}")
if bad:
    print("FAIL:", bad)
    sys.exit(1)
PY
echo "ok"

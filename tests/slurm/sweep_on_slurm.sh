#!/usr/bin/env bash
# A sweep through a real Slurm (tests/slurm/local_slurm.sh starts one on this machine): the 4-shard
# job array and its dependent merge job, submitted by `tissuemesh sweep --slurm 4 --submit`, end
# with the results.csv of the same sweep run locally (both without warm starts, so the tables are
# the same bits). Usage: sweep_on_slurm.sh TISSUEMESH_EXE SOURCE_DIR. Exit 77 (skip) without root
# or without the Slurm packages.
set -euo pipefail
exe=$(realpath "$1")
src=$(realpath "$2")
[[ $(id -u) == 0 ]] || { echo "sweep_on_slurm: needs root (slurmd)"; exit 77; }
work=$(mktemp -d)
chmod 755 "$work"  # the munge user reaches its key and socket below it
cluster=$work/cluster
trap 'bash "$src/tests/slurm/local_slurm.sh" stop "$cluster"; rm -rf "$work"' EXIT
set +e
env_line=$(bash "$src/tests/slurm/local_slurm.sh" start "$cluster")
rc=$?
set -e
[[ $rc == 0 ]] || exit $rc
eval "$env_line"
cd "$work"
sed "s#preset: materials/#preset: $src/configs/materials/#" "$src/configs/phantom-coarse.yaml" > coarse.yaml
"$exe" demo -c coarse.yaml --skip-calculix -o demo > /dev/null
cat > sweep.yaml <<'YAML'
parameters:
  materials.breast.mu: {range: [100 Pa, 300 Pa], scale: log}
  materials.tumor.E: {values: [5 kPa, 20 kPa]}
design: {type: grid, levels: 3}
YAML
"$exe" sweep demo/mesh.vtu -c coarse.yaml --sweep sweep.yaml -o local --no-warm-start > /dev/null
"$exe" sweep demo/mesh.vtu -c coarse.yaml --sweep sweep.yaml -o onslurm --no-warm-start --slurm 4 --submit
for _ in $(seq 600); do
  [[ -f onslurm/results.csv ]] && [[ -z $(squeue -h 2> /dev/null) ]] && break
  sleep 0.5
done
ls onslurm/slurm
if [[ ! -f onslurm/results.csv ]]; then
  echo "sweep_on_slurm: no results.csv after 300 s; queue and logs:"
  squeue || true
  tail -n 20 onslurm/slurm/*.log "$cluster"/slurmctld.log || true
  exit 1
fi
cmp onslurm/results.csv local/results.csv
echo "sweep_on_slurm: 4 shards + merge through Slurm $(sinfo --version | cut -d' ' -f2) give the local table ($(($(wc -l < local/results.csv) - 1)) samples)"

#!/usr/bin/env bash
# A single-node Slurm on this machine for the sweep tests (Debian packages slurm-wlm and munge,
# installed by scripts/setup.sh): munged, slurmctld and slurmd with a generated slurm.conf in a
# folder of their own, so that nothing of the machine's own configuration is used or changed.
#
#   local_slurm.sh start DIR   # prints "export SLURM_CONF=DIR/slurm.conf"; waits until the node is idle
#   local_slurm.sh stop DIR    # stops the daemons started from DIR
# Needs root (slurmd runs jobs as their submitter). Exit 77 (a skip for ctest) when the packages
# are missing; 1 when the cluster does not come up (its logs are printed).
set -euo pipefail
cmd=$1
dir=$(realpath -m "$2")
conf=$dir/slurm.conf
stop() {
  for p in slurmd slurmctld; do
    [[ -f $dir/$p.pid ]] && kill "$(cat "$dir/$p.pid")" 2> /dev/null || true
  done
  [[ -f $dir/munged.pid ]] && kill "$(cat "$dir/munged.pid")" 2> /dev/null || true
  sleep 0.5
}
if [[ $cmd == stop ]]; then stop; exit 0; fi
for exe in munged slurmctld slurmd sbatch; do
  command -v "$exe" > /dev/null || { echo "local_slurm: $exe not installed (Debian slurm-wlm, munge)" >&2; exit 77; }
done
mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
chmod 755 "$dir"
chown munge:munge "$dir/munge"
# munge: its own key and socket under DIR, run as the munge user.
if [[ ! -f $dir/munge/munge.key ]]; then
  runuser -u munge -- mungekey --create --keyfile="$dir/munge/munge.key" --force
fi
runuser -u munge -- munged --key-file="$dir/munge/munge.key" --socket="$dir/munge/munge.socket" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munge/munged.log" --seed-file="$dir/munge/munged.seed"
host=$(hostname -s)
cpus=$(nproc)
mem=$(awk '/MemTotal/ {print int($2 / 1024 / 2)}' /proc/meminfo)
port=$((20000 + RANDOM % 20000))
cat > "$conf" <<CONF
ClusterName=tissuemesh-test
SlurmctldHost=$host
SlurmctldPort=$port
SlurmdPort=$((port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$dir/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$conf
slurmctld -f "$conf"
slurmd -f "$conf"
for _ in $(seq 100); do
  if sinfo -h -o %T 2> /dev/null | grep -q idle; then echo "export SLURM_CONF=$conf"; exit 0; fi
  sleep 0.2
done
echo "local_slurm: the node did not come up; logs:" >&2
tail -20 "$dir/slurmctld.log" "$dir/slurmd.log" "$dir/munge/munged.log" >&2 || true
stop
exit 1

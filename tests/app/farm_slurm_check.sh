#!/usr/bin/env bash
# scripts/farm/slurm_record.sh through a real Slurm: a private single-node cluster
# (munged, slurmctld and slurmd on 127.0.0.1, state in a temporary folder) runs the job
# array of three 10-frame chunks with `sbatch --wait`; the frames must equal one full
# 24-frame run byte for byte. Skipped (77) where Slurm or munge is not installed
# (.ci/run installs them; docs/farm.md).
set -euo pipefail
bin=$(realpath "${FOGPIPE_BIN:?run through ctest}")
for tool in munged slurmctld slurmd sbatch; do
  command -v "$tool" > /dev/null || { echo "skipped: $tool is not installed"; exit 77; }
done
[[ $(id -u) == 0 ]] || { echo "skipped: a private slurmd needs root"; exit 77; }
d=$(mktemp -d /tmp/fogpipe-slurm-XXXXXX)
chmod 755 "$d"
cleanup() {
  local pids=()
  for pid_file in "$d"/slurmd.pid "$d"/slurmctld.pid "$d"/munged.pid; do
    [[ -f $pid_file ]] && pids+=("$(cat "$pid_file")")
  done
  ((${#pids[@]})) && kill "${pids[@]}" 2> /dev/null
  for _ in $(seq 50); do # the daemons save their state as they stop
    alive=0
    for pid in "${pids[@]}"; do kill -0 "$pid" 2> /dev/null && alive=1; done
    ((alive)) || break
    sleep 0.2
  done
  rm -rf "$d"
}
trap cleanup EXIT
mkdir -p "$d"/{state,spool,out}
head -c 1024 /dev/urandom > "$d/munge.key"
chmod 400 "$d/munge.key"
munged --force --socket="$d/munge.socket" --key-file="$d/munge.key" --pid-file="$d/munged.pid" \
  --log-file="$d/munged.log" --seed-file="$d/munge.seed"
node=$(hostname -s)
cat > "$d/slurm.conf" << CONF
ClusterName=fogpipe-test
SlurmctldHost=$node(127.0.0.1)
AuthType=auth/munge
AuthInfo=socket=$d/munge.socket
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SwitchType=switch/none
MpiDefault=none
ReturnToService=2
SlurmUser=root
SlurmdUser=root
SlurmctldPort=26817
SlurmdPort=26818
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmdSpoolDir=$d/spool
StateSaveLocation=$d/state
SlurmctldLogFile=$d/slurmctld.log
SlurmdLogFile=$d/slurmd.log
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
NodeName=$node NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=10 State=UP
CONF
export SLURM_CONF=$d/slurm.conf
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 60); do
  sinfo -h -o %t 2> /dev/null | grep -q idle && break
  sleep 1
done
sinfo -h -o %t | grep -q idle || { cat "$d"/slurm*.log; echo "FAIL: the node never came up"; exit 1; }

"$bin" record configs/default.ini --frames 24 --size 64x36 --out "$d/out/whole" > /dev/null
FOGPIPE=$bin CONFIG=$PWD/configs/default.ini FRAMES=24 CHUNK=10 SIZE=64x36 OUT=$d/out/farm \
  timeout 300 sbatch --wait --array=0-2 --cpus-per-task=1 --chdir="$d/out" \
  scripts/farm/slurm_record.sh
diff <(ls -A "$d/out/whole") <(ls -A "$d/out/farm") || { cat "$d"/out/*.log; echo "FAIL: the folders list different files"; exit 1; }
for f in "$d"/out/whole/*.exr; do
  cmp -s "$f" "$d/out/farm/$(basename "$f")" || { echo "FAIL: $(basename "$f") differs"; exit 1; }
done
echo "farm_slurm_check: a 3-task Slurm job array rendered the 24 frames of one full run, byte for byte"

#!/usr/bin/env bash
# A real Slurm cluster of one node on 127.0.0.1: munged, slurmctld and slurmd started in a temp
# directory with a generated slurm.conf and non-default ports, so nothing on the machine is touched.
# A 4-task job array (scripts/slurm/relight.sbatch) shades 8 frames; every frame must be shaded by
# exactly one task and be byte-for-byte the file a single process writes. Daemons are stopped by
# their pids; nothing is left running or on disk.
set -euo pipefail
cd "$(dirname "$0")/../.."
repo=$PWD
phongcl="$repo/${PHONGCL_BUILD_DIR:-build}/phongcl"
[ -x "$phongcl" ] || { echo "50-slurm: $phongcl not built (scripts/build.sh)" >&2; exit 1; }
for tool in munged mungekey slurmctld slurmd sbatch squeue scontrol; do
  command -v "$tool" >/dev/null || { echo "50-slurm: $tool missing (scripts/setup.sh slurm)" >&2; exit 1; }
done

work=$(mktemp -d /tmp/phongcl-slurm.XXXXXX)
chmod 755 "$work"  # munged refuses directories others can write to
pids=()
cleanup() {
  local status=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ $status -ne 0 ]; then
    for log in "$work"/*.log; do [ -f "$log" ] && { echo "--- $log"; tail -n 20 "$log"; }; done
  fi
  rm -rf "$work"
  exit $status
}
trap cleanup EXIT

# Ports away from Slurm's 6817/6818, chosen per run so two checks on one machine do not collide.
base_port=$((20000 + RANDOM % 20000))
user=$(id -un)
mkdir -p "$work/state" "$work/spool" "$work/frames" "$work/lit" "$work/single" "$work/munge"
chmod 711 "$work/munge"  # clients need to reach the socket

mungekey --create --keyfile="$work/munge/munge.key" >/dev/null 2>&1
chmod 400 "$work/munge/munge.key"
munged --foreground --force --socket="$work/munge/munge.socket" --key-file="$work/munge/munge.key" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munged.log" --seed-file="$work/munge/munged.seed" >"$work/munged.out.log" 2>&1 &
pids+=($!)

cpus=$(nproc)
cat >"$work/slurm.conf" <<CONF
ClusterName=phongcl-check
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$base_port
SlurmdPort=$((base_port + 1))
SrunPortRange=$((base_port + 2))-$((base_port + 40))
SlurmUser=$user
SlurmdUser=$user
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.socket
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
NodeName=phongcl-node NodeAddr=127.0.0.1 NodeHostname=$(hostname -s) CPUs=$cpus State=UNKNOWN
PartitionName=check Nodes=phongcl-node Default=YES MaxTime=10 State=UP
CONF
export SLURM_CONF="$work/slurm.conf"

for _ in $(seq 50); do [ -S "$work/munge/munge.socket" ] && break; sleep 0.1; done
slurmctld -D -i -f "$SLURM_CONF" >"$work/slurmctld.out.log" 2>&1 &
pids+=($!)
slurmd -D -N phongcl-node -f "$SLURM_CONF" >"$work/slurmd.out.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  sinfo -h -N -o %T 2>/dev/null | grep -qE '^idle' && break
  sleep 0.2
done
sinfo -h -N -o %T | grep -qE '^idle' || { echo "50-slurm: the node never became idle" >&2; exit 1; }

# 8 frames: the bundled G-buffer, with the first light moving from frame to frame.
for frame in $(seq 1 8); do
  name=$(printf '%04d' "$frame")
  cp scenes/default/gbuffer.exr "$work/frames/g.$name.exr"
  sed "s/\[4, 6, 5\]/[$frame, 6, 5]/" scenes/default/scene.json >"$work/frames/s.$name.json"
done
shade=(--scene "$work/frames/s.####.json" --gbuffer "$work/frames/g.####.exr" --frames 1-8)
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$repo/build/pocl-cache}" PHONGCL_CACHE_DIR="$work/phongcl-cache"

# Each task runs single-threaded EXR I/O (one CPU each), the array two at a time on two cores.
PHONGCL="$phongcl" sbatch --wait --array=0-3 --cpus-per-task=1 --chdir="$work" \
  --output="$work/task-%a.log" --error="$work/task-%a.log" scripts/slurm/relight.sbatch \
  "${shade[@]}" --out "$work/lit/lit.####.exr" >"$work/sbatch.log"

"$phongcl" shade "${shade[@]}" --threads 1 --out "$work/single/lit.####.exr" >"$work/single.log"

failures=0
for task in 0 1 2 3; do
  grep -q "shard      $task/4 (Slurm job array task $task)" "$work/task-$task.log" ||
    { echo "50-slurm: task $task did not take its shard from the array" >&2; failures=1; }
done
for frame in $(seq 1 8); do
  name=$(printf '%04d' "$frame")
  shaded_by=$(grep -l "^  frame $frame  read" "$work"/task-*.log | wc -l)
  [ "$shaded_by" -eq 1 ] || { echo "50-slurm: frame $frame shaded by $shaded_by tasks" >&2; failures=1; }
  cmp -s "$work/lit/lit.$name.exr" "$work/single/lit.$name.exr" ||
    { echo "50-slurm: frame $frame differs from the single-process run" >&2; failures=1; }
done
leftovers=$(find "$work/lit" -name '*.tmp*' | wc -l)
[ "$leftovers" -eq 0 ] || { echo "50-slurm: $leftovers temporaries left in the output directory" >&2; failures=1; }
[ $failures -eq 0 ] || exit 1
echo "50-slurm: a 4-task Slurm array shaded 8 frames, each once, identical to one process"

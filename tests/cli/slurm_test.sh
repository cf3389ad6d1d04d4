#!/bin/bash
# A study on a real Slurm cluster: a single-node cluster from Debian's packages (munge,
# slurmctld, slurmd; a generated slurm.conf in a temporary folder, loopback only) runs a small
# study as `vmt study sbatch` submits it, and its merged cases are the same bytes as a local
# run's. Then one shard's task is cancelled: `vmt study status` names the shard, the same
# command submits that shard alone and the merge, and the result is again the same bytes.
# Usage: slurm_test.sh VMT SOURCE_DIR WORK_DIR
set -euo pipefail
vmt=$1 src=$2 work=$3
scene=$src/tests/sim/study/tiny-study.yaml
plan=(--every-ms 1000)
fail() { echo "FAILED: $*" >&2; exit 1; }
for tool in mungekey munged slurmctld slurmd sbatch squeue scontrol scancel sinfo; do
  command -v "$tool" > /dev/null || fail "$tool not found: tools/setup-debian.sh installs Slurm"
done
rm -rf "$work" && mkdir -p "$work" && cd "$work"

# Without a cluster: the scripts and the commands (--print), and refusals before any job.
"$vmt" study sbatch "$scene" --out "$work/printed" --shards 2 "${plan[@]}" --print > print.txt
grep -q "sbatch --parsable --array=1,2 $work/printed/slurm/shards.sh" print.txt || fail "--print: $(cat print.txt)"
grep -q "sbatch --parsable --dependency=afterok:ARRAY_JOB_ID $work/printed/slurm/merge.sh" print.txt ||
  fail "--print: no merge after the shards: $(cat print.txt)"
grep -q -- '--shard "$k/2" --jobs "${SLURM_CPUS_PER_TASK:-1}" --every-ms 1000$' printed/slurm/shards.sh ||
  fail "shards.sh: $(cat printed/slurm/shards.sh)"
refused() {  # refused MESSAGE COMMAND...: exit 2 with MESSAGE, no job
  local message=$1; shift
  if "$@" > out.txt 2>&1; then fail "accepted: $*"; fi
  grep -q -- "$message" out.txt || fail "$*: expected '$message', got: $(cat out.txt)"
}
refused "holds another Slurm study" "$vmt" study sbatch "$scene" --out printed --shards 3 "${plan[@]}"
refused "a study needs a .study:. section" "$vmt" study sbatch "$src/scenes/turning.yaml" --out other --shards 2
refused "may not hold blanks" "$vmt" study sbatch "$scene" --out "$work/a b" --shards 2
refused "whole number in 1..100000" "$vmt" study sbatch "$scene" --out other --shards 0
refused "not a folder" "$vmt" study status "$work/none"
mkdir -p damaged && echo '{"scene_file": 3}' > damaged/study.json
refused "damaged/study.json: scene_file: expected the scene's path" "$vmt" study status damaged

# The cluster's files in a short path (munge's socket path has a length limit).
cluster=$(mktemp -d /tmp/vmt-slurm.XXXXXX)
export SLURM_CONF=$cluster/slurm.conf
stop_cluster() {
  scontrol shutdown > /dev/null 2>&1 || true
  sleep 1
  for pid_file in "$cluster"/*.pid; do
    [ -f "$pid_file" ] && kill "$(cat "$pid_file")" 2> /dev/null || true
  done
  munged --stop --socket="$cluster/munge.sock" > /dev/null 2>&1 || true
  rm -rf "$cluster"
}
trap stop_cluster EXIT
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
mkdir -p "$cluster/state" "$cluster/spool"
mungekey --create --keyfile="$cluster/munge.key" && chmod 600 "$cluster/munge.key"
munged --force --key-file="$cluster/munge.key" --socket="$cluster/munge.sock" \
  --pid-file="$cluster/munged.pid" --log-file="$cluster/munged.log" --seed-file="$cluster/munged.seed"
cat > "$SLURM_CONF" << CONF
ClusterName=vmttest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
AuthInfo=socket=$cluster/munge.sock
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
StateSaveLocation=$cluster/state
SlurmdSpoolDir=$cluster/spool
SlurmctldPidFile=$cluster/slurmctld.pid
SlurmdPidFile=$cluster/slurmd.pid
SlurmctldLogFile=$cluster/slurmctld.log
SlurmdLogFile=$cluster/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
NodeName=vmttest NodeHostname=$(hostname) NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=vmt Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF" -N vmttest
for _ in $(seq 60); do
  [ "$(sinfo --noheader --format=%T 2> /dev/null)" = idle ] && break
  sleep 0.5
done
[ "$(sinfo --noheader --format=%T)" = idle ] || fail "the Slurm node did not come up: $(tail -n 5 "$cluster"/*.log)"

# Polls `vmt study status DIR` until it says complete (exit 0); at most $2 s.
wait_complete() {
  for _ in $(seq $(($2 * 2))); do
    "$vmt" study status "$1" > status.txt 2>&1 && return 0
    sleep 0.5
  done
  cat status.txt; squeue; tail -n 20 "$1"/slurm/*.log
  fail "$1 did not complete in $2 s"
}

"$vmt" study repos "$scene" --out local --jobs 2 "${plan[@]}" > /dev/null
cases=$(wc -l < local/cases.jsonl)
[ "$cases" -ge 8 ] || fail "expected at least 8 cases locally, got $cases"

# The whole study through the cluster: three array tasks, the merge after them.
"$vmt" study sbatch "$scene" --out "$work/cluster-study" --shards 3 "${plan[@]}" > sbatch.txt ||
  fail "vmt study sbatch: $(cat sbatch.txt)"
grep -q "submitted: array job [0-9]* (shards 1,2,3), merge job [0-9]* after it" sbatch.txt ||
  fail "submission: $(cat sbatch.txt)"
wait_complete cluster-study 120
cmp local/cases.csv cluster-study/cases.csv || fail "cases.csv of the Slurm study differs from the local run"
cmp local/cases.jsonl cluster-study/cases.jsonl || fail "cases.jsonl of the Slurm study differs"
for k in 1 2 3; do
  grep -q "cluster-study/shards/$k (shard $k/3): [0-9]* of [0-9]* cases$" status.txt ||
    fail "status of shard $k: $(cat status.txt)"
done
"$vmt" study sbatch "$scene" --out "$work/cluster-study" --shards 3 "${plan[@]}" |
  grep -q "complete ($cases cases), nothing to submit" || fail "a complete study was submitted again"

# A shard whose task is killed: the merge can never run; status names the shard, and the same
# command submits it alone (and a new merge) without running the others' cases again.
"$vmt" study sbatch "$scene" --out "$work/killed" --shards 3 "${plan[@]}" --sbatch-option=--hold > sbatch.txt
read -r array merge < killed/slurm/jobs.txt
refused "its jobs are still queued or running" "$vmt" study sbatch "$scene" --out "$work/killed" --shards 3 "${plan[@]}"
scancel "${array}_2"
scontrol release "$array" && scontrol release "$merge"
for _ in $(seq 120); do
  [ "$(squeue --noheader --jobs="$array" 2> /dev/null | wc -l)" -eq 0 ] && break
  sleep 0.5
done
if "$vmt" study status killed > status.txt; then fail "a study with a cancelled shard is complete"; fi
grep -q "killed/shards/2: not started" status.txt || fail "status of the killed shard: $(cat status.txt)"
grep -q "shards 2 incomplete: .vmt study sbatch" status.txt || fail "status gives no command: $(cat status.txt)"
before1=$(stat -c %.9Y killed/shards/1/cases.jsonl)
"$vmt" study sbatch "$scene" --out "$work/killed" --shards 3 "${plan[@]}" > sbatch.txt ||
  fail "resubmission: $(cat sbatch.txt)"
grep -q "(shards 2)," sbatch.txt || fail "the resubmission ran other shards: $(cat sbatch.txt)"
wait_complete killed 120
[ "$(stat -c %.9Y killed/shards/1/cases.jsonl)" = "$before1" ] || fail "shard 1 ran again"
cmp local/cases.csv killed/cases.csv || fail "the completed study differs from the local run"
[ -z "$(squeue --noheader)" ] || fail "jobs left in the queue: $(squeue)"
echo "slurm: a study of $cases cases through a Slurm array job and a merge job; a killed shard resubmitted alone"

#!/usr/bin/env bash
# .ci/cluster.sh VOXCAST: the `cluster` step of .ci/run (docs/cluster.md,
# "The CI's cluster"). Starts a Slurm of one node on this machine from
# Debian's packages (munged, slurmctld, slurmd), reachable on the loopback
# address only and on ports of its own, with its own munge socket, state and
# spool folders, so nothing of the machine's (or another run's) is touched;
# then, through it:
#   1. a 12-point sweep as 4 shards, a truth job and a merge job, submitted by
#      `voxcast sweep --slurm 4`; shard 2 is cancelled while it waits for the
#      truth (what a node failure or an administrator does), so the merge is
#      cancelled too (--kill-on-invalid-dep=yes) and `sweep-status` names the
#      failed shard;
#   2. `--resume` submits shard 2 and the merge again, nothing else; the merged
#      results must equal a single-machine run's byte for byte, and the truth
#      must have been rendered once, by the truth job;
#   3. a regression over 3 shards, whose merged table must equal a local run's.
# Every daemon it started is stopped by the PID it recorded, whatever happens.
set -euo pipefail
if [ "$(id -u)" -ne 0 ]; then
  echo "cluster: SKIPPED: starting munged (as the munge user) and slurmd needs root"
  exit 0
fi
VOXCAST=$(realpath "$1")
SCENE=$(realpath "$(dirname "$0")/../scenes/mip.toml")
ROOT=$(mktemp -d /tmp/voxcast-slurm.XXXXXX)
chmod 755 "$ROOT"
host=$(hostname -s)
pids=()

stop_daemons() {
  local p
  for p in "${pids[@]}"; do
    [ -f "$p" ] && kill "$(cat "$p")" 2>/dev/null || true
  done
  for p in "${pids[@]}"; do  # wait for each to be gone (at most 10 s)
    for _ in $(seq 1 100); do
      [ -f "$p" ] && kill -0 "$(cat "$p")" 2>/dev/null || break
      sleep 0.1
    done
  done
}
fail() {
  echo "cluster: FAILED: $*"
  echo "--- scontrol -o show job"
  scontrol -o show job 2>&1 | head -n 20 || true
  for f in "$ROOT"/slurmctld.log "$ROOT"/slurmd.log; do
    echo "--- last lines of $f"
    tail -n 20 "$f" 2>/dev/null || true
  done
  exit 1
}
trap 'stop_daemons; rm -rf "$ROOT"' EXIT

# The loopback only: the node's name must resolve to 127.x.x.x here, and the
# daemons are given that address and bound to it (NoInAddrAny,NoCtldInAddrAny).
addr=$(getent hosts "$host" | awk '{print $1; exit}')
case "$addr" in
  127.*) ;;
  *)
    echo "cluster: SKIPPED: $host resolves to '${addr:-nothing}', not to a loopback address; the daemons would listen on the network (map it to 127.0.1.1 in /etc/hosts to run this step)"
    exit 0
    ;;
esac

# munge, on a socket of our own.
mkdir -p "$ROOT/munge"
chown munge:munge "$ROOT/munge"
runuser -u munge -- munged --socket="$ROOT/munge/socket" --pid-file="$ROOT/munge/munged.pid" \
  --log-file="$ROOT/munge/munged.log" --seed-file="$ROOT/munge/seed"
pids+=("$ROOT/munge/munged.pid")
munge --socket="$ROOT/munge/socket" -n | unmunge --socket="$ROOT/munge/socket" >/dev/null ||
  fail "munge does not answer on $ROOT/munge/socket"

# Ports of our own (two above 20000, from the PID), so parallel runs do not meet.
port=$((20000 + ($$ % 20000) * 2))
mkdir -p "$ROOT/state" "$ROOT/spool"
export SLURM_CONF=$ROOT/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=voxcast-ci
SlurmctldHost=$host($addr)
SlurmctldPort=$port
SlurmdPort=$((port + 1))
AuthType=auth/munge
AuthInfo=socket=$ROOT/munge/socket
CredType=cred/munge
SlurmUser=root
SlurmdUser=root
CommunicationParameters=NoInAddrAny,NoCtldInAddrAny
StateSaveLocation=$ROOT/state
SlurmdSpoolDir=$ROOT/spool
SlurmctldPidFile=$ROOT/slurmctld.pid
SlurmdPidFile=$ROOT/slurmd.pid
SlurmctldLogFile=$ROOT/slurmctld.log
SlurmdLogFile=$ROOT/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
SchedulerParameters=sched_interval=1,bf_interval=1
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MailProg=/bin/true
MinJobAge=3600
ReturnToService=2
NodeName=$host NodeAddr=$addr CPUs=$(nproc) State=UNKNOWN
PartitionName=ci Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$SLURM_CONF"
pids+=("$ROOT/slurmctld.pid")
slurmd -f "$SLURM_CONF"
pids+=("$ROOT/slurmd.pid")
for _ in $(seq 1 150); do
  sinfo -h -o %T 2>/dev/null | grep -qE '^idle' && break
  sleep 0.2
done
sinfo -h -o %T | grep -qE '^idle' || fail "the node did not become idle in 30 s"
echo "cluster: slurmctld and slurmd up on $addr:$port (node $host, $(nproc) CPUs)"

# wait_for DIR STATUS...: polls sweep-status until it exits with one of the
# statuses (0 finished, 9 something failed), at most 5 minutes.
wait_for() {
  local dir=$1 rc
  shift
  for _ in $(seq 1 600); do
    rc=0
    "$VOXCAST" sweep-status "$dir" >"$ROOT/status.txt" 2>&1 || rc=$?
    if [[ " $* " == *" $rc "* ]]; then
      cat "$ROOT/status.txt"
      return 0
    fi
    sleep 0.5
  done
  cat "$ROOT/status.txt"
  fail "sweep-status $dir did not reach status $* in 5 minutes"
}

ARGS=("$SCENE" --set render.width=32 --set render.height=32 --truth-oversampling 2
  --vary precision.profile=vizard2,balanced,precise --vary render.oversampling=1,2
  --vary render.ert_threshold=0.95,0.99 --no-plots)

echo "--- a single machine: the results to compare with"
"$VOXCAST" sweep "${ARGS[@]}" --out "$ROOT/whole" >/dev/null

echo "--- sweep --slurm 4, held; shard 2 cancelled before it starts; released"
"$VOXCAST" sweep "${ARGS[@]}" --out "$ROOT/run" --slurm 4 --slurm-opt "--hold" | tee "$ROOT/submit.txt"
source "$ROOT/run/slurm/jobs.env"
scancel "${shards}_2"
t0=$(date +%s.%N)
scontrol release "$truth" "$shards" "$merge"
wait_for "$ROOT/run" 9
t1=$(date +%s.%N)
grep -qE '^  shard 2 +FAILED +Slurm job [0-9]+_2: gone from its array before it ran' "$ROOT/status.txt" ||
  fail "sweep-status does not name shard 2 as cancelled"
grep -qE '^  merge +FAILED +Slurm job [0-9]+: CANCELLED' "$ROOT/status.txt" ||
  fail "the merge is not cancelled after a failed shard (--kill-on-invalid-dep)"
for k in 0 1 3; do
  grep -qE "^  shard $k +done" "$ROOT/status.txt" || fail "shard $k did not finish"
done

echo "--- --resume: shard 2 and the merge, nothing else"
"$VOXCAST" sweep "${ARGS[@]}" --out "$ROOT/run" --slurm 4 --resume | tee "$ROOT/resume.txt"
grep -q '^truth ' "$ROOT/resume.txt" && fail "--resume submitted the truth job again"
grep -q '(tasks 2 of 4)' "$ROOT/resume.txt" || fail "--resume did not submit shard 2 alone"
wait_for "$ROOT/run" 0 9
grep -q '^finished' "$ROOT/status.txt" || fail "the resumed run did not finish"
for f in results.csv results.json; do
  cmp "$ROOT/whole/$f" "$ROOT/run/$f" || fail "$f of the cluster run differs from one machine's"
done
grep -q '1 rendered, 0 already in the cache' "$ROOT/run/slurm/logs/truth.log" ||
  fail "the truth job did not render the one truth"
if grep -h '^points' "$ROOT"/run/slurm/logs/shard-*.log | grep -qv '(0 truth images rendered'; then
  fail "a shard rendered a truth"
fi

# The time model of docs/cluster.md against this run: the jobs' own times
# (from their summaries) and the wall time from release to the last job.
truth_s=$(sed -nE 's/^truths .* in ([0-9.]+) s .*/\1/p' "$ROOT/run/slurm/logs/truth.log" | head -n 1)
shard_s=$(sed -nE 's/^points .* in ([0-9.]+) s .*/\1/p' "$ROOT"/run/slurm/logs/shard-[013].log | tr '\n' ' ')
echo "cluster: time model: truth ${truth_s} s; shards 0, 1, 3: ${shard_s}s; released to settled $(awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.1f", b - a }') s on $(nproc) CPUs"

echo "--- an option sbatch refuses: one line naming the command and sbatch's words"
rc=0
"$VOXCAST" sweep "${ARGS[@]}" --out "$ROOT/refused" --slurm 2 --slurm-opt "--partition=nowhere" \
  >"$ROOT/refused.txt" 2>&1 || rc=$?
cat "$ROOT/refused.txt"
[ "$rc" -eq 1 ] && grep -q "submission failed .*sbatch: error: .*[Pp]artition" "$ROOT/refused.txt" ||
  fail "a partition sbatch refuses was not one line with its message and exit status 1"

echo "--- regress --slurm 3 against a local regress"
RARGS=(--scenes "$(dirname "$SCENE")/../tests/regress" --golden "$ROOT/no-goldens"
  --profiles vizard2,balanced --set render.width=24 --set render.height=24)
"$VOXCAST" regress "${RARGS[@]}" >"$ROOT/regress-local.txt" 2>/dev/null || true
"$VOXCAST" regress "${RARGS[@]}" --slurm 3 --out "$ROOT/regress" >/dev/null
wait_for "$ROOT/regress" 4  # every golden is missing: it fails as a local run does
grep -qE '^  merge +done +exit status 4' "$ROOT/status.txt" || fail "the regress merge did not exit 4"
grep -vE '^(===|voxcast: )' "$ROOT/regress/slurm/logs/merge.log" | cmp - "$ROOT/regress-local.txt" ||
  fail "the merged regress table differs from the local one"
echo "cluster: ok"

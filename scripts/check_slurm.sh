#!/usr/bin/env bash
# Checks scripts/slurm-array.sh against a real single-node Slurm (Debian's slurm-wlm and munge,
# installed with apt-get when missing): a munge key, slurm.conf, state, spool, logs and pid files
# in a temporary folder; munged, slurmctld and slurmd on 127.0.0.1 (free ports); every job
# cancelled and every daemon stopped at the end, also on failure. Needs root (the daemons start
# jobs); as another user it re-runs itself with sudo. Run by scripts/test (about 35 s on 2
# cores).
#   1. configs/quick.toml at solver tol 3e-7 (CHECK_SLURM_TOL; 2-3 s a shard) as 4 shards
#      (--cpus-per-task=1, an sbatch option passed through): the merged table's datasets are
#      identical to a single `sweep run`'s.
#   2. The same, with shard 2 requeued (`scontrol requeue`) once its checkpoint holds nodes: it
#      resumes from the checkpoint ("resuming from ...: N nodes already computed", N > 0,
#      restart 1), and the merged table is still identical.
# Also: --dry-run prints both job scripts; without sbatch, or without the binary, it exits 2.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
if [ "$(id -u)" -ne 0 ]; then
  echo "check_slurm: starting slurmd needs root: re-running with sudo" >&2
  exec sudo -E bash "$0" "$@"
fi
OBLIQUE_SETUP_EXTRA="slurm-wlm munge" source scripts/setup.sh
# h5py and numpy from the checks' own virtual environment (scripts/venv.sh; nothing installed
# into the system's Python).
if ! python3 -c 'import h5py, numpy' >/dev/null 2>&1; then
  source scripts/venv.sh
fi
sweep="$root/target/release/sweep" # what scripts/slurm-array.sh submits; scripts/test builds it
[ -x "$sweep" ] || { echo "check_slurm: $sweep missing: source scripts/build.sh first" >&2; exit 2; }
# Nothing of a surrounding Slurm (a real cluster's config, or this check run inside a job).
while read -r v; do unset "$v"; done < <(compgen -e | grep -E '^(SLURM|SBATCH|SALLOC|SRUN)_' || true)

t0=$(date +%s.%N)
work="$(mktemp -d)"
chmod 711 "$work" # munged wants its socket's folder searchable by all
export SLURM_CONF="$work/slurm.conf"
fail() {
  echo "check_slurm: $*" >&2
  exit 1
}
elapsed() { python3 -c "import sys; print(f'{float(sys.argv[2]) - float(sys.argv[1]):.1f}')" "$@"; }
pid_of() { [ -s "$work/$1.pid" ] && cat "$work/$1.pid"; }
alive() { [ -n "$1" ] && kill -0 "$1" 2>/dev/null; }
cleanup() {
  local rc=$? p d i pids
  trap - EXIT
  if alive "$(pid_of slurmctld || true)"; then
    scancel --quiet --partition=check 2>/dev/null || true
    for i in $(seq 1 40); do
      [ -z "$(squeue -h -o %A 2>/dev/null)" ] && break
      sleep 0.25
    done
  fi
  if [ "$rc" -ne 0 ]; then
    for d in slurmctld slurmd munged; do
      [ -f "$work/$d.log" ] && { echo "--- last lines of $d.log" >&2; tail -n 15 "$work/$d.log" >&2; }
    done
    for f in "$work"/c*/table.h5.parts/*.log; do
      [ -f "$f" ] && { echo "--- $f" >&2; tail -n 8 "$f" >&2; }
    done
  fi
  # Each takes a second or two to stop: all at once.
  pids=()
  for d in slurmd slurmctld munged; do
    p=$(pid_of "$d" || true)
    alive "$p" && kill "$p" 2>/dev/null && pids+=("$p")
  done
  for p in "${pids[@]}"; do
    for i in $(seq 1 100); do alive "$p" || break; sleep 0.1; done
    if alive "$p"; then kill -9 "$p" 2>/dev/null || true; fi
  done
  rm -rf "$work"
  exit "$rc"
}
trap cleanup EXIT

# --- the script's own checks, without Slurm
tol=${CHECK_SLURM_TOL:-3e-7} # a smaller one (1e-7) makes each shard longer, for timings
sed "s/^tol = .*/tol = $tol/" configs/quick.toml >"$work/config.toml"
grep -q "^tol = $tol\$" "$work/config.toml" || fail "configs/quick.toml has no 'tol = ' line to set"
bash scripts/slurm-array.sh --dry-run "$work/config.toml" 4 "$work/dry/t.h5" -- --time=5 \
  >"$work/dry.txt" 2>/dev/null || fail "--dry-run failed"
grep -q -- '--array=1-4' "$work/dry.txt" && grep -q -- 'sweep merge' "$work/dry.txt" &&
  grep -q -- '--dependency=afterok:ARRAY_JOB_ID --time=5' "$work/dry.txt" ||
  fail "--dry-run does not print both job scripts and the options: $(cat "$work/dry.txt")"
[ ! -e "$work/dry" ] || fail "--dry-run created $work/dry"
mkdir "$work/nosbatch"
for c in bash dirname realpath sed; do ln -s "$(command -v $c)" "$work/nosbatch/$c"; done
code=0
PATH="$work/nosbatch" bash scripts/slurm-array.sh "$work/config.toml" 4 "$work/x.h5" \
  2>"$work/err.txt" || code=$?
[ "$code" -eq 2 ] && grep -q 'sbatch not found' "$work/err.txt" ||
  fail "without sbatch: exit $code, $(cat "$work/err.txt")"
mkdir -p "$work/unbuilt/scripts" # a checkout without target/release/sweep
cp scripts/slurm-array.sh "$work/unbuilt/scripts/"
code=0
bash "$work/unbuilt/scripts/slurm-array.sh" "$work/config.toml" 4 "$work/x.h5" 2>"$work/err.txt" ||
  code=$?
[ "$code" -eq 2 ] && grep -q 'is not built' "$work/err.txt" ||
  fail "without the binary: exit $code, $(cat "$work/err.txt")"

# --- a single-node Slurm
mkdir -p "$work/state" "$work/spool"
head -c 1024 /dev/urandom >"$work/munge.key"
chmod 600 "$work/munge.key"
munged --key-file="$work/munge.key" --socket="$work/munge.sock" --pid-file="$work/munged.pid" \
  --log-file="$work/munged.log" --seed-file="$work/munged.seed" ||
  fail "munged did not start"
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*(x.getsockname()[1] for x in s))')
host=$(hostname -s 2>/dev/null || uname -n)
cat >"$SLURM_CONF" <<EOF
ClusterName=oblique-check
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
# cred_expire: also how long a requeued job waits before it may start again (default 120 s)
AuthInfo=socket=$work/munge.sock,cred_expire=5
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
MpiDefault=none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=1
KillWait=5
ReturnToService=2
NodeName=oblique-node NodeHostname=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=check Nodes=oblique-node Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$SLURM_CONF" || fail "slurmctld did not start"
slurmd -f "$SLURM_CONF" -N oblique-node || fail "slurmd did not start"
for i in $(seq 1 120); do
  state=$(sinfo -h -n oblique-node -o %t 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.25
done
[ "$state" = idle ] || fail "the node did not come up (state '$state')"
t_up=$(date +%s.%N)
echo "check_slurm: Slurm $(sinfo -V | cut -d' ' -f2) up on $host, $(nproc) CPUs ($(elapsed "$t0" "$t_up") s)"

# The merged tables must hold exactly the datasets of the single run, bit for bit.
same_datasets() {
  python3 - "$1" "$2" <<'EOF'
import sys, h5py, numpy as np
def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__(name, np.asarray(obj[()]))
                     if isinstance(obj, h5py.Dataset) else None)
    return out
a, b = datasets(sys.argv[1]), datasets(sys.argv[2])
if sorted(a) != sorted(b):
    sys.exit(f"dataset names differ: {sorted(set(a) ^ set(b))}")
bad = [k for k in a if a[k].dtype != b[k].dtype or a[k].shape != b[k].shape
       or a[k].tobytes() != b[k].tobytes()]
if bad or len(a) < 10:
    sys.exit(f"{len(bad)} of {len(a)} datasets differ: {bad[:5]}")
print(len(a))
EOF
}
# Wait until job $1 has left the queue; print its final state.
wait_job() {
  local s
  for i in $(seq 1 1200); do
    s=$(scontrol -o show job "$1" 2>/dev/null | grep -o 'JobState=[A-Z_]*' | cut -d= -f2 || true)
    case $s in PENDING | RUNNING | CONFIGURING | COMPLETING | REQUEUED | '') sleep 0.2 ;; *) break ;; esac
  done
  echo "$s"
}
submit() { # $1: case folder; prints "ARRAY MERGE"
  mkdir -p "$work/$1"
  bash scripts/slurm-array.sh "$work/config.toml" 4 "$work/$1/table.h5" -- --cpus-per-task=1 \
    >"$work/$1/submit.txt" || fail "slurm-array.sh failed: $(cat "$work/$1/submit.txt")"
  sed -n 's/^submitted shards as job array \([0-9]*\) and the merge as job \([0-9]*\)$/\1 \2/p' \
    "$work/$1/submit.txt"
}

# --- the reference: one `sweep run` of the same config on this machine
t=$(date +%s.%N)
"$sweep" run "$work/config.toml" -o "$work/single.h5" --quiet || fail "the single run failed"
single_s=$(elapsed "$t" "$(date +%s.%N)")

# --- case 1: 4 shards and the merge
t=$(date +%s.%N)
read -r array merge < <(submit c1) || true
[ -n "${merge:-}" ] || fail "no job ids in: $(cat "$work/c1/submit.txt")"
s=$(wait_job "$merge")
[ "$s" = COMPLETED ] || fail "case 1: the merge job ended $s: $(cat "$work/c1/table.h5.parts/merge.log" 2>/dev/null)"
slurm_s=$(elapsed "$t" "$(date +%s.%N)")
n=$(same_datasets "$work/single.h5" "$work/c1/table.h5") || fail "case 1: the merged table differs from the single run"
echo "check_slurm: 4 shards + merge under Slurm: $n datasets identical to the single run" \
  "(Slurm $slurm_s s, single run $single_s s on $(nproc) CPUs)"

# --- case 2: shard 2 requeued mid-run resumes from its checkpoint
t=$(date +%s.%N)
read -r array merge < <(submit c2) || true
[ -n "${merge:-}" ] || fail "no job ids in: $(cat "$work/c2/submit.txt")"
ckpt="$work/c2/table.h5.parts/part-2.bin.ckpt"
size0=""
for i in $(seq 1 3000); do
  if [ -f "$ckpt" ]; then
    size=$(stat -c %s "$ckpt" 2>/dev/null || echo 0)
    [ -n "$size0" ] || size0=$size
    [ "$size" -gt "$size0" ] && break # a batch of nodes saved since we first saw it
  fi
  [ -f "$work/c2/table.h5.parts/part-2.bin" ] && fail "case 2: shard 2 finished before it could be requeued"
  sleep 0.02
done
[ -n "$size0" ] && [ "$size" -gt "$size0" ] || fail "case 2: shard 2 wrote no checkpoint"
scontrol requeue "${array}_2" || fail "case 2: scontrol requeue ${array}_2 failed"
s=$(wait_job "$merge")
[ "$s" = COMPLETED ] || fail "case 2: the merge job ended $s: $(cat "$work/c2/table.h5.parts/merge.log" 2>/dev/null)"
requeue_s=$(elapsed "$t" "$(date +%s.%N)")
log="$work/c2/table.h5.parts/shard-2.log"
resumed=$(sed -n 's/^resuming from .*part-2\.bin\.ckpt: \([0-9]*\) nodes already computed$/\1/p' "$log")
[ -n "$resumed" ] && [ "$resumed" -gt 0 ] ||
  fail "case 2: shard 2 did not resume from its checkpoint: $(cat "$log")"
grep -q 'restart 1,' "$log" || fail "case 2: shard 2 was not restarted by Slurm: $(cat "$log")"
restarts=$(scontrol -o show job "${array}_2" | grep -o 'Restarts=[0-9]*' || true)
n=$(same_datasets "$work/single.h5" "$work/c2/table.h5") || fail "case 2: the merged table differs from the single run"
echo "check_slurm: shard 2 requeued mid-run ($restarts) resumed with $resumed nodes from its" \
  "checkpoint; $n datasets identical to the single run (Slurm $requeue_s s)"
echo "check_slurm: passed in $(elapsed "$t0" "$(date +%s.%N)") s"

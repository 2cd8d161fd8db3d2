#!/usr/bin/env bash
# Build a table on a Slurm cluster: one array task per shard, then a merge job that starts when
# every shard has finished. A requeued or resubmitted task resumes from its checkpoint, a task
# whose part is already written does nothing, and the merged table's datasets are identical to
# those of a single `sweep run`.
#
#   scripts/slurm-array.sh [--dry-run] CONFIG SHARDS OUTPUT [--] [SBATCH OPTIONS...]
#
#   scripts/slurm-array.sh configs/full.toml 32 tables/full.h5 -- --partition=short --time=01:00:00
#   scripts/slurm-array.sh --dry-run configs/quick.toml 4 out/quick.h5   # print, submit nothing
#
# SBATCH OPTIONS (everything after OUTPUT; the `--` is optional) go to both sbatch calls, after
# the script's own, so they override them: e.g. --cpus-per-task=8 (default 2; each task runs
# `sweep run --threads` with what Slurm gives it), --partition, --time, --account, --qos.
# --dry-run prints the two job scripts and the sbatch commands instead of submitting them.
# Parts, checkpoints and logs go to OUTPUT.parts/ (shard-K.log, merge.log). Run it on a login
# node from a checkout on a file system the compute nodes share, after `source scripts/build.sh`
# (or `cargo build --release --bin sweep`). Exit status 2: bad arguments, no sbatch on PATH, or
# no sweep binary; 1: sbatch refused a job.
set -euo pipefail
usage() { sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; }
fail() { echo "slurm-array.sh: $*" >&2; exit 2; }

dry_run=0 positional=() sbatch_opts=()
while [ $# -gt 0 ]; do
  case $1 in
    -h | --help) usage; exit 0 ;;
    --dry-run) dry_run=1 ;;
    --) shift; sbatch_opts+=("$@"); break ;;
    -*)
      if [ ${#positional[@]} -lt 3 ]; then
        fail "unknown option '$1' (sbatch options go after CONFIG SHARDS OUTPUT; --help for usage)"
      fi
      sbatch_opts+=("$1") ;;
    *)
      if [ ${#positional[@]} -lt 3 ]; then positional+=("$1"); else sbatch_opts+=("$1"); fi ;;
  esac
  shift
done
if [ ${#positional[@]} -lt 3 ]; then
  usage >&2
  exit 2
fi
config=${positional[0]} shards=${positional[1]} output=${positional[2]}
case $shards in
  '' | *[!0-9]* | 0*) fail "SHARDS must be a positive integer, got '$shards'" ;;
esac
[ -f "$config" ] || fail "config $config: no such file"

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
sweep="$root/target/release/sweep"
missing="" no_slurm=""
[ -x "$sweep" ] || missing="$sweep is not built; build it in $root with
  source scripts/build.sh   (or: cargo build --release --bin sweep)"
command -v sbatch >/dev/null 2>&1 || no_slurm="sbatch not found on PATH: this script submits to a
  Slurm cluster (run it on a login node). Without Slurm, run the shards with
  sweep run CONFIG --shard K/N -o PART   and   sweep merge PARTS... -o TABLE
  (README, \"Long runs: interruption, shards, clusters\")"
if [ "$dry_run" -eq 0 ]; then
  [ -z "$missing" ] || fail "$missing"
  [ -z "$no_slurm" ] || fail "$no_slurm"
else
  for m in "$missing" "$no_slurm"; do [ -z "$m" ] || echo "slurm-array.sh: note: $m" >&2; done
fi

# Absolute paths: the jobs may start in another directory (--chdir among the sbatch options).
config=$(realpath -- "$config")
output=$(realpath -m -- "$output")
parts="$output.parts"
q() { printf '%q' "$1"; }

shard_script="#!/usr/bin/env bash
#SBATCH --job-name=sweep-shard
#SBATCH --array=1-$shards
#SBATCH --cpus-per-task=2
#SBATCH --requeue
#SBATCH --open-mode=append
#SBATCH --output=\"$parts/shard-%a.log\"
# Shard K of $shards (K = the array task id) of $(q "$config").
# A requeued task resumes from its checkpoint; a task whose part is already written does nothing.
set -euo pipefail
k=\$SLURM_ARRAY_TASK_ID
part=$(q "$parts")/part-\$k.bin
echo \"shard \$k/$shards on \$(hostname), job \${SLURM_JOB_ID:-?}, restart \${SLURM_RESTART_COUNT:-0},\" \\
  \"\$(date -u +%FT%TZ)\"
if [ -f \"\$part\" ]; then
  echo \"\$part is already written: nothing to do\"
  exit 0
fi
exec $(q "$sweep") run $(q "$config") --shard \"\$k/$shards\" -o \"\$part\" \\
  --threads \"\${SLURM_CPUS_PER_TASK:-0}\" --resume"

merge_script="#!/usr/bin/env bash
#SBATCH --job-name=sweep-merge
#SBATCH --kill-on-invalid-dep=yes
#SBATCH --output=\"$parts/merge.log\"
# The table from the $shards parts; it starts when every shard task has succeeded (and is
# cancelled if one fails: fix it, then run this script again, which skips finished shards).
set -euo pipefail
parts=()
for k in \$(seq 1 $shards); do parts+=($(q "$parts")/part-\$k.bin); done
exec $(q "$sweep") merge \"\${parts[@]}\" -o $(q "$output")"

quoted_opts=""
for o in "${sbatch_opts[@]}"; do quoted_opts+=" $(q "$o")"; done
if [ "$dry_run" -eq 1 ]; then
  echo "# mkdir -p $(q "$parts")"
  echo "# sbatch --parsable$quoted_opts <<'EOF'   (prints ARRAY_JOB_ID)"
  echo "$shard_script"
  echo "EOF"
  echo "# sbatch --parsable --dependency=afterok:ARRAY_JOB_ID$quoted_opts <<'EOF'"
  echo "$merge_script"
  echo "EOF"
  exit 0
fi

made=0
[ -d "$parts" ] || made=1
mkdir -p "$parts"
array_id=$(sbatch --parsable "${sbatch_opts[@]}" <<<"$shard_script") || {
  echo "slurm-array.sh: sbatch refused the shard array (its message above)" >&2
  [ "$made" -eq 0 ] || rmdir "$parts" 2>/dev/null || true
  exit 1
}
array_id=${array_id%%;*}
merge_id=$(sbatch --parsable --dependency="afterok:$array_id" "${sbatch_opts[@]}" \
  <<<"$merge_script") || {
  echo "slurm-array.sh: sbatch refused the merge job (its message above); the shards run as" \
    "job array $array_id: merge their parts with \`sweep merge $parts/part-*.bin -o $output\`" >&2
  exit 1
}
merge_id=${merge_id%%;*}
echo "submitted shards as job array $array_id and the merge as job $merge_id"
echo "progress: squeue -j $array_id,$merge_id; logs in $parts/"

#!/usr/bin/env bash
# Build a table on a Slurm cluster: one array task per shard, then a merge job that starts when
# every shard has finished. Each task is resumable (a requeued or restarted task continues from
# its checkpoint), and the merged table is identical (datasets) to a single `sweep run`.
#
#   scripts/slurm-array.sh CONFIG SHARDS OUTPUT [extra sbatch options...]
#   scripts/slurm-array.sh configs/full.toml 32 tables/full.h5 --partition=short --time=01:00:00
#
# Run it from the repository root on the login node, after `cargo build --release --bin sweep`
# (scripts/setup.sh installs what the build needs on Debian). Parts and logs go to
# OUTPUT.parts/. Every task uses the CPUs Slurm gives it (--cpus-per-task, default 2 here).
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n '2,12p' "$0" >&2
  exit 2
fi
config=$1 shards=$2 output=$3
shift 3
case $shards in
  '' | *[!0-9]* | 0) echo "SHARDS must be a positive integer, got '$shards'" >&2; exit 2 ;;
esac
[ -f "$config" ] || { echo "config $config: no such file" >&2; exit 2; }
sweep="$(pwd)/target/release/sweep"
[ -x "$sweep" ] || { echo "$sweep missing: run cargo build --release --bin sweep first" >&2; exit 2; }
command -v sbatch >/dev/null || { echo "sbatch not found: this script needs Slurm" >&2; exit 2; }
parts="$output.parts"
mkdir -p "$parts"

array_id=$(sbatch --parsable --array="1-$shards" --cpus-per-task="${CPUS:-2}" \
  --job-name=sweep-shard --output="$parts/shard-%a.log" --requeue "$@" \
  --wrap="$sweep run '$config' --shard \${SLURM_ARRAY_TASK_ID}/$shards \
          -o \"$parts/part-\${SLURM_ARRAY_TASK_ID}.bin\" --threads \${SLURM_CPUS_PER_TASK:-0} \
          --resume")

list=""
for k in $(seq 1 "$shards"); do list="$list '$parts/part-$k.bin'"; done
merge_id=$(sbatch --parsable --dependency="afterok:$array_id" --job-name=sweep-merge \
  --output="$parts/merge.log" "$@" --wrap="$sweep merge $list -o '$output'")

echo "submitted shards as job array $array_id and the merge as job $merge_id"
echo "progress: squeue -j $array_id,$merge_id; logs in $parts/"

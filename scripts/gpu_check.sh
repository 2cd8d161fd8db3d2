#!/usr/bin/env bash
# The CUDA example (examples/cuda/oblique_gpu.cu) on an NVIDIA GPU: device answers against the
# host's and the CLI's, and the throughput of P, a curve and 3-D rebounds. Two steps:
#
#   bash scripts/gpu_check.sh --prepare   where the project builds (no GPU needed): writes out/gpu/
#       full.oblq     sweep export of tables/full.h5 with the curve of two steel spheres
#       cli.csv.gz    `sweep query tables/full.h5 --batch` at 10^6 random points (gamma,alpha,P)
#       oblique_gpu   the example built by scripts/check_cuda.sh (sm_90 code, compute_90 PTX),
#                     used where the GPU machine has no nvcc
#   bash scripts/gpu_check.sh             on the GPU machine, with out/gpu/ copied there: needs no
#       network, HDF5 or Rust; builds the example with the machine's nvcc (-arch=native) when it
#       has one, runs it on the CLI's points and on 2^24 random points and impacts, and writes
#       the report to out/gpu/report.txt (and $OUT/gpu_report.txt when OUT is set). A minute or
#       two: the build, then the runs (each at most 4 minutes, under timeout).
#
# Exit status: 0 when every device answer has the host's and the CLI's status and agrees to
# 1e-12 (the rounding of the device's log, as the header states), 1 otherwise.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
dir=out/gpu
mkdir -p "$dir"

if [ "${1:-}" = "--prepare" ]; then
  bash scripts/check_cuda.sh
  cp target/cuda-check/oblique_gpu "$dir/oblique_gpu"
  [ -x target/release/sweep ] || source scripts/build.sh
  target/release/sweep export tables/full.h5 -o "$dir/full.oblq" --gamma 1.7497858600774299
  # 10^6 random points over every regime (alpha = alpha_c2 u/(1 - u), 1 in 64 no slip), seeded.
  python3 - "$dir/points.csv" <<'EOF'
import random, sys
r = random.Random(7)
with open(sys.argv[1], "w") as f:
    f.write("gamma,alpha\n")
    for _ in range(1_000_000):
        g = 0.1 + 3.4 * r.random()
        u = r.random()
        a = float("inf") if r.random() < 1 / 64 else 2 * g * g / 7 * u / (1 - u)
        f.write(f"{g:.12g},{a:.12g}\n")
EOF
  target/release/sweep query tables/full.h5 --batch "$dir/points.csv" | cut -d, -f1-3 |
    gzip -6 > "$dir/cli.csv.gz"
  rm "$dir/points.csv"
  ls -l "$dir"
  echo "gpu_check: prepared $dir ($(du -sh "$dir" | cut -f1)); on the GPU machine: bash scripts/gpu_check.sh"
  exit 0
fi

for f in full.oblq cli.csv.gz; do
  [ -f "$dir/$f" ] || { echo "gpu_check: $dir/$f is missing: run bash scripts/gpu_check.sh --prepare where the project builds, and copy $dir" >&2; exit 1; }
done
# The report goes to out/gpu/report.txt, and to $OUT/gpu_report.txt when OUT is set.
exec > >(tee "$dir/report.txt" ${OUT:+"$OUT/gpu_report.txt"}) 2>&1
echo "== $(date -u +%FT%TZ) $(uname -m)"
nvidia-smi --query-gpu=name,driver_version,memory.total,clocks.max.sm --format=csv,noheader || true

# The machine's nvcc if it has one, else the one check_cuda.sh installed, else the prebuilt binary.
nvcc="${NVCC:-$(command -v nvcc || true)}"
if [ -z "$nvcc" ]; then
  for c in /usr/local/cuda/bin/nvcc $(ls -d /usr/local/cuda-*/bin/nvcc 2>/dev/null | sort -rV) \
    target/cuda-nvcc/nvidia/cu13/bin/nvcc; do
    if [ -x "$c" ]; then nvcc="$c"; break; fi
  done
fi
exe="$dir/oblique_gpu"
if [ -n "$nvcc" ]; then
  echo "== build: $nvcc ($("$nvcc" --version | sed -n 's/.*release \([0-9.]*\).*/release \1/p'))"
  if timeout 180 "$nvcc" -O2 -fmad=false -arch=native -Xcompiler -ffp-contract=off -I include \
    -o "$dir/oblique_gpu_native" examples/cuda/oblique_gpu.cu; then
    exe="$dir/oblique_gpu_native"
  else
    echo "gpu_check: the build failed; running the prebuilt $exe"
  fi
else
  echo "== no nvcc here: running the prebuilt $exe (nvcc 13.5 from PyPI, sm_90)"
fi
[ -x "$exe" ] || { echo "gpu_check: no $exe and no nvcc" >&2; exit 1; }

status=0
echo "== the CLI's answers (sweep query tables/full.h5 --batch) at 10^6 random points"
gzip -dc "$dir/cli.csv.gz" | timeout 240 "$exe" "$dir/full.oblq" --check - || status=1
echo "== 2^24 random points, curve queries and sphere-sphere impacts"
timeout 240 "$exe" "$dir/full.oblq" 16777216 || status=1
echo "== $([ $status = 0 ] && echo ok || echo FAILED) ($exe)"
exit $status

#!/usr/bin/env bash
# The CUDA example (examples/cuda/oblique_gpu.cu) on an NVIDIA GPU: device answers against the
# host's and the CLI's, and the throughput of P, a curve and 3-D rebounds, for three tables:
# tables/full.h5 (P(gamma, alpha)) and the P(gamma, alpha, e_n) tables tables/default.h5 and
# tables/dissipative.h5 (Kelvin-Voigt law; the latter with knots in its partial-slip patch).
# Two steps:
#
#   bash scripts/gpu_check.sh --prepare   where the project builds (no GPU needed): writes out/gpu/
#       full.oblq         sweep export of tables/full.h5 with the curve of two steel spheres
#       default.oblq      sweep export of tables/default.h5 (an e_n axis, no curves)
#       dissipative.oblq  sweep export of tables/dissipative.h5 (an e_n axis, knots, no curves)
#       full.csv.gz       `sweep query tables/full.h5 --batch` at 10^5 seeded random points
#                         (gamma,alpha,P)
#       default.csv.gz, dissipative.csv.gz   the same at 5 x 10^4 points of each table
#                         (gamma,alpha,e_n,P; fewer points: out/gpu stays under 40 MiB)
#       oblique_gpu       the example built by scripts/check_cuda.sh (sm_90 code, compute_90 PTX),
#                         used where the GPU machine has no nvcc
#   bash scripts/gpu_check.sh             on the GPU machine, with out/gpu/ copied there: needs no
#       network, HDF5 or Rust; builds the example with the machine's nvcc (-arch=native) when it
#       has one, then for each table runs it on the CLI's points and on 2^24 random points and
#       impacts, and writes the report to out/gpu/report.txt (and $OUT/gpu_report.txt when OUT
#       is set). A few minutes: the build (at most 3 minutes), then six runs, each under
#       timeout, all of them within 7 minutes of the start.
#
# GPU_CHECK_N=N sets the number of random points and impacts (default 2^24 = 16777216).
#
# Exit status: 0 when every device answer has the host's and the CLI's status and agrees to
# 1e-12 (the rounding of the device's log, as the header states), 1 otherwise.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
dir=out/gpu
tables=(full default dissipative)
mkdir -p "$dir"

if [ "${1:-}" = "--prepare" ]; then
  bash scripts/check_cuda.sh
  cp target/cuda-check/oblique_gpu "$dir/oblique_gpu"
  [ -x target/release/sweep ] || source scripts/build.sh
  # Nothing else travels: a run's binary and report, and full.csv.gz under an older name.
  rm -f "$dir/oblique_gpu_native" "$dir/report.txt" "$dir/cli.csv.gz"
  seed=7
  for t in "${tables[@]}"; do
    if [ "$t" = full ]; then
      target/release/sweep export tables/full.h5 -o "$dir/full.oblq" --gamma 1.7497858600774299
    else
      target/release/sweep export "tables/$t.h5" -o "$dir/$t.oblq"
    fi
    # 10^5 (full) or 5 x 10^4 (e_n tables) random points over every regime, seeded: gamma
    # uniform over the table's domain, alpha = alpha_c2 u/(1 - u), 1 in 64 no slip; with an e_n
    # axis (the export's header, docs/export-format.md) e_n uniform over its range, 1 in 32
    # each exactly at 1, e_n_min and e_n_max; where partial_high has knots (version 5 or 7), a third
    # in partial slip inside the knots' region (alpha uniform over alpha_c1(gamma, e_n) to
    # alpha_c2, from 0 without the full-slip line).
    points=100000
    [ "$t" = full ] || points=50000
    python3 - "$dir/$t.oblq" "$dir/points.csv" "$seed" "$points" <<'PY'
import random, struct, sys
with open(sys.argv[1], "rb") as f:
    d = f.read()
version, = struct.unpack_from("<I", d, 8)
g_lo, g_hi, a_max = struct.unpack_from("<3d", d, 32)
no_line, = struct.unpack_from("<I", d, 68)
e_n = 2 <= version <= 5 or version == 7  # version 6: an elastic table with split masks
e_lo, e_hi = struct.unpack_from("<2d", d, 96) if e_n else (1.0, 1.0)
box = None
rec = struct.unpack_from("<Q", d, 72)[0] + 160
# The knots' region of partial_high (record 1; version 5, or 7 where it has a block), root
# cells to gamma and e_n.
if version == 5 or (version == 7 and struct.unpack_from("<Q", d, rec + 152)[0]):
    p_lo, p_hi = struct.unpack_from("<2d", d, rec + 8)
    bg, = struct.unpack_from("<I", d, rec + 24)
    be, = struct.unpack_from("<I", d, rec + 136)
    kb, = struct.unpack_from("<Q", d, rec + 152)
    rg0, rg1, re0, re1 = struct.unpack_from("<4d", d, kb + 48)
    wg, we = (p_hi - p_lo) / bg, (e_hi - e_lo) / be
    box = (p_lo + rg0 * wg, p_lo + rg1 * wg, e_lo + re0 * we, e_lo + re1 * we)
r = random.Random(int(sys.argv[3]))
with open(sys.argv[2], "w") as f:
    f.write("gamma,alpha,e_n\n" if e_n else "gamma,alpha\n")
    for i in range(int(sys.argv[4])):
        if box and i % 3 == 0:
            g = box[0] + (box[1] - box[0]) * r.random()
            e = box[2] + (box[3] - box[2]) * r.random()
            c1 = 0.0 if no_line else 2 * g * g / (7 * (g * g * (1 + e) - e))
            a = c1 + (2 * g * g / 7 - c1) * r.random()
            f.write(f"{g:.12g},{a:.12g},{e:.12g}\n")
            continue
        g = g_lo + (g_hi - g_lo) * r.random()
        u = r.random()
        a = float("inf") if r.random() < 1 / 64 else 2 * g * g / 7 * u / (1 - u)
        if a > a_max:
            a = a_max * r.random()
        if not e_n:
            f.write(f"{g:.12g},{a:.12g}\n")
            continue
        v = r.random()
        e = (min(1.0, e_hi) if v < 1 / 32 else e_lo if v < 2 / 32 else e_hi if v < 3 / 32
             else e_lo + (e_hi - e_lo) * r.random())
        f.write(f"{g:.12g},{a:.12g},{e:.12g}\n")
PY
    cols=1-3
    [ "$t" = full ] || cols=1-4
    target/release/sweep query "tables/$t.h5" --batch "$dir/points.csv" | cut -d, -f$cols |
      gzip -6 > "$dir/$t.csv.gz"
    rm "$dir/points.csv"
    seed=$((seed + 1))
  done
  ls -l "$dir"
  echo "gpu_check: prepared $dir ($(du -sh "$dir" | cut -f1)); on the GPU machine: bash scripts/gpu_check.sh"
  exit 0
fi

for t in "${tables[@]}"; do
  for f in "$t.oblq" "$t.csv.gz"; do
    [ -f "$dir/$f" ] || { echo "gpu_check: $dir/$f is missing: run bash scripts/gpu_check.sh --prepare where the project builds, and copy $dir" >&2; exit 1; }
  done
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

# Each run at most 120 s, and all of them within 420 s of the start (the build included).
status=0
n="${GPU_CHECK_N:-16777216}"
limit() {
  local left=$((420 - SECONDS))
  [ $left -lt 120 ] || left=120
  [ $left -gt 1 ] || left=1
  echo $left
}
for t in "${tables[@]}"; do
  echo "== $t: tables/$t.h5, the CLI's answers (sweep query tables/$t.h5 --batch) at $([ "$t" = full ] && echo "10^5" || echo "5 x 10^4") random points"
  gzip -dc "$dir/$t.csv.gz" | timeout "$(limit)" "$exe" "$dir/$t.oblq" --check - ||
    { rc=$?; status=1; [ $rc != 124 ] || echo "gpu_check: $t: timed out"; }
  echo "== $t: tables/$t.h5, $n random points$([ "$t" = full ] && echo ", curve queries") and impacts"
  timeout "$(limit)" "$exe" "$dir/$t.oblq" "$n" ||
    { rc=$?; status=1; [ $rc != 124 ] || echo "gpu_check: $t: timed out"; }
done
echo "== $([ $status = 0 ] && echo ok || echo FAILED) ($exe, ${SECONDS} s)"
exit $status

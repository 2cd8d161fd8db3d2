#!/usr/bin/env bash
# The evaluator header in CUDA device code, checked without a GPU: installs nvcc from PyPI (the
# nvidia-cuda-nvcc wheel and the three it needs, pinned, into target/cuda-nvcc: about 320 MB,
# a few seconds) and compiles, with every warning an error (nvcc's own and the host compiler's):
#   tests/cuda/device_check.cu   one kernel that calls every function the header marks OBLQ_FN
#   examples/cuda/oblique_gpu.cu the CUDA example, linked (sm_90 code and compute_90 PTX) into
#                                target/cuda-check/oblique_gpu; nothing runs
# and makes sure those flags refuse a host-only call (memcmp) in a __host__ __device__ function:
# nvcc only warns about one by default, and such a kernel then silently does nothing.
# NVCC=/path/to/nvcc uses that compiler instead of the wheel (no install).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
wheel=target/cuda-nvcc
out=target/cuda-check
nvcc="${NVCC:-$wheel/nvidia/cu13/bin/nvcc}"
if [ ! -x "$nvcc" ]; then
  echo "check_cuda: installing nvcc 13.5 from PyPI into $wheel" >&2
  PIP_ROOT_USER_ACTION=ignore python3 -m pip install --quiet --disable-pip-version-check \
    --upgrade --target "$wheel" nvidia-cuda-nvcc==13.5.37 nvidia-cuda-crt==13.5.37 \
    nvidia-nvvm==13.5.37 nvidia-cuda-runtime==13.5.37
fi
mkdir -p "$out"
flags=(-O2 -fmad=false -Werror all-warnings -Xcompiler -Wall,-Wextra,-Werror,-ffp-contract=off
  -I include)

# The flags must turn a host-only call in device code into an error.
cat > "$out/host_call.cu" <<'EOF'
#include <string.h>
__host__ __device__ static inline int f(const char *s) { return memcmp(s, "OBLQ", 4); }
__global__ void k(const char *s, int *r) { *r = f(s); }
EOF
if "$nvcc" "${flags[@]}" -c "$out/host_call.cu" -o "$out/host_call.o" 2> "$out/host_call.log"; then
  echo "check_cuda: a host-only call (memcmp) in device code compiled: the flags let it through" >&2
  exit 1
fi
if ! grep -q 'calling a __host__ function("memcmp")' "$out/host_call.log"; then
  echo "check_cuda: the host-only call failed for another reason:" >&2
  cat "$out/host_call.log" >&2
  exit 1
fi

# Device code is generated only for the functions a kernel reaches: the check's kernel must call
# every public function of the header (the internal oblq__ ones are reached through them).
missing=$(grep -oE '^OBLQ_FN [^(]*\boblq_[a-z][a-z0-9_]*\(' include/oblique_eval.h |
  grep -oE 'oblq_[a-z0-9_]+\($' | sort -u | while read -r f; do
    grep -qF "$f" tests/cuda/device_check.cu || echo "${f%(}"
  done)
if [ -n "$missing" ]; then
  echo "check_cuda: tests/cuda/device_check.cu does not call:" $missing >&2
  exit 1
fi
"$nvcc" "${flags[@]}" -c tests/cuda/device_check.cu -o "$out/device_check.o"
"$nvcc" "${flags[@]}" -gencode arch=compute_90,code='[sm_90,compute_90]' \
  -o "$out/oblique_gpu" examples/cuda/oblique_gpu.cu
echo "check_cuda: every OBLQ_FN function and examples/cuda compile for the device" \
  "($("$nvcc" --version | sed -n 's/.*release \([0-9.]*\).*/nvcc \1/p'), warnings as errors)"

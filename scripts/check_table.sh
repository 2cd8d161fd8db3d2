#!/usr/bin/env bash
# Check a P(gamma, alpha) table written by `sweep run` (docs/table-format.md):
#   1. h5dump can read its header (a well-formed HDF5 file);
#   2. the Python reference reader (scripts/read_table.py) reproduces every held-out
#      /checks/P_interpolated to 1e-12;
#   3. the table agrees with direct simulations (`sweep impact --tol 1e-8`) at 12 deterministic
#      points over all patches to MAX_ERROR (default 1e-5).
# Usage: scripts/check_table.sh TABLE        (CI: scripts/check_table.sh tables/full.h5)
# Environment: SWEEP (sweep binary, default target/release/sweep, built if missing),
#              MAX_ERROR (default 1e-5), PYTHON (default python3).
# Exits non-zero on the first failure.
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 TABLE" >&2
  exit 2
fi
table="$1"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/.." && pwd)"
python="${PYTHON:-python3}"
max_error="${MAX_ERROR:-1e-5}"
sweep="${SWEEP:-$root/target/release/sweep}"

if [ ! -f "$table" ]; then
  echo "check_table: $table: no such file" >&2
  exit 1
fi

# Without h5py and numpy, the checks' own virtual environment (scripts/venv.sh; nothing is
# installed into the system's Python).
if ! "$python" -c 'import h5py, numpy' >/dev/null 2>&1; then
  source "$root/scripts/venv.sh"
  python="$OBLIQUE_VENV/bin/python3"
  "$python" -c 'import h5py, numpy' || {
    echo "check_table: h5py/numpy still not importable" >&2
    exit 1
  }
fi

if ! command -v h5dump >/dev/null 2>&1; then
  echo "check_table: h5dump not found (run scripts/setup.sh: Debian package hdf5-tools)" >&2
  exit 1
fi

if [ ! -x "$sweep" ]; then
  echo "check_table: building $sweep" >&2
  # shellcheck source=setup.sh
  source "$here/setup.sh"
  (cd "$root" && cargo build --release --quiet --bin sweep)
fi

echo "== h5dump -H $table"
if ! h5dump -H "$table" >/dev/null; then
  echo "check_table: FAIL: h5dump cannot read $table" >&2
  exit 1
fi
echo "ok"

echo "== held-out checks (read_table.py --check-stored)"
"$python" "$here/read_table.py" "$table" --check-stored

echo "== against sweep impact (read_table.py --check-against-sweep 12 --max-error $max_error)"
"$python" "$here/read_table.py" "$table" --check-against-sweep 12 --max-error "$max_error" \
  --sweep "$sweep"

echo "check_table: $table passed"

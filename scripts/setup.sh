#!/usr/bin/env bash
# Install what the project needs beyond the Rust toolchain (Debian): the HDF5 C library and
# pkg-config. Idempotent: does nothing when they are present. Sourced by scripts/sweep and
# scripts/test.
set -euo pipefail
need=()
dpkg -s libhdf5-dev >/dev/null 2>&1 || need+=(libhdf5-dev)
command -v pkg-config >/dev/null 2>&1 || need+=(pkg-config)
command -v h5dump >/dev/null 2>&1 || need+=(hdf5-tools)
# Extra packages a caller needs (scripts/test: the compilers of the C/C++/Fortran checks).
for pkg in ${OBLIQUE_SETUP_EXTRA:-}; do
  dpkg -s "$pkg" >/dev/null 2>&1 || need+=("$pkg")
done
if [ ${#need[@]} -gt 0 ]; then
  echo "setup: installing ${need[*]} with apt-get (once; about a minute)..." >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  log="$(mktemp)"
  if ! { $SUDO apt-get update -qq &&
    DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}"; } >"$log" 2>&1; then
    cat "$log" >&2
    echo "setup: apt-get failed (its output above); install ${need[*]} by hand" >&2
    rm -f "$log"
    exit 1
  fi
  rm -f "$log"
  echo "setup: installed ${need[*]}" >&2
fi
# hdf5-metno's build script finds Debian's HDF5 through pkg-config, as a plain `cargo build`
# does: no HDF5_DIR, so that the README's cargo commands and scripts/sweep share one build
# (a different HDF5_DIR rebuilds hdf5-metno-sys and everything above it). Only where
# pkg-config cannot find HDF5 is Debian's serial directory named.
if [ -z "${HDF5_DIR:-}" ] && ! pkg-config --exists hdf5 2>/dev/null &&
  [ -d /usr/lib/x86_64-linux-gnu/hdf5/serial ]; then
  export HDF5_DIR=/usr/lib/x86_64-linux-gnu/hdf5/serial
fi

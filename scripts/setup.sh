#!/usr/bin/env bash
# Install what the project needs beyond the Rust toolchain (Debian): the HDF5 C library and
# pkg-config. Idempotent: does nothing when they are present.
set -euo pipefail
need=()
dpkg -s libhdf5-dev >/dev/null 2>&1 || need+=(libhdf5-dev)
command -v pkg-config >/dev/null 2>&1 || need+=(pkg-config)
command -v h5dump >/dev/null 2>&1 || need+=(hdf5-tools)
if [ ${#need[@]} -gt 0 ]; then
  echo "setup: installing ${need[*]} (apt-get)" >&2
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${need[@]}" >/dev/null
fi
# HDF5 on Debian lives under an architecture/serial directory; tell hdf5-metno's build script.
if [ -z "${HDF5_DIR:-}" ] && [ -d /usr/lib/x86_64-linux-gnu/hdf5/serial ]; then
  export HDF5_DIR=/usr/lib/x86_64-linux-gnu/hdf5/serial
fi

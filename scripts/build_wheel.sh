#!/usr/bin/env bash
# Builds the portable wheel of the Python package: see --help.
set -euo pipefail
usage() {
  cat <<'EOF'
Usage: scripts/build_wheel.sh [OUT_DIR]

Builds the Python package `oblique` as one wheel that installs with pip on any x86-64 Linux
with glibc 2.28 or newer (RHEL/Rocky/Alma 8 and later, Ubuntu 20.04 and later, Debian 10 and
later) and CPython 3.9 or newer (abi3), with neither Rust nor HDF5 installed there:

  OUT_DIR/oblique-VERSION-cp39-abi3-manylinux_2_28_x86_64.whl   (OUT_DIR: target/wheel-dist)

How: maturin links the extension with zig's C toolchain against glibc 2.28's symbols (--zig
--compatibility manylinux_2_28), and the package feature `static-hdf5` compiles HDF5 and zlib
from source (crates hdf5-metno-src and libz-sys) into the extension, so the wheel needs no
libhdf5. The tools (maturin, auditwheel, ziglang, cmake; pinned) are installed once with pip
into target/wheel-tools; the build has its own folder, target/wheel-build, so that it leaves
the project's release build alone. From nothing it takes about 3 minutes on 2 cores.

`auditwheel show` must find the wheel consistent with manylinux_2_28, or the script fails.
The environment's CARGO_TARGET_DIR is not used (the folder above is).

Options:
  -h, --help   this text
EOF
}
case "${1:-}" in
  -h | --help)
    usage
    exit 0
    ;;
  -*)
    echo "build_wheel: unknown option '$1' (see --help)" >&2
    exit 2
    ;;
esac
[ $# -le 1 ] || {
  echo "build_wheel: at most one argument, OUT_DIR (see --help)" >&2
  exit 2
}
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dist="${1:-$root/target/wheel-dist}"
tools="$root/target/wheel-tools"
fail() {
  echo "build_wheel: $*" >&2
  exit 1
}
# The pinned tools. ziglang provides `python3 -m ziglang` (zig cc, the linker and the C compiler
# of HDF5 and zlib against glibc 2.28); cmake builds HDF5.
pins=(maturin==1.16.0 auditwheel==6.8.2 ziglang==0.17.1 cmake==4.4.5)
if ! [ -x "$tools/bin/maturin" ] || ! [ -x "$tools/bin/cmake" ] ||
  ! "$tools/bin/python3" -c 'import auditwheel, ziglang' >/dev/null 2>&1; then
  echo "build_wheel: installing ${pins[*]} into $tools (pip, once)" >&2
  rm -rf "$tools"
  python3 -m venv "$tools" || fail "\`python3 -m venv $tools\` failed (Debian: apt-get install python3-venv)"
  "$tools/bin/python3" -m pip install --quiet --disable-pip-version-check "${pins[@]}" ||
    fail "pip could not install ${pins[*]}"
fi
mkdir -p "$dist"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT
t0=$(date +%s)
echo "build_wheel: building the manylinux_2_28 wheel (target/wheel-build; minutes from nothing)" >&2
# maturin runs zig through the tools' python3 (`python3 -m ziglang`), and cmake from PATH.
if ! PATH="$tools/bin:$PATH" CARGO_TARGET_DIR="$root/target/wheel-build" \
  maturin build --release --strip -m "$root/python/Cargo.toml" --features static-hdf5 \
  --zig --compatibility manylinux_2_28 -o "$dist" >"$log" 2>&1; then
  cat "$log" >&2
  fail "maturin build failed (its output above)"
fi
wheel="$(sed -n 's/.*Built wheel for .* to \(.*\.whl\)$/\1/p' "$log" | tail -1)"
[ -n "$wheel" ] && [ -f "$wheel" ] || {
  cat "$log" >&2
  fail "maturin named no wheel (its output above)"
}
case "$(basename "$wheel")" in
  *-cp39-abi3-manylinux_2_28_x86_64.whl) ;;
  *) fail "$(basename "$wheel"): not an abi3 manylinux_2_28 wheel" ;;
esac
show="$("$tools/bin/auditwheel" show "$wheel" 2>&1)" || fail "auditwheel show failed: $show"
echo "$show" | tr '\n' ' ' | grep -q 'consistent with the following platform tag: "manylinux_2_28_x86_64"' ||
  fail "auditwheel show does not find manylinux_2_28: $show"
echo "build_wheel: $wheel ($(($(stat -c %s "$wheel") / 1024)) KiB, manylinux_2_28 by auditwheel show) in $(($(date +%s) - t0)) s" >&2
echo "$wheel"

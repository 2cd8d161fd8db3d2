#!/usr/bin/env bash
# Installs the C library of oblique-lookup (the crate oblique-lookup-capi) into PREFIX, laid out as
# cargo-c would, for C and C++ programs built with pkg-config. See --help.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: scripts/install-capi.sh [--help] PREFIX

Builds the crate oblique-lookup-capi (cargo build --release -p oblique-lookup-capi; nothing is
recompiled when it is up to date) and installs:

  PREFIX/lib/liboblique.so.X.Y.Z      the shared library (stripped), SONAME liboblique.so.0
  PREFIX/lib/liboblique.so.0          -> liboblique.so.X.Y.Z
  PREFIX/lib/liboblique.so            -> liboblique.so.0
  PREFIX/lib/liboblique.a             the static library (debug info stripped)
  PREFIX/include/oblique_lookup.h     the header (C99 and later, C++11 and later)
  PREFIX/lib/pkgconfig/oblique.pc     for pkg-config: Cflags, Libs and, for --static, Libs.private

X.Y.Z is the crate's version. PREFIX is created if missing. With DESTDIR set, the files go
under DESTDIR/PREFIX (PREFIX must then be absolute) while oblique.pc names PREFIX, for packaging.
The environment's CARGO (default: cargo), CARGO_TARGET_DIR and HDF5_DIR are honoured.

Then, for example:

  export PKG_CONFIG_PATH=PREFIX/lib/pkgconfig
  cc -std=c99 -O2 -o query crates/lookup-capi/examples/query.c $(pkg-config --cflags --libs oblique)
  LD_LIBRARY_PATH=PREFIX/lib ./query tables/quick.h5
EOF
}

prefix=""
for arg in "$@"; do
  case "$arg" in
    -h | --help)
      usage
      exit 0
      ;;
    -*)
      echo "install-capi: unknown option '$arg' (see --help)" >&2
      exit 2
      ;;
    *)
      if [ -n "$prefix" ]; then
        echo "install-capi: one PREFIX only (see --help)" >&2
        exit 2
      fi
      prefix="$arg"
      ;;
  esac
done
if [ -z "$prefix" ]; then
  usage >&2
  exit 2
fi

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
# HDF5_DIR (and the HDF5 library and pkg-config, once, when missing), as for every build here: a
# different HDF5_DIR would make cargo rebuild the HDF5 bindings.
source "$root/scripts/setup.sh"
cargo="${CARGO:-cargo}"
destdir="${DESTDIR:-}"
if [ -n "$destdir" ]; then
  case "$prefix" in
    /*) ;;
    *)
      echo "install-capi: with DESTDIR, PREFIX must be an absolute path (got '$prefix')" >&2
      exit 2
      ;;
  esac
else
  mkdir -p "$prefix"
  prefix="$(cd "$prefix" && pwd)"
fi
dest="$destdir$prefix"
for tool in strip readelf; do
  if ! command -v "$tool" >/dev/null 2>&1; then
    echo "install-capi: '$tool' not found (Debian: apt-get install binutils)" >&2
    exit 1
  fi
done

scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT

# 1. Build. The JSON messages name the artifacts and the native libraries the build scripts of
# the dependencies link (HDF5); cargo's progress and diagnostics still go to stderr.
messages="$scratch/messages.json"
if ! "$cargo" build --release -p oblique-lookup-capi --manifest-path "$root/Cargo.toml" \
  --message-format=json-render-diagnostics >"$messages"; then
  echo "install-capi: the build failed (cargo's messages above)" >&2
  exit 1
fi
manifest="$root/crates/lookup-capi/Cargo.toml"
artifact="$(grep '"reason":"compiler-artifact"' "$messages" |
  grep -F "\"manifest_path\":\"$manifest\"" | grep -F '/liboblique.so"' | tail -n 1)" || true
if [ -z "$artifact" ]; then
  echo "install-capi: cargo reported no liboblique.so of $manifest" >&2
  exit 1
fi
# The package id ends in the version: "path+file:///…/lookup-capi#oblique-lookup-capi@0.1.0".
version="$(sed -n 's/.*"package_id":"[^"]*[#@]\([0-9][0-9A-Za-z.+-]*\)".*/\1/p' <<<"$artifact")"
if [ -z "$version" ]; then
  echo "install-capi: no version in cargo's message: $artifact" >&2
  exit 1
fi
so="$(grep -o '"[^"]*/liboblique\.so"' <<<"$artifact" | tr -d '"')" || true
archive="$(grep -o '"[^"]*/liboblique\.a"' <<<"$artifact" | tr -d '"')" || true
for f in "$so" "$archive"; do
  if [ -z "$f" ] || [ ! -f "$f" ]; then
    echo "install-capi: cargo did not produce liboblique.so and liboblique.a (crate-type)" >&2
    exit 1
  fi
done
soname="$(readelf -d "$so" | sed -n 's/.*Library soname: \[\(.*\)\].*/\1/p')"
case "$soname" in
  liboblique.so.[0-9]*) ;;
  *)
    echo "install-capi: $so has SONAME '$soname', not liboblique.so.N (crates/lookup-capi/build.rs)" >&2
    exit 1
    ;;
esac

# 2. What a program linking liboblique.a needs besides it (pkg-config --static): the native
# libraries of the dependencies, from their build scripts' messages (HDF5: a -L and -lhdf5), then
# those of Rust's standard library, which rustc prints for a static library (an empty one here,
# which takes a second and leaves the project's build alone). Together they are what
# `cargo rustc -p oblique-lookup-capi --crate-type staticlib -- --print native-static-libs`
# prints, plus the -L folders it leaves out.
private=()
add_private() {
  local flag="$1" have
  for have in "${private[@]+"${private[@]}"}"; do
    if [ "$have" = "$flag" ]; then return 0; fi
  done
  private+=("$flag")
}
json_list() { # json_list KEY LINE: the strings of the JSON array KEY in LINE, one per line
  grep -o "\"$1\":\[[^]]*\]" <<<"$2" | sed -e 's/^[^[]*\[//' -e 's/\]$//' | tr ',' '\n' |
    sed -n 's/^"\(.*\)"$/\1/p'
}
while IFS= read -r line; do
  while IFS= read -r path; do
    case "$path" in
      native=* | all=*) path="${path#*=}" ;;
      *=*) continue ;; # dependency=, crate=, framework=: not for the C linker
    esac
    if [ -d "$path" ]; then add_private "-L$path"; fi
  done < <(json_list linked_paths "$line")
  while IFS= read -r lib; do
    case "$lib" in
      static:*-bundle*=*) lib="${lib#*=}" ;;     # not bundled: the C linker needs it
      static=* | static:*=*) continue ;;           # bundled into liboblique.a
      *=*) lib="${lib#*=}" ;;
    esac
    add_private "-l${lib%%:*}"
  done < <(json_list linked_libs "$line")
done < <(grep '"reason":"build-script-executed"' "$messages")
rustc="${RUSTC:-rustc}"
: >"$scratch/empty.rs"
if ! std_libs="$("$rustc" --crate-type staticlib --crate-name empty --edition 2021 \
  --print native-static-libs -o "$scratch/libempty.a" "$scratch/empty.rs" 2>&1)"; then
  echo "$std_libs" >&2
  echo "install-capi: '$rustc' failed to list the standard library's native libraries" >&2
  exit 1
fi
std_libs="$(sed -n 's/^note: native-static-libs: //p' <<<"$std_libs")"
if [ -z "$std_libs" ]; then
  echo "install-capi: '$rustc --print native-static-libs' printed no list" >&2
  exit 1
fi
for flag in $std_libs; do
  private+=("$flag") # in rustc's order, duplicates included: they can matter
done

# 3. Install.
lib="$dest/lib"
real="liboblique.so.$version"
install -d "$lib/pkgconfig" "$dest/include"
install -m 0755 "$so" "$lib/$real.tmp"
strip --strip-unneeded "$lib/$real.tmp"
mv -f "$lib/$real.tmp" "$lib/$real"
ln -sfn "$real" "$lib/$soname"
ln -sfn "$soname" "$lib/liboblique.so"
install -m 0644 "$archive" "$lib/liboblique.a.tmp"
strip --strip-debug "$lib/liboblique.a.tmp"
mv -f "$lib/liboblique.a.tmp" "$lib/liboblique.a"
install -m 0644 "$root/crates/lookup-capi/include/oblique_lookup.h" "$dest/include/oblique_lookup.h"
cat >"$lib/pkgconfig/oblique.pc" <<EOF
prefix=$prefix
exec_prefix=\${prefix}
libdir=\${exec_prefix}/lib
includedir=\${prefix}/include

Name: oblique
Description: P(gamma, alpha) table lookup and rebound queries of oblique impacts with friction (C ABI of oblique-lookup)
Version: $version
Libs: -L\${libdir} -loblique
Libs.private: ${private[*]}
Cflags: -I\${includedir}
EOF

size() { stat -c %s "$1"; }
echo "install-capi: installed oblique $version into $dest" >&2
echo "  lib/$real ($(size "$lib/$real") bytes; unstripped $(size "$so")), lib/$soname, lib/liboblique.so" >&2
echo "  lib/liboblique.a ($(size "$lib/liboblique.a") bytes; unstripped $(size "$archive"))" >&2
echo "  include/oblique_lookup.h, lib/pkgconfig/oblique.pc" >&2

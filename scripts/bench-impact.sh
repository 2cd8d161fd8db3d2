#!/usr/bin/env bash
# Single-impact benchmark: the accurate scheme refined to an estimated error <= 1e-6
# (and 1e-5) against the seed's explicit Euler scheme at a true error <= 1e-5. Installs what is
# missing, runs `cargo bench --bench impact` with the given arguments (criterion's), then prints
# the criterion medians as a table (docs/benchmarks.md). IMPACT_BENCH_CLOCK=cpu measures thread
# CPU time instead of elapsed time (for a busy machine). Examples:
#   scripts/bench-impact.sh                        # everything (about 2 minutes)
#   scripts/bench-impact.sh accurate_1e-6          # a subset, by criterion filter
#   scripts/bench-impact.sh 'euler/g3'
#   IMPACT_BENCH_SEARCH=1 scripts/bench-impact.sh  # redo the Euler resolution search (~45 min)
# Criterion's data: target/criterion/<group>/<case>/new/estimates.json.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$here/.."
source scripts/setup.sh
cargo bench --bench impact -- "$@"
if [ -n "${IMPACT_BENCH_SEARCH:-}" ] || ! command -v python3 >/dev/null 2>&1; then
  exit 0
fi
python3 - <<'PY'
import json, os
root = "target/criterion"
def median(group, case):
    path = os.path.join(root, group, case, "new", "estimates.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)["median"]["point_estimate"] * 1e-9
def fmt(t):
    if t is None:
        return "-"
    if t >= 1:
        return f"{t:.3g} s"
    return f"{t * 1e3:.3g} ms" if t >= 1e-3 else f"{t * 1e6:.3g} µs"
def ratio(num, den):
    if not num or not den:
        return "-"
    r = num / den
    return f"{r:.2f}×" if r < 1 else f"{r:.1f}×" if r < 10 else f"{r:.0f}×"
for suffix, clock in (("", "elapsed time"), ("_cpu", "thread CPU time")):
    groups = [g + suffix for g in ("accurate_1e-6", "accurate_1e-5", "euler")]
    if not any(os.path.isdir(os.path.join(root, g)) for g in groups):
        continue
    print(f"\nmedians, {clock} (criterion, latest run of each case):")
    print("| γ | α | accurate 1e-6 | accurate 1e-5 | euler 1e-5 | euler / acc 1e-6 | euler / acc 1e-5 |")
    print("|---|---|---|---|---|---|---|")
    for g in ["0.5", "1.754", "3"]:
        for a in ["0.3", "1", "inf"]:
            case = f"g{g}_a_inf" if a == "inf" else f"g{g}_a{a}"
            t6, t5, te = (median(grp, case) for grp in groups)
            alpha = "∞" if a == "inf" else a
            print(f"| {g} | {alpha} | {fmt(t6)} | {fmt(t5)} | {fmt(te)} | {ratio(te, t6)} | {ratio(te, t5)} |")
PY

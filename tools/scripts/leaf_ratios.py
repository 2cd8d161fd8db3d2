"""Each leaf's largest error against its own prediction, from `probe` output.

    python3 tools/scripts/leaf_ratios.py TABLE PROBE_OUT.csv [LAMBDA]

PROBE_OUT.csv is what `target/release/probe TABLE TOL` prints (its last column names each
point's patch and leaf). For every leaf that holds a point: the largest error over the leaf's
`leaf_predicted_error`, and over its own bound `leaf_predicted_error + LAMBDA * max
error_estimate` (LAMBDA: 4.34 with an e_n axis, the default; 2.66 without). Prints the median,
90 %, 99 % and largest of the first ratio, how many leaves exceed 1, and the largest of the
second (docs/accuracy.md, "The default table")."""
import csv
import sys

import h5py
import numpy as np


def main() -> None:
    table, rows_path = sys.argv[1], sys.argv[2]
    lam = float(sys.argv[3]) if len(sys.argv) > 3 else 4.34
    with h5py.File(table, "r") as f:
        pred, est = {}, {}
        for name, p in f["patches"].items():
            pred[name] = p["leaf_predicted_error"][...]
            e = p["error_estimate"][...]
            est[name] = e.reshape(e.shape[0], -1).max(axis=1)
    by_pred: dict = {}
    by_bound: dict = {}
    largest = 0.0
    with open(rows_path) as fh:
        for r in csv.reader(fh):
            if not r or r[8] == "-":
                continue
            patch, leaf_s = r[8].split(":")
            leaf, err = int(leaf_s), float(r[7])
            largest = max(largest, err)
            key = (patch, leaf)
            p = pred[patch][leaf]
            by_pred[key] = max(by_pred.get(key, 0.0), err / p)
            by_bound[key] = max(by_bound.get(key, 0.0), err / (p + lam * est[patch][leaf]))
    v = np.array(sorted(by_pred.values()))
    q = np.quantile(v, [0.5, 0.9, 0.99, 1.0])
    print(f"largest error {largest:.3e}; {len(v)} leaves")
    print("error / prediction: median %.2f, 90%% %.2f, 99%% %.2f, largest %.2f; above 1: %d"
          % (q[0], q[1], q[2], q[3], int((v > 1).sum())))
    print("error / leaf bound: largest %.2f" % max(by_bound.values()))


if __name__ == "__main__":
    main()

"""Build a table from Python, as `sweep run` does, and query it.

    python3 python/examples/build_table.py [CONFIG [OUTPUT]]

CONFIG defaults to the repository's configs/dissipative-pair.toml (alumina-96 on soda-lime
glass, e_n from 0.5 to 1: about 7 s on 2 cores), found from this file's place; OUTPUT to the
config's `output` (out/dissipative-pair.h5), relative to the current directory.
"""

import sys
from pathlib import Path

import numpy as np

import oblique

CONFIG = Path(__file__).resolve().parents[2] / "configs" / "dissipative-pair.toml"
config = sys.argv[1] if len(sys.argv) > 1 else CONFIG
output = sys.argv[2] if len(sys.argv) > 2 else None

# Progress goes to stderr; Ctrl-C stops the build with its finished nodes kept, and
# build_table(..., resume=True) continues it.
path = oblique.build_table(config, output)
table = oblique.Table(path)
print(table)
info = table.info
print(f"{info['checks']} held-out checks, largest error {info['checks_max_error']:.1e}")
gamma = table.pair_gamma if table.pair_gamma is not None else 1.754
alpha = np.array([0.1, 0.3, 1.0, np.inf])
print("alpha          :", alpha)
print("P(gamma, e_n=1):", np.round(table.p(gamma, alpha), 6))

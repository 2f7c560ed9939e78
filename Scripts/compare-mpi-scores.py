#!/usr/bin/env python3
# Compares the score arrays two runs of BenchmarkScoresMPI wrote with --write-scores=DIR
# (e.g. 1 and 2 processes): View Coverage must be identical, Blur and Needle within the
# relative tolerance (default 1e-12; only the order of the sums over views differs).
#   /usr/bin/python3 Scripts/compare-mpi-scores.py DIR_ONE DIR_TWO [--rtol=1e-12]
import sys

import numpy as np

dirs = [a for a in sys.argv[1:] if not a.startswith("--")]
rtol = float(next((a.split("=", 1)[1] for a in sys.argv[1:] if a.startswith("--rtol=")), 1e-12))
if len(dirs) != 2:
    sys.exit(__doc__ or "usage: compare-mpi-scores.py DIR_ONE DIR_TWO [--rtol=1e-12]")
ok = True
for name in ("ViewCoverage", "BlurScore", "NeedleScore"):
    a, b = (np.fromfile(f"{d}/{name}.f64", dtype=np.float64) for d in dirs)
    if a.shape != b.shape:
        print(f"{name}: {a.size} against {b.size} values")
        ok = False
        continue
    same_nan = np.array_equal(np.isnan(a), np.isnan(b))
    finite = ~np.isnan(a)
    diff = np.abs(a[finite] - b[finite])
    scale = np.maximum(np.abs(a[finite]), np.abs(b[finite]))
    rel = np.max(np.where(scale > 0, diff / np.where(scale > 0, scale, 1), diff), initial=0.0)
    limit = 0.0 if name == "ViewCoverage" else rtol
    good = same_nan and rel <= limit
    ok &= good
    print(f"{name}: {a.size} values, {int(np.sum(a[finite] != b[finite]))} differ, "
          f"max relative difference {rel:.3e} (limit {limit:g}), NaN at the same rows: "
          f"{same_nan} -> {'ok' if good else 'FAIL'}")
sys.exit(0 if ok else 1)

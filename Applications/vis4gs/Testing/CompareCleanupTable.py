#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The clean-up panel of `vis4gs view` against `vis4gs analyze --select --report` (issue 20).

The view's self-test saves its rule (cleanup-rule.txt), the Gaussians it selected
(cleanup-selection.csv) and the before/after table it shows (cleanup-before-after.csv, the
table's own values in analyze's columns). analyze, run with --select=@cleanup-rule.txt, reads
the log through another path (TrainingLogReader, its own score computation and camera
images) and writes selection.csv and before-after.csv. Both must select the same Gaussians
and show the same figures in the same order (worst first).

Usage: CompareCleanupTable.py VIEW_DIR ANALYZE_DIR
"""
import csv
import math
import sys


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def ids(path):
    return {int(r["GaussianId"]) for r in rows(path)}


def main():
    view_dir, analyze_dir = sys.argv[1], sys.argv[2]
    failures = []
    gui_ids = ids(f"{view_dir}/cleanup-selection.csv")
    cli_ids = ids(f"{analyze_dir}/selection.csv")
    if not gui_ids or gui_ids != cli_ids:
        failures.append(
            f"selections differ: view {len(gui_ids)}, analyze {len(cli_ids)}, "
            f"{len(gui_ids ^ cli_ids)} ids in one only")
    gui = rows(f"{view_dir}/cleanup-before-after.csv")
    cli = rows(f"{analyze_dir}/before-after.csv")
    if len(gui) != len(cli) or len(gui) < 3:
        failures.append(f"row counts differ: view {len(gui)}, analyze {len(cli)}")
    largest = 0.0
    figures = ("psnr_before", "psnr_after", "ssim_before", "ssim_after", "l1_before", "l1_after")
    for g, c in zip(gui, cli):
        key = (g["view"], g["split"], g["affected"])
        if key != (c["view"], c["split"], c["affected"]):
            failures.append(f"row {key} of the view is {(c['view'], c['split'], c['affected'])} "
                            "in analyze (order or affected flag)")
            continue
        for name in figures:
            a, b = float(g[name]), float(c[name])
            if math.isnan(a) and math.isnan(b):
                continue
            # analyze prints 9 significant digits.
            diff = abs(a - b)
            largest = max(largest, diff / max(1.0, abs(b)))
            if not diff <= 1e-7 * max(1.0, abs(b)):
                failures.append(f"{key} {name}: view {a!r}, analyze {b!r}")
    # The figures are not trivially equal: deleting the selection changes some view.
    changed = sum(1 for g in gui[2:] if g["affected"] == "1"
                  and float(g["psnr_before"]) != float(g["psnr_after"]))
    if changed == 0:
        failures.append("no view changed: the comparison would hold for any selection")
    for f in failures:
        print("FAILED: " + f)
    if failures:
        return 1
    print(f"the view's clean-up table equals analyze's: {len(gui_ids)} Gaussians, {len(gui)} "
          f"rows, {changed} views changed, largest relative difference {largest:.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

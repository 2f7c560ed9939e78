"""The assertion helper of the check scripts of this folder (CheckRepair.py,
CheckCleanupRepair.py, CheckCleanupScene.py, ...): check() prints each assertion and records a
failed one; finish() then exits with status 1 listing the failures (what CTest looks at), or
prints the closing line.
"""
import csv
import sys

problems = []


def check(ok, what):
    """Prints 'ok: WHAT' or 'FAILED: WHAT' (recorded); returns @p ok."""
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        problems.append(what)
    return ok


def finish(success):
    """Exit status 1 naming the failed checks, else prints @p success."""
    if problems:
        print("FAILED: " + "; ".join(problems))
        sys.exit(1)
    print(success)


def read_figures(path):
    """The rows of a figures table (repair.csv, before-after.csv) by (view, split)."""
    with open(path, newline="") as f:
        return {(r["view"], r["split"]): r for r in csv.DictReader(f)}


def largest_relative_difference(table, reference):
    """The largest |x - y| / |y| over the numeric columns of @p reference's rows (y) and the
    same cells of @p table (x); inf when @p table lacks a row."""
    worst = 0.0
    for key, row in reference.items():
        if key not in table:
            return float("inf")
        for column, value in row.items():
            if column in ("view", "split"):
                continue
            x, y = float(table[key][column]), float(value)
            worst = max(worst, abs(x - y) / max(abs(y), 1e-300))
    return worst

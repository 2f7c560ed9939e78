"""Keeps CompareFloaterFilter.py from rotting without chromium or a GPU: its ranking, the
matching of splat-transform's output to the input and the subset writer on generated rows,
checked against brute-force answers; then, with a vis4gs binary, the whole script on the
embedded demo log with a given set of "filtered" ids in place of the filter (two repair
iterations), checking the counts and figures it reports.

Usage: TestCompareFloaterFilter.py WORKDIR [VIS4GS DEMO_LOG]"""
import csv
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import CompareFloaterFilter as cff  # noqa: E402
import reference_ply  # noqa: E402

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


def generated_rows(n=2000, seed=7):
    rng = np.random.default_rng(seed)
    names = (["x", "y", "z", "opacity"] + ["scale_%d" % i for i in range(3)] +
             ["rot_%d" % i for i in range(4)] + ["ViewCoverage", "BlurScore", "NeedleScore", "NeedleShape"])
    rows = np.zeros(n, dtype=[(c, "<f4") for c in names] + [("id", "<i4")])
    for c in names:
        rows[c] = rng.normal(0, 1, n)
    rows["ViewCoverage"] = rng.integers(0, 12, n) / 11.0  # many ties, as fractions of views
    rows["BlurScore"][rng.choice(n, 50, replace=False)] = np.nan  # never computed
    rows["id"] = rng.permutation(10 * n)[:n] + 100000  # ids neither dense nor in order
    return rows


def check_ranking(rows):
    for k in (1, 137, 500):
        for name, criteria in cff.RULES.items():
            ids, tied = cff.select_most_suspicious(rows, criteria, k)
            check(len(ids) == k and len(np.unique(ids)) == k and np.isin(ids, rows["id"]).all(),
                  "%s: %d distinct ids of the scene for k=%d" % (name, len(np.unique(ids)), k))
            if len(criteria) != 1:
                continue
            column, direction = criteria[0]
            sel = np.isin(rows["id"], ids)
            v = rows[column].astype(np.float64) * direction
            # Brute force: no unselected finite value is more suspicious than a selected one.
            worst_kept = np.nanmax(np.where(sel, np.nan, v))
            least_selected = np.min(v[sel])
            check(worst_kept <= least_selected and np.isfinite(v[sel]).all(),
                  "%s k=%d: selected values >= %.4g >= every kept value %.4g, none NaN"
                  % (name, k, least_selected, worst_kept))
            check(tied == int(np.count_nonzero(v == least_selected)),
                  "%s k=%d: %d tied at the cut" % (name, k, tied))
    ids0, _ = cff.select_most_suspicious(rows, cff.RULES["coverage"], 300, seed=0)
    ids1, _ = cff.select_most_suspicious(rows, cff.RULES["coverage"], 300, seed=1)
    check(not np.array_equal(np.sort(ids0), np.sort(ids1)),
          "coverage ties at the cut are broken by the seed, not by row order")


def check_matching(rows):
    rng = np.random.default_rng(3)
    removed = rng.choice(rows["id"], 321, replace=False)
    kept = rows[~np.isin(rows["id"], removed)]
    kept = kept[rng.permutation(len(kept))]  # the filter may reorder
    got = cff.removed_ids(rows, kept)
    check(np.array_equal(np.sort(got), np.sort(removed)), "removed ids by the id column")
    no_id = kept[[c for c in kept.dtype.names if c != "id"]]
    got = cff.removed_ids(rows, no_id)
    check(np.array_equal(np.sort(got), np.sort(removed)), "removed ids by exact positions")
    stranger = kept.copy()
    stranger["x"][0] += 1.0
    for what, out in (("id", np.concatenate([kept, rows[:1].copy()])), ("position", stranger)):
        if what == "id":
            out["id"][-1] = -5
        else:
            out = out[[c for c in out.dtype.names if c != "id"]]
        try:
            cff.removed_ids(rows, out)
            check(False, "an output row unknown by %s raises ValueError" % what)
        except ValueError as e:
            check(True, "an output row unknown by %s raises ValueError (%s)" % (what, e))


def check_writer(rows, work):
    src = os.path.join(work, "rows.ply")
    header = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(rows)
    header += "".join("property %s %s\n" % ("int" if c == "id" else "float", c)
                      for c in rows.dtype.names) + "end_header\n"
    with open(src, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(rows.tobytes())
    remove = rows["id"][::7]
    dst = os.path.join(work, "rows-cleaned.ply")
    kept = cff.write_without(src, dst, remove)
    back = reference_ply.read_ply(dst)["vertex"]
    expected = rows[np.arange(len(rows)) % 7 != 0]
    check(kept == len(expected) and back.dtype == rows.dtype and
          back.tobytes() == expected.tobytes(),
          "write_without: %d rows kept bit for bit, id still an int" % kept)


def check_end_to_end(vis4gs, log, work):
    scene = os.path.join(work, "demo.ply")
    reference_ply.run([vis4gs, "convert", log, scene])
    ids = reference_ply.read_ply(scene)["vertex"]["id"].astype(np.int64)
    given = np.random.default_rng(5).choice(ids, 120, replace=False)
    ids_file = os.path.join(work, "given-ids.txt")
    np.savetxt(ids_file, given, fmt="%d")
    out = os.path.join(work, "compare")
    cff.main(["--vis4gs", vis4gs, "--log", log, "--output", out, "--floater-ids", ids_file,
              "--rules", "coverage,random", "--scores", "coverage", "--repair-iterations", "2"])
    with open(os.path.join(out, "comparison.csv")) as f:
        table = {r["rule"]: r for r in csv.DictReader(f)}
    check(sorted(table) == ["coverage", "none", "random", "splat-transform"],
          "comparison.csv rows: %s" % sorted(table))
    for name, row in table.items():
        expected = 0 if name == "none" else 120
        check(int(row["removed"]) == expected, "%s removed %s (%d expected)"
              % (name, row["removed"], expected))
        check(row["test_psnr_source"] == table["none"]["test_psnr_source"],
              "%s: same source test PSNR as the others" % name)
        kept = reference_ply.read_ply(os.path.join(out, "rule-" + name, "cleaned.ply"))["vertex"]
        check(len(kept) == len(ids) - expected, "%s/cleaned.ply: %d Gaussians" % (name, len(kept)))
    check(int(table["splat-transform"]["overlap_with_filter"]) == 120,
          "the given ids are the filter's set")
    check(table["none"]["test_psnr_deleted"] == table["none"]["test_psnr_source"],
          "deleting nothing leaves the test PSNR as it was")
    check(table["splat-transform"]["test_psnr_deleted"] != table["none"]["test_psnr_deleted"],
          "deleting 120 Gaussians changes the test PSNR")
    scores = reference_ply.read_ply(os.path.join(out, "analysis", "scores.ply"))["vertex"]
    chosen = np.isin(scores["id"], np.loadtxt(os.path.join(out, "floater-ids.txt"), np.int64))
    check(chosen.sum() == 120, "floater-ids.txt holds the given ids")
    md = open(os.path.join(out, "comparison.md")).read()
    check(md.count("\n| ") == 5, "comparison.md: a header and four rows")


def main():
    work = sys.argv[1]
    os.makedirs(work, exist_ok=True)
    rows = generated_rows()
    check_ranking(rows)
    check_matching(rows)
    check_writer(rows, work)
    if len(sys.argv) > 3 and sys.argv[2]:
        check_end_to_end(sys.argv[2], sys.argv[3], work)
    print("%d failures" % len(failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

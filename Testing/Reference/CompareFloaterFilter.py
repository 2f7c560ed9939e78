"""Vis4GS's guided clean-up measured against splat-transform's floater filter (issue 34 part 4).

For a training log written by `vis4gs train --eval` (held-out test views, images on disk):

1. `vis4gs analyze LOG` computes the scores (View Coverage, Blur, Needle, needle shape) of the
   last snapshot and writes them with the Gaussians and their ids to scores.ply (timed: CPU only).
2. `splat-transform scores.ply --filter-floaters floaters.ply` (PlayCanvas, WebGPU; on a machine
   without a GPU, the SwiftShader Vulkan driver of Debian's chromium package,
   install-swiftshader.sh) removes K Gaussians; the ids it kept name them (splat-transform keeps
   the extra columns, so the id travels with each row; exact positions are the fallback).
3. Each Vis4GS rule removes its K most suspicious Gaussians (the same number), and a random
   choice of K and no deletion at all are the controls.
4. `vis4gs repair LOG cleaned.ply --iterations=N` measures PSNR, SSIM and L1 on every training
   and test view for the source, the cleaned scene and the cleaned scene fine-tuned N iterations.

Writes DIR/comparison.csv, DIR/comparison.md (the table of the user guide) and DIR/timing.csv.
The functions are imported by TestCompareFloaterFilter.py, which runs them on small inputs
without chromium so that the script does not rot; the full comparison is a measurement.

Usage: CompareFloaterFilter.py --vis4gs=BIN --log=LOG.h5 --output=DIR [--build=BUILD]
  [--splat-transform=CLI] [--floater-ids=FILE] [--filter-floaters=0.05,0.1,0.004]
  [--repair-iterations=30] [--rules=...] [--scores=coverage,blur,needle,shape] [--threads=0]
"""
import argparse
import csv
import os
import resource
import subprocess
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import reference_ply  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))

# Each rule: the score columns of scores.ply it ranks and the direction in which a Gaussian is
# more suspicious (+1: large values, -1: small ones). A combination ranks by the mean of the
# per-score percentile ranks, so that no score's units dominate.
RULES = {
    "coverage": [("ViewCoverage", -1)],  # `views` orders the Gaussians identically
    "blur": [("BlurScore", +1)],
    "needle": [("NeedleScore", +1)],
    "shape": [("NeedleShape", +1)],
    "opacity": [("opacity", -1)],
    "coverage+blur": [("ViewCoverage", -1), ("BlurScore", +1)],
    "coverage+needle": [("ViewCoverage", -1), ("NeedleScore", +1)],
    "coverage+blur+needle": [("ViewCoverage", -1), ("BlurScore", +1), ("NeedleScore", +1)],
}
DEFAULT_RULES = ["coverage", "blur", "needle", "opacity", "coverage+blur", "coverage+needle",
                 "coverage+blur+needle"]


def suspicion_rank(values, direction):
    """Percentile rank in [0, 1], 1 the most suspicious; non-finite values rank 0 (a score that
    could not be computed does not select a Gaussian)."""
    v = np.asarray(values, dtype=np.float64) * direction
    finite = np.isfinite(v)
    rank = np.zeros(len(v))
    if finite.any():
        order = np.argsort(v[finite], kind="stable")
        r = np.empty(order.size)
        r[order] = np.arange(1, order.size + 1) / order.size
        # Equal values share the highest rank of their group, so ties never split by row order.
        vals = v[finite]
        uniq, inverse = np.unique(vals, return_inverse=True)
        top = np.zeros(uniq.size)
        np.maximum.at(top, inverse, r)
        rank[finite] = top[inverse]
    return rank


def select_most_suspicious(rows, criteria, k, seed=0):
    """Ids of the @k most suspicious Gaussians of @rows (scores.ply's vertex array) by @criteria
    (a RULES entry). Ties at the cut are broken at random (@seed), not by id, since ids follow
    the order of creation. Returns (ids, number of Gaussians tied at the cut)."""
    if k <= 0:
        return np.zeros(0, dtype=np.int64), 0
    score = np.mean([suspicion_rank(rows[name], d) for name, d in criteria], axis=0)
    noise = np.random.default_rng(seed).random(len(score))
    order = np.lexsort((noise, -score))  # most suspicious first
    chosen = order[:k]
    cut = score[order[k - 1]]
    tied = int(np.count_nonzero(score == cut))
    return np.asarray(rows["id"][chosen], dtype=np.int64), tied


def removed_ids(source, kept):
    """Ids of the rows of @source (with an id column) missing from @kept (splat-transform's
    output). By id when @kept has one; else by the exact float bits of position, scale, rotation
    and opacity, which the filter copies unchanged. Raises ValueError on an output row that
    matches no input row, or on duplicate keys that make the match ambiguous."""
    if "id" in kept.dtype.names:
        src = np.asarray(source["id"], dtype=np.int64)
        out = np.asarray(kept["id"], dtype=np.int64)
        unknown = np.setdiff1d(out, src)
        if unknown.size:
            raise ValueError("%d ids of the filtered scene are not in the input (first %d)"
                             % (unknown.size, unknown[0]))
        return np.setdiff1d(src, out)
    cols = [c for c in ("x", "y", "z", "scale_0", "scale_1", "scale_2", "rot_0", "rot_1", "rot_2",
                        "rot_3", "opacity") if c in kept.dtype.names]

    def keys(a):
        return [tuple(r) for r in np.stack([np.asarray(a[c], "<f4").view("<u4") for c in cols], 1)]

    index = {}
    for i, key in enumerate(keys(source)):
        if key in index:
            raise ValueError("two input Gaussians have the same %s: the match is ambiguous"
                             % ",".join(cols))
        index[key] = i
    keep = np.zeros(len(source), dtype=bool)
    for key in keys(kept):
        if key not in index:
            raise ValueError("a Gaussian of the filtered scene matches no input Gaussian")
        keep[index[key]] = True
    return np.asarray(source["id"][~keep], dtype=np.int64)


def write_without(src_path, dst_path, remove):
    """Writes the PLY @src_path without the rows whose id is in @remove: the header as it was
    (every property type kept, the id an int) with the new count, the kept rows' bytes."""
    data = open(src_path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    rows = reference_ply.read_ply(src_path)["vertex"]
    keep = ~np.isin(np.asarray(rows["id"], dtype=np.int64), remove)
    header = data[:end].decode("ascii").replace(
        "element vertex %d\n" % len(rows), "element vertex %d\n" % int(keep.sum()), 1)
    with open(dst_path, "wb") as f:
        f.write(header.encode("ascii"))
        f.write(rows[keep].tobytes())
    return int(keep.sum())


class Timer:
    """Wall and CPU time (user + sys of the children) of each step."""

    def __init__(self):
        self.rows = []

    def run(self, step, cmd, env=None):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.monotonic()
        r = subprocess.run(cmd, capture_output=True, text=True, env=env)
        wall = time.monotonic() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        self.rows.append((step, wall, cpu))
        if r.returncode != 0:
            print("FAILED: %s exited %d\n%s%s" % (" ".join(cmd), r.returncode, r.stdout[-4000:],
                                                  r.stderr[-4000:]))
            sys.exit(1)
        print("%s: %.1f s wall, %.1f s CPU" % (step, wall, cpu), flush=True)
        return r.stdout


def mean_rows(path):
    """{split: {column: value}} of repair.csv's `mean` rows."""
    out = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            if row["view"] == "mean":
                out[row["split"]] = {k: float(v) for k, v in row.items() if k not in ("view", "split")}
    return out


def swiftshader_env():
    """The environment splat-transform's WebGPU needs without a GPU: chromium's SwiftShader."""
    env = dict(os.environ)
    if "VK_ICD_FILENAMES" not in env:
        r = subprocess.run(["bash", os.path.join(HERE, "install-swiftshader.sh")],
                           capture_output=True, text=True)
        if r.returncode != 0:
            sys.stdout.write(r.stderr)
            sys.exit(r.returncode)
        env["VK_ICD_FILENAMES"] = r.stdout.strip().splitlines()[-1]
    if "XDG_RUNTIME_DIR" not in env:
        env["XDG_RUNTIME_DIR"] = "/tmp/xdg-runtime-%d" % os.getuid()
        os.makedirs(env["XDG_RUNTIME_DIR"], mode=0o700, exist_ok=True)
    return env


def describe(rows, ids):
    """Medians of what a selection removed: opacity (sigmoid), largest scale, coverage."""
    sel = np.isin(np.asarray(rows["id"], dtype=np.int64), ids)
    if not sel.any():
        return {"opacity": float("nan"), "scale": float("nan"), "coverage": float("nan")}
    opacity = 1.0 / (1.0 + np.exp(-np.asarray(rows["opacity"][sel], np.float64)))
    scale = np.exp(np.max(np.stack([rows["scale_%d" % i][sel] for i in range(3)], 1), 1))
    out = {"opacity": float(np.median(opacity)), "scale": float(np.median(scale))}
    out["coverage"] = (float(np.median(rows["ViewCoverage"][sel]))
                       if "ViewCoverage" in rows.dtype.names else float("nan"))
    return out


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--vis4gs", required=True)
    p.add_argument("--log", required=True, help="training log of vis4gs train --eval")
    p.add_argument("--output", required=True)
    p.add_argument("--build", help="build folder for install-splat-transform.sh")
    p.add_argument("--splat-transform", help="splat-transform's bin/cli.mjs")
    p.add_argument("--floater-ids", help="ids the filter removed (one a line): skips the filter")
    p.add_argument("--filter-floaters", default="", help="size,op,min; empty: its defaults")
    p.add_argument("--repair-iterations", type=int, default=30)
    p.add_argument("--rules", default=",".join(DEFAULT_RULES))
    p.add_argument("--scores", default="coverage,blur,needle,shape")
    p.add_argument("--threads", default="0")
    a = p.parse_args(argv)
    rules = [r for r in a.rules.split(",") if r]
    for r in rules:
        if r not in RULES and r != "random":
            p.error("unknown rule %r (known: %s, random)" % (r, ", ".join(RULES)))
    os.makedirs(a.output, exist_ok=True)
    timer = Timer()
    threads = "--threads=" + a.threads

    analysis = os.path.join(a.output, "analysis")
    timer.run("vis4gs analyze (scores, CPU)", [a.vis4gs, "analyze", a.log, "--scores=" + a.scores,
                                              "--top=1", "--overlay-views=0", threads,
                                              "--output=" + analysis])
    scores_ply = os.path.join(analysis, "scores.ply")
    rows = reference_ply.read_ply(scores_ply)["vertex"]
    print("scores.ply: %d Gaussians" % len(rows))

    if a.floater_ids:
        filtered = np.loadtxt(a.floater_ids, dtype=np.int64, ndmin=1)
    else:
        cli = a.splat_transform or reference_ply.splat_transform(a.build or a.output)
        floaters_ply = os.path.join(a.output, "floaters.ply")
        option = ["--filter-floaters"] + ([a.filter_floaters] if a.filter_floaters else [])
        timer.run("splat-transform --filter-floaters (WebGPU)",
                  ["node", cli, "-w", scores_ply] + option + [floaters_ply],
                  env=swiftshader_env())
        filtered = removed_ids(rows, reference_ply.read_ply(floaters_ply)["vertex"])
    k = len(filtered)
    np.savetxt(os.path.join(a.output, "floater-ids.txt"), filtered, fmt="%d")
    print("the floater filter removes %d of %d Gaussians" % (k, len(rows)))

    selections = [("splat-transform", filtered, 0), ("none", np.zeros(0, np.int64), 0)]
    for r in rules:
        if r == "random":
            rng = np.random.default_rng(0)
            ids = np.asarray(rows["id"], np.int64)[rng.choice(len(rows), k, replace=False)]
            selections.append(("random", ids, 0))
        else:
            t0 = time.process_time()
            ids, tied = select_most_suspicious(rows, RULES[r], k)
            selections.append((r, ids, tied))
            timer.rows.append(("select " + r, 0.0, time.process_time() - t0))

    table = []
    for name, ids, tied in selections:
        folder = os.path.join(a.output, "rule-" + name.replace("+", "-"))
        os.makedirs(folder, exist_ok=True)
        cleaned = os.path.join(folder, "cleaned.ply")
        kept = write_without(scores_ply, cleaned, ids)
        if kept + len(ids) != len(rows):
            print("FAILED: %s: %d kept + %d removed != %d" % (name, kept, len(ids), len(rows)))
            sys.exit(1)
        timer.run("vis4gs repair %s" % name,
                  [a.vis4gs, "repair", a.log, cleaned, threads,
                   "--iterations=%d" % a.repair_iterations, "--output=" + os.path.join(folder, "repair")])
        m = mean_rows(os.path.join(folder, "repair", "repair.csv"))
        row = {"rule": name, "removed": len(ids), "tied_at_cut": tied,
               "overlap_with_filter": int(np.isin(ids, filtered).sum())}
        row.update({"median_" + key: v for key, v in describe(rows, ids).items()})
        for split in ("test", "train"):
            for key, v in m.get(split, {}).items():
                row["%s_%s" % (split, key)] = v
        table.append(row)

    columns = list(table[0].keys())
    for row in table[1:]:
        columns += [c for c in row if c not in columns]
    with open(os.path.join(a.output, "comparison.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, columns)
        w.writeheader()
        w.writerows(table)
    with open(os.path.join(a.output, "timing.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["step", "wall_s", "cpu_s"])
        w.writerows([(s, "%.2f" % wall, "%.2f" % cpu) for s, wall, cpu in timer.rows])

    def fig(row, key, fmt):
        return fmt % row[key] if key in row else "-"

    lines = ["| removed by | K | in the filter's set | test PSNR deleted (repaired) | "
             "test SSIM deleted (repaired) | test L1 deleted (repaired) | train PSNR deleted |",
             "|---|---|---|---|---|---|---|"]
    for row in table:
        lines.append("| %s | %d | %d | %s (%s) | %s (%s) | %s (%s) | %s |" % (
            row["rule"], row["removed"], row["overlap_with_filter"],
            fig(row, "test_psnr_deleted", "%.3f"), fig(row, "test_psnr_repaired", "%.3f"),
            fig(row, "test_ssim_deleted", "%.4f"), fig(row, "test_ssim_repaired", "%.4f"),
            fig(row, "test_l1_deleted", "%.5f"), fig(row, "test_l1_repaired", "%.5f"),
            fig(row, "train_psnr_deleted", "%.3f")))
    src = table[0]
    lines.append("\nSource: test PSNR %s, SSIM %s, L1 %s; train PSNR %s; %d Gaussians; repair %d "
                 "iterations." % (fig(src, "test_psnr_source", "%.3f"),
                                  fig(src, "test_ssim_source", "%.4f"),
                                  fig(src, "test_l1_source", "%.5f"),
                                  fig(src, "train_psnr_source", "%.3f"), len(rows),
                                  a.repair_iterations))
    text = "\n".join(lines) + "\n"
    open(os.path.join(a.output, "comparison.md"), "w").write(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())

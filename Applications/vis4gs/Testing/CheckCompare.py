"""Checks `vis4gs compare` (issue 20) against computations made here from the inputs.

Usage:
  CheckCompare.py VIS4GS OUTPUT_DIR log LOG.h5
      Two iterations of the demo log: 1600 against the last with thresholds, and 400 against
      1600 without (births and deaths). differences.csv is recomputed with numpy from the log's
      snapshots (h5py): ids matched, float64 distances, strict thresholds; metrics.csv holds the
      log's /metrics rows as h5py reads them, per-view rows whose means are the "mean" rows,
      and the last state's training mean agrees with the trainer's own /metrics at that
      iteration.
  CheckCompare.py VIS4GS OUTPUT_DIR ply ANALYZE_DIR LOG.h5
      The scene of `analyze --select=views<=3 --delete` (scores.ply) against its cleaned copy
      (cleaned.ply), both PLYs, with the log's training cameras as a cameras.json and the
      images analyze wrote: the selected ids (selection.csv) died, every other id is unchanged
      with all differences exactly 0, and the per-view PSNR of both states equals analyze's
      before-after.csv (the same measurement code, so to rounding).
Prints "FAILED: ..." for each failed check and exits 1.
"""
import csv
import os
import re
import subprocess
import sys

import h5py
import numpy as np

problems = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        problems.append(what)


def run(args):
    result = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(result.stdout)
    if result.returncode != 0:
        print(f"FAILED: exit status {result.returncode} from {' '.join(args)}")
        sys.exit(1)
    return result.stdout


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_outputs(folder):
    for name in ("differences.csv", "metrics.csv", "report.html"):
        check(os.path.getsize(os.path.join(folder, name)) > 0, f"{name} written")
    return read_csv(os.path.join(folder, "differences.csv")), read_csv(
        os.path.join(folder, "metrics.csv"))


def expected_differences(log, it_a, it_b, move_t, opacity_t, scale_t):
    """Rows (id, status, move, opacity, scale) computed from the snapshots with numpy."""
    sa, sb = log[f"snapshots/{it_a:06d}"], log[f"snapshots/{it_b:06d}"]
    ida, idb = sa["id"][()].astype(np.int64), sb["id"][()].astype(np.int64)
    common, ia, ib = np.intersect1d(ida, idb, return_indices=True)
    pa, pb = sa["position"][()].astype(np.float64), sb["position"][()].astype(np.float64)
    move = np.linalg.norm(pb[ib] - pa[ia], axis=1)
    sig = lambda x: 1.0 / (1.0 + np.exp(-x.astype(np.float64)))
    opacity = sig(sb["opacity_logit"][()][ib]) - sig(sa["opacity_logit"][()][ia])
    ds = sb["log_scale"][()][ib].astype(np.float64) - sa["log_scale"][()][ia].astype(np.float64)
    scale = ds[np.arange(len(ds)), np.argmax(np.abs(ds), axis=1)]
    rows = {}
    for k, gid in enumerate(common):
        words = [w for w, v, t in (("moved", move[k], move_t), ("opacity", opacity[k], opacity_t),
                                    ("scale", scale[k], scale_t)) if abs(v) > t]
        rows[int(gid)] = ("+".join(words) or "unchanged", move[k], opacity[k], scale[k])
    for gid in np.setdiff1d(ida, idb):
        rows[int(gid)] = ("died", np.nan, np.nan, np.nan)
    for gid in np.setdiff1d(idb, ida):
        rows[int(gid)] = ("born", np.nan, np.nan, np.nan)
    return rows


def compare_rows(rows, expected, label):
    ids = [int(r["id"]) for r in rows]
    check(ids == sorted(expected), f"{label}: one row per id of either state, by increasing id "
          f"({len(ids)} rows, expected {len(expected)})")
    statuses = {}
    worst = 0.0
    for r in rows:
        e = expected.get(int(r["id"]))
        if e is None:
            continue
        statuses.setdefault(r["status"] == e[0], []).append(int(r["id"]))
        for got, want in zip((r["dmove"], r["dopacity"], r["dscale"]), e[1:]):
            got = float(got)
            if np.isnan(want):
                worst = max(worst, 0.0 if np.isnan(got) else np.inf)
            else:
                worst = max(worst, abs(got - want) / max(1e-6, abs(want)))
    check(not statuses.get(False), f"{label}: every status agrees with numpy "
          f"(disagreeing ids: {statuses.get(False, [])[:10]})")
    check(worst < 1e-5, f"{label}: dmove, dopacity, dscale agree with numpy (worst relative "
          f"error {worst:.2e})")
    counts = {}
    for e in expected.values():
        counts[e[0]] = counts.get(e[0], 0) + 1
    print(f"{label}: numpy counts {dict(sorted(counts.items()))}")
    return counts


def check_means(metrics, label):
    for source in ("a", "b"):
        for split in ("train", "test"):
            views = [r for r in metrics if r["source"] == source and r["split"] == split and
                     r["view"] != "mean"]
            mean = [r for r in metrics if r["source"] == source and r["split"] == split and
                    r["view"] == "mean"]
            check(len(views) > 0 and len(mean) == 1, f"{label}: {source} {split}: "
                  f"{len(views)} views and one mean row")
            if views and mean:
                for key in ("psnr", "ssim", "l1"):
                    m = np.mean([float(r[key]) for r in views])
                    check(abs(m - float(mean[0][key])) < 1e-6 * max(1, abs(m)),
                          f"{label}: {source} {split} mean {key} is the mean of its views")


def check_log(vis4gs, folder, log_path):
    with h5py.File(log_path, "r") as log:
        iterations = sorted(int(k) for k in log["snapshots"].keys())
        last = iterations[-1]
        table = {k: log["metrics"][k][()] for k in ("iteration", "psnr", "ssim", "l1",
                                                     "num_gaussians")}
        test_table = {k: log["metrics/test"][k][()] for k in ("iteration", "psnr")}
        for it_a, it_b, thresholds in ((1600, -1, (1e-3, 0.01, 0.05)), (400, 1600, (0, 0, 0))):
            out = os.path.join(folder, f"{it_a}-{it_b}")
            label = f"iterations {it_a} -> {it_b if it_b >= 0 else last}"
            text = run([vis4gs, "compare", log_path, log_path, f"--iteration-a={it_a}",
                        f"--iteration-b={it_b}", f"--move={thresholds[0]}",
                        f"--opacity={thresholds[1]}", f"--scale={thresholds[2]}", "--threads=2",
                        f"--output={out}"])
            rows, metrics = read_outputs(out)
            expected = expected_differences(log, it_a, it_b if it_b >= 0 else last, *thresholds)
            counts = compare_rows(rows, expected, label)
            born, died = counts.get("born", 0), counts.get("died", 0)
            said = re.search(r"(\d+) Gaussians in both, (\d+) born, (\d+) died", text)
            check(said is not None and (int(said.group(2)), int(said.group(3))) == (born, died),
                  f"{label}: the printed born/died counts are numpy's ({born}, {died})")
            if it_a == 400:
                check(born > 0 and died > 0, f"{label}: densification and pruning between them "
                      f"show as {born} born and {died} died")
            else:
                check(0 < counts.get("unchanged", 0) < len(expected),
                      f"{label}: the thresholds leave {counts.get('unchanged', 0)} unchanged")
            check_means(metrics, label)
            logged = [r for r in metrics if r["source"] == "log-a" and r["split"] == "train"]
            check([int(r["iteration"]) for r in logged] == list(table["iteration"]) and
                  np.allclose([float(r["psnr"]) for r in logged], table["psnr"], rtol=1e-7) and
                  np.allclose([float(r["l1"]) for r in logged], table["l1"], rtol=1e-7),
                  f"{label}: metrics.csv holds the log's /metrics ({len(logged)} rows)")
            check(sum(r["source"] == "log-a" and r["split"] == "test" for r in metrics) ==
                  len(test_table["iteration"]), f"{label}: and its /metrics/test")
            check(not any(r["source"] == "log-b" for r in metrics),
                  f"{label}: one log, its tables once")
            if it_b < 0:
                mine = float(next(r["psnr"] for r in metrics if r["source"] == "b" and
                                  r["split"] == "train" and r["view"] == "mean"))
                trainer = float(table["psnr"][list(table["iteration"]).index(last)])
                check(abs(mine - trainer) < 0.05, f"{label}: the last state's training PSNR "
                      f"{mine:.4f} dB agrees with the trainer's /metrics {trainer:.4f} dB")
            html = open(os.path.join(out, "report.html"), encoding="utf-8").read()
            check(f"<td>{born}</td><td>{died}</td>" in html, f"{label}: the report's counts")


def check_ply(vis4gs, folder, analyze, log_path):
    cameras = os.path.join(folder, "cameras.json")
    run([sys.executable, os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                      "LogCamerasJson.py"), log_path, cameras])
    out = os.path.join(folder, "ply")
    run([vis4gs, "compare", os.path.join(analyze, "scores.ply"),
         os.path.join(analyze, "cleaned.ply"), f"--cameras={cameras}",
         f"--images={os.path.join(analyze, 'images')}", "--threads=2", f"--output={out}"])
    rows, metrics = read_outputs(out)
    selected = sorted(int(line) for line in open(os.path.join(analyze, "selection.csv"))
                      .read().split()[1:])
    died = [int(r["id"]) for r in rows if r["status"] == "died"]
    check(len(selected) > 0 and died == selected,
          f"the {len(selected)} deleted ids (selection.csv) died ({len(died)} died)")
    others = [r for r in rows if r["status"] != "died"]
    check(all(r["status"] == "unchanged" for r in others) and
          all(float(r[k]) == 0.0 for r in others for k in ("dmove", "dopacity", "dscale")),
          f"the other {len(others)} are unchanged, every difference exactly 0")
    before = {r["view"]: r for r in read_csv(os.path.join(analyze, "before-after.csv"))
              if r["split"] == "train" and r["view"] != "mean"}
    worst = 0.0
    views = 0
    for source, key in (("a", "psnr_before"), ("b", "psnr_after")):
        for r in metrics:
            if r["source"] == source and r["view"] != "mean":
                worst = max(worst, abs(float(r["psnr"]) - float(before[r["view"]][key])))
                views += 1
    check(views == 2 * len(before) and worst < 1e-3, f"per-view PSNR of both states equals "
          f"analyze's before-after.csv ({views} figures, largest difference {worst:.2e} dB)")


def main():
    vis4gs, folder, mode = sys.argv[1:4]
    os.makedirs(folder, exist_ok=True)
    if mode == "log":
        check_log(vis4gs, folder, sys.argv[4])
    else:
        check_ply(vis4gs, folder, sys.argv[4], sys.argv[5])
    if problems:
        sys.exit(1)
    print("compare outputs agree with numpy")


if __name__ == "__main__":
    main()

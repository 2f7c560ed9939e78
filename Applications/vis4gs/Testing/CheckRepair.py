"""Checks `vis4gs repair` (issue 20) on the demo log: analyze --select="views<=3" --delete's
cleaned.ply fine-tuned for 50 iterations, positions fixed, densification off.

Checked from the files, with h5py and the wrapped VTK pipeline:
- repaired.h5's first event rows are prune events at the source iteration naming exactly the
  deleted ids (the snapshot's ids that cleaned.ply lacks, and selection.csv's ids), no other
  event follows (densification off);
- its first snapshot is the source snapshot as logged, bit for bit; its last holds exactly the
  kept ids, at the same positions (fixed), with other parameters changed (it trained);
- the log opens in the genealogy (vtkGaussianTrainingLogReader -> vtkGaussianGenealogyTreeFilter):
  one tree over the source's Gaussians, the deleted ones pruned at the source iteration, the
  others alive;
- repair.csv: the training PSNR after the repair >= after the deletion; its source and
  deleted columns equal analyze's before-after.csv; the log's /metrics row at the source
  iteration is the deleted scene's training PSNR;
- `vis4gs compare LOG repaired.h5` (two logs): the deleted ids died, the others did not move,
  and metrics.csv holds both runs' /metrics tables.

Usage: CheckRepair.py VIS4GS LOG.h5 ANALYZE_DIR OUTPUT_DIR
"""
import csv
import os
import subprocess
import sys

import h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from CleanupReport import read_ply  # noqa: E402
from Checks import check, finish  # noqa: E402



def main(vis4gs_exe, log_path, analyze, folder):
    result = subprocess.run([vis4gs_exe, "repair", log_path,
                             os.path.join(analyze, "cleaned.ply"), "--iterations=50",
                             "--threads=2", f"--output={folder}"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(result.stdout)
    if result.returncode != 0:
        print(f"FAILED: vis4gs repair exited with {result.returncode}")
        sys.exit(1)
    repaired = os.path.join(folder, "repaired.h5")
    selected = sorted(int(v) for v in
                      open(os.path.join(analyze, "selection.csv")).read().split()[1:])
    with h5py.File(log_path, "r") as src, h5py.File(repaired, "r") as out:
        last = sorted(src["snapshots"].keys())[-1]
        source = int(last)
        src_ids = src["snapshots"][last]["id"][()].astype(np.int64)
        cleaned_ids = read_ply(os.path.join(analyze, "cleaned.ply"))["id"].astype(np.int64)
        deleted = np.setdiff1d(src_ids, cleaned_ids).tolist()
        check(deleted == selected, f"the {len(selected)} selected ids are the ones cleaned.ply "
              "lacks (numpy)")
        ev = {k: out["events"][k][()] for k in ("iteration", "kind", "parent", "child")}
        check(len(ev["kind"]) == len(selected) and np.all(ev["kind"] == 3) and
              np.all(ev["iteration"] == source) and np.all(ev["child"] == -1) and
              sorted(ev["parent"].tolist()) == selected,
              f"{len(ev['kind'])} event rows: prune events at iteration {source} naming the "
              "deleted ids, nothing else")
        snaps = sorted(out["snapshots"].keys())
        check(int(snaps[0]) == source and int(snaps[-1]) == source + 50,
              f"snapshots {snaps[0]} (source) and {snaps[-1]} (repaired)")
        first, final = out["snapshots"][snaps[0]], out["snapshots"][snaps[-1]]
        same = all(np.array_equal(first[k][()], src["snapshots"][last][k][()])
                   for k in ("id", "position", "log_scale", "rotation", "opacity_logit", "sh"))
        check(same, "the first snapshot is the source snapshot, bit for bit")
        kept = np.setdiff1d(src_ids, selected)
        check(np.array_equal(final["id"][()], kept), f"the last holds the {kept.size} kept ids")
        rows = np.searchsorted(src_ids, kept)
        check(np.array_equal(final["position"][()], src["snapshots"][last]["position"][()][rows]),
              "at the same positions (fixed)")
        check(not np.array_equal(final["opacity_logit"][()],
                                 src["snapshots"][last]["opacity_logit"][()][rows]),
              "with trained opacities")
        metrics = {k: out["metrics"][k][()] for k in ("iteration", "psnr")}

    import vis4gs
    reader = vis4gs.vtkGaussianTrainingLogReader()
    reader.SetFileName(repaired)
    tree = vis4gs.vtkGaussianGenealogyTreeFilter()
    tree.SetInputConnection(reader.GetOutputPort(3))
    tree.Update()
    vd = tree.GetOutput().GetVertexData()
    ok = vd.GetArray("GaussianId") is not None
    check(ok, "the repaired log opens in the genealogy")
    if ok:
        ids = vtk_to_numpy(vd.GetArray("GaussianId"))[1:]
        pruned = vtk_to_numpy(vd.GetArray("Pruned"))[1:]
        death = vtk_to_numpy(vd.GetArray("DeathIteration"))[1:]
        check(np.array_equal(np.sort(ids), src_ids), f"one tree over the {src_ids.size} "
              "source Gaussians")
        check(sorted(ids[pruned == 1].tolist()) == selected and np.all(death[pruned == 1] == source)
              and np.all(death[pruned == 0] == -1),
              f"the deleted ones pruned at {source}, the others alive")

    with open(os.path.join(folder, "repair.csv"), newline="") as f:
        figures = {(r["view"], r["split"]): r for r in csv.DictReader(f)}
    mean = figures[("mean", "train")]
    psnr = [float(mean[k]) for k in ("psnr_source", "psnr_deleted", "psnr_repaired")]
    check(psnr[2] >= psnr[1], f"training PSNR after the repair {psnr[2]:.4f} dB >= after the "
          f"deletion {psnr[1]:.4f} dB (source {psnr[0]:.4f} dB)")
    with open(os.path.join(analyze, "before-after.csv"), newline="") as f:
        before = {(r["view"], r["split"]): r for r in csv.DictReader(f)}
    worst = max(max(abs(float(r["psnr_source"]) - float(before[k]["psnr_before"])),
                    abs(float(r["psnr_deleted"]) - float(before[k]["psnr_after"])))
                for k, r in figures.items())
    check(worst < 1e-6, f"source and deleted figures equal analyze's before-after.csv "
          f"(largest difference {worst:.1e} dB)")
    at = list(metrics["iteration"]).index(source)
    check(abs(metrics["psnr"][at] - psnr[1]) < 1e-3, f"the log's /metrics at {source} "
          f"({metrics['psnr'][at]:.4f} dB) is the deleted scene's training PSNR")

    # Two logs compared (vis4gs compare): the source run's last snapshot against the repaired
    # run's; metrics.csv holds both runs' /metrics tables.
    out = os.path.join(folder, "compare")
    result = subprocess.run([vis4gs_exe, "compare", log_path, repaired, "--no-metrics",
                             f"--output={out}"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True)
    check(result.returncode == 0, "vis4gs compare LOG repaired.h5 exits 0")
    with open(os.path.join(out, "differences.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    died = sorted(int(r["id"]) for r in rows if r["status"] == "died")
    check(died == selected and not any(r["status"] == "born" for r in rows) and
          all(float(r["dmove"]) == 0 for r in rows if r["status"] != "died"),
          "compare: the deleted ids died, none was born, none of the others moved")
    with open(os.path.join(out, "metrics.csv"), newline="") as f:
        sources = [r["source"] for r in csv.DictReader(f)]
    with h5py.File(log_path, "r") as src:
        n_src = len(src["metrics"]["iteration"]) + len(src["metrics/test"]["iteration"])
    n_rep = len(metrics["iteration"]) * 2  # train and test rows
    check(sources.count("log-a") == n_src and sources.count("log-b") == n_rep,
          f"compare: metrics.csv holds both runs' /metrics ({n_src} and {n_rep} rows)")
    finish("repair outputs agree")


if __name__ == "__main__":
    main(*sys.argv[1:5])

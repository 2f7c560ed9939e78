"""The clean-up panel (issue 20) on a scene file with cameras and images, not a training log:
`vis4gs view SCENE.ply --cameras=cameras.json --images=DIR --iteration=SOURCE --self-test=SHOTS`
on the scene vis4gs-RepairScene built (CheckRepairScene.py: the demo log's last snapshot as a
PLY with an id property, its training cameras as cameras.json, its images as PNG files). The
self-test applies the rule "views<=3", measures the preview (per view, before / after), deletes,
fine-tunes 2 iterations from SOURCE and opens the comparison window, writing what it did; this
script runs it (its exit status is the self-test's) and checks from the files, with csv, h5py
and numpy:
- the direction on the training views (the scene has no held-out view): deleting Gaussians
  fitted to them lowers their mean PSNR and raises no view beyond rounding;
- the panel's figures equal repair.csv of `vis4gs repair SCENE.ply CLEANED --iterations=2
  --iteration=SOURCE` (what vis4gs-RepairScene ran: full renders, not the panel's per-tile
  sums), row by row, within 1e-8 relative;
- the panel deleted the Gaussians that command deleted (the view numbers a PLY's rows; its id
  property maps them), and its repaired log holds the same prune events and snapshots.

Usage: CheckCleanupScene.py VIS4GS SCENE_DIR SHOTS_DIR
"""
import os
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from CleanupReport import read_ply  # noqa: E402
from Checks import (check, finish, largest_relative_difference,  # noqa: E402
                    read_figures)


def main(vis4gs_exe, scene_dir, shots):
    scene = os.path.join(scene_dir, "scene.ply")
    run = os.path.join(scene_dir, "scene-run")
    with h5py.File(os.path.join(run, "repaired.h5"), "r") as log:
        snaps = sorted(log["snapshots"].keys(), key=int)
        source = int(snaps[0])
        command_pruned = np.sort(log["events"]["parent"][()].astype(np.int64))
    result = subprocess.run([vis4gs_exe, "view", scene,
                             f"--cameras={os.path.join(scene_dir, 'cameras.json')}",
                             f"--images={os.path.join(scene_dir, 'images')}",
                             f"--iteration={source}", f"--self-test={shots}",
                             "--resolution=1280,800"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(result.stdout)
    if not check(result.returncode == 0,
                 f"vis4gs view --self-test on the scene file exited with {result.returncode}"):
        finish("")

    # The preview of deleting the rule's selection (the self-test's step 5). The scene holds
    # the training views only (a trainer's cameras.json): the Gaussians "views<=3" selects were
    # fitted to them, so deleting them lowers the training mean and raises no view beyond
    # rounding; a floater's harm shows in held-out views (the demo log's tests check those).
    preview = read_figures(os.path.join(shots, "cleanup-before-after.csv"))
    mean = preview[("mean", "train")]
    check(float(mean["psnr_after"]) < float(mean["psnr_before"]),
          f"deleting Gaussians fitted to the training views lowers their mean PSNR: "
          f"{float(mean['psnr_before']):.4f} -> {float(mean['psnr_after']):.4f} dB")
    views = [r for k, r in preview.items() if k[0] != "mean"]
    change = np.array([float(r["psnr_after"]) - float(r["psnr_before"]) for r in views])
    check(len(views) > 0 and change.max() < 1e-3 and np.count_nonzero(change < -1e-3) > 0,
          f"no training view gains more than 0.001 dB ({change.max():.2g}); "
          f"{np.count_nonzero(change < -1e-3)} of {len(views)} lose more")

    # The fine-tune (step 7) against vis4gs repair's. Its direction over 2 iterations is not
    # asserted: from iteration 2000 the trainer's cold Adam state lowers the training PSNR
    # at first (vis4gs repair gives the same figures).
    panel = read_figures(os.path.join(shots, "cleanup-repair.csv"))
    mean = panel[("mean", "train")]
    print(f"training PSNR source -> deleted -> repaired: {float(mean['psnr_source']):.4f} -> "
          f"{float(mean['psnr_deleted']):.4f} -> {float(mean['psnr_repaired']):.4f} dB")
    check(np.isfinite(float(mean["psnr_repaired"])), "the repaired figures are measured")
    command = read_figures(os.path.join(run, "repair.csv"))
    worst = largest_relative_difference(panel, command)
    check(panel.keys() == command.keys() and worst <= 1e-8,
          f"the panel's figures equal vis4gs repair's repair.csv: {len(command)} rows "
          f"(largest relative difference {worst:.1e})")

    # The same deletion and fine-tune: the panel's ids are the PLY's rows.
    ply_ids = read_ply(scene)["id"].astype(np.int64)
    rows = np.array([int(v) for v in
                     open(os.path.join(shots, "cleanup-repair-deleted.csv")).read().split()[1:]],
                    np.int64)
    check(np.array_equal(np.sort(ply_ids[rows]), command_pruned),
          f"the panel deleted the {command_pruned.size} Gaussians vis4gs repair deleted")
    with h5py.File(os.path.join(shots, "cleanup-repaired.h5"), "r") as a, \
            h5py.File(os.path.join(run, "repaired.h5"), "r") as b:
        ev = a["events"]
        check(np.all(ev["kind"][()] == 3) and np.all(ev["iteration"][()] == source) and
              np.array_equal(np.sort(ply_ids[ev["parent"][()]]), command_pruned),
              f"the panel's log: prune events at iteration {source} of those Gaussians only")
        names = sorted(a["snapshots"].keys(), key=int)
        same = names == snaps
        for name in names if same else []:
            for key in b["snapshots"][name].keys():
                x, y = a["snapshots"][name][key][()], b["snapshots"][name][key][()]
                same = same and np.array_equal(ply_ids[x] if key == "id" else x, y)
        check(same, f"its snapshots {names} equal repair's, dataset by dataset")
    check(os.path.isfile(os.path.join(shots, "cleanup-compare.png")),
          "the comparison window's screenshot is written")
    finish("the panel's clean-up of a scene file equals vis4gs repair")


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit("usage: CheckCleanupScene.py VIS4GS SCENE_DIR SHOTS_DIR")
    main(*sys.argv[1:])

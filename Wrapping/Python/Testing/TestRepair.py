"""Scene.repair() (issue 20) on a planted case of the demo log, against `vis4gs repair`.

  TestRepair.py VIS4GS LOG OUTPUT_DIR ITERATIONS

The case study's floater, found by its scores (the visible Gaussian, opacity >= 0.1, with the
lowest positive View Coverage), is deleted and the rest fine-tuned for a few iterations (2: one
Adam step, the trainer makes none at its last iteration), once
with Scene.repair() and once with `vis4gs repair` on the cleaned PLY that Scene.select().save()
writes. Checked: the Python figures equal repair.csv's exactly (as the CSV prints them, 9
significant digits; view and split names too), the repaired Gaussians equal the last snapshot of
`vis4gs repair`'s log bit for bit, the positions are the snapshot's (fixed), and the direction
of the deletion: the floater hangs in front of a test view (one training view sees it), and the
mean test PSNR rises when it is deleted.

Both sides get a warm-up of 3 (not the default 10: --warmup and warmup= must be passed on).
Not asserted here: training PSNR after the fine-tune >= after the deletion (one Adam step, at
a quarter of the learning rates). A fine-tune starts Adam from zero moments (the log keeps no
optimiser state), so without a warm-up its first steps move every parameter by about its
learning rate and the training PSNR first dips (the demo's `views<=3` repair: 30.43 dB after
the deletion, 30.30 dB at +10, 30.54 dB at +50; with the default warm-up 30.43 dB at +10); the
warm-up's direction is asserted on the planted case of TestFineTune
(FineTune.WarmupKeepsTheFirstStepsFromDipping), the repair's in CheckRepair.py (50
iterations) and TestGaussianFineTuneFilter."""
import csv
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
from vtkmodules.vtkCommonCore import vtkObject

import vis4gs

# Not the default warm-up, so that both sides must pass it on (--warmup, warmup=).
WARMUP = 3
failures = []
vtkObject.GlobalWarningDisplayOff()


def check(cond, what):
    print(("ok: " if cond else "FAILED: ") + what)
    if not cond:
        failures.append(what)


def main(vis4gs_exe, log_path, folder, iterations):
    shutil.rmtree(folder, ignore_errors=True)
    os.makedirs(folder)
    scene = vis4gs.open(log_path)
    coverage = scene.scores(["coverage"])["coverage"]
    opacity = scene["Opacity"]
    candidates = np.flatnonzero((opacity >= 0.1) & (coverage > 0))
    floater = int(scene.ids[candidates[np.argmin(coverage[candidates])]])
    print(f"the case study's floater: Gaussian {floater} of iteration {scene.iteration}, "
          f"View Coverage {coverage[scene.ids == floater][0]:.4f}")

    # The command line on the cleaned scene.
    cleaned = os.path.join(folder, "cleaned.ply")
    scene.select(mask=scene.ids != floater).save(cleaned)
    cli = os.path.join(folder, "cli")
    result = subprocess.run([vis4gs_exe, "repair", log_path, cleaned,
                             f"--iterations={iterations}", f"--warmup={WARMUP}", "--threads=2",
                             f"--output={cli}"],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(result.stdout)
    check(result.returncode == 0, f"vis4gs repair exits 0 (got {result.returncode})")
    if result.returncode != 0:
        return
    with open(os.path.join(cli, "repair.csv"), newline="") as f:
        rows = list(csv.reader(f))

    # Python, the same inputs (no log: the CLI's is checked above and in CheckRepair.py).
    repaired = scene.repair(ids=[floater], iterations=iterations, warmup=WARMUP, threads=2)
    figures = repaired.figures
    try:
        scene.repair(ids=[floater], iterations=2, iteration=scene.iteration + 1)
        check(False, "repair(iteration=) of another snapshot of a log raises")
    except vis4gs.Vis4GSError as e:
        check("open that snapshot instead" in str(e), f"repair(iteration=) of another snapshot "
              f"of a log raises: {e}")
    check(list(figures) == rows[0], f"the figures' columns are repair.csv's: {list(figures)}")
    check(len(rows) - 1 == len(figures["view"]), f"{len(rows) - 1} rows in repair.csv, "
          f"{len(figures['view'])} in Python")
    same = True
    for r, row in enumerate(rows[1:]):
        for c, name in enumerate(rows[0]):
            value = figures[name][r]
            text = value if isinstance(value, str) else "%.9g" % value
            if text != row[c]:
                same = False
                print(f"row {r} {name}: Python {text}, repair.csv {row[c]}")
    check(same, "every figure equals repair.csv's, as printed")

    # The repaired Gaussians: the CLI log's last snapshot, bit for bit; positions fixed.
    with h5py.File(os.path.join(cli, "repaired.h5"), "r") as f:
        last = sorted(f["snapshots"].keys(), key=int)[-1]
        snap = f["snapshots"][last]
        check(int(last) == scene.iteration + iterations == repaired.iteration,
              f"the repaired snapshot is iteration {last}")
        check(np.array_equal(snap["id"][()].astype(np.int64), repaired.ids),
              "the repaired ids are the CLI's")
        check(np.array_equal(snap["position"][()].view(np.uint32),
                             np.asarray(repaired.positions, dtype=np.float32).view(np.uint32)),
              "the repaired positions are the CLI's, bit for bit")
        check(np.array_equal(np.asarray(snap["opacity_logit"][()]).reshape(-1).view(np.uint32),
                             np.asarray(repaired["OpacityLogit"],
                                        dtype=np.float32).reshape(-1).view(np.uint32)),
              "the repaired opacities are the CLI's, bit for bit")
    kept = scene.ids != floater
    check(np.array_equal(np.asarray(scene.positions)[kept], np.asarray(repaired.positions)),
          "positions fixed")
    # The direction of the deletion on the planted case.
    mean = {figures["split"][r]: r for r in range(len(figures["view"]))
            if figures["view"][r] == "mean"}
    t, h = mean["train"], mean["test"]
    for split, r in (("training", t), ("test", h)):
        print(f"{split} PSNR: source {figures['psnr_source'][r]:.4f} dB, deleted "
              f"{figures['psnr_deleted'][r]:.4f} dB, after {iterations} iterations "
              f"{figures['psnr_repaired'][r]:.4f} dB")
    check(figures["psnr_deleted"][h] > figures["psnr_source"][h],
          "deleting the floater raises the test views' PSNR")
    check(figures["psnr_repaired"][t] != figures["psnr_deleted"][t],
          "the fine-tune changed the training figures")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4]))
    if failures:
        print(f"FAILED: {len(failures)} check(s)")
        sys.exit(1)
    print("Scene.repair() = vis4gs repair")

"""Guided clean-up from Python (issue 20): Scene.select_rule, Scene.measure_removal and
Scene.compare against what we did not compute with the layer.

Usage: TestCleanupLayer.py VIS4GS LOG CLEANUP_DIR OUTPUT_DIR
  CLEANUP_DIR: the output of `vis4gs analyze LOG --scores=coverage --select=views<=3 --delete
  --report` (the vis4gsCleanup-floaters fixture), read as files.

- select_rule("views<=3") selects the ids of the program's selection.csv and keeps its
  canonical rule (selection-rule.txt); add / subtract / intersect with a current selection and
  the rule re-applied to another iteration equal numpy's evaluation of the rules;
- measure_removal() of that selection writes the program's before-after.csv byte for byte (an
  independent path into the same Core: the program's own reading of the log and extracted
  PNGs), and the PSNR of one changed view, before and after, equals a numpy float64
  computation from the layer's renders and the log's image read with h5py;
- planted cases found by their scores: deleting the case-study floater (lowest positive View
  Coverage with opacity >= 0.1) raises the PSNR of a test view it took part in; deleting the
  largest opaque Gaussian that nearly every training view sees lowers the training PSNR;
- compare() of iterations 400 and 1600 writes `vis4gs compare`'s differences.csv byte for byte
  and its id sets equal the file's statuses, id for id.
Prints "FAILED: ..." for each failed check and exits 1.
"""
import csv
import os
import subprocess
import sys
import time

import h5py
import numpy as np

import vis4gs

problems = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        problems.append(what)


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def main(program, log_path, cleanup, output):
    os.makedirs(output, exist_ok=True)
    cpu = time.process_time()
    # The log's images, read before the layer opens the log (HDF5 refuses a second open with
    # other locking flags in one process).
    with h5py.File(log_path, "r") as f:
        log_images = {name: f["images"][name][()] for name in f["images"]}
    scene = vis4gs.open(log_path)

    # Selection by rule = the program's selection.csv and canonical rule.
    with open(os.path.join(cleanup, "selection-rule.txt")) as f:
        saved_rule = f.read().strip()
    floaters = scene.select_rule("Views <= 3")
    program_ids = np.loadtxt(os.path.join(cleanup, "selection.csv"), delimiter=",", skiprows=1,
                             dtype=np.int64, ndmin=1)
    check(floaters.rule == saved_rule, f"rule in canonical form {floaters.rule!r} = the "
          f"program's {saved_rule!r}")
    check(np.array_equal(np.sort(floaters.ids), np.sort(program_ids)),
          f"select_rule: {len(floaters)} ids = selection.csv's {program_ids.size}")
    check(floaters.mask.sum() == len(floaters) and 0 < len(floaters) < len(scene),
          "the mask marks the selection, some but not all")
    coverage = scene["ViewCoverage"].astype(np.float64)
    views = np.round(coverage * scene.views_used)
    opacity = 1.0 / (1.0 + np.exp(-scene["OpacityLogit"].astype(np.float64)))
    ids = scene.ids.astype(np.int64)
    few = views <= 3
    opaque = opacity >= 0.5
    for combine, expected in (("add", few | opaque), ("subtract", opaque & ~few),
                              ("intersect", opaque & few)):
        combined = scene.select_rule("views<=3", combine=combine, current=opaque)
        check(np.array_equal(np.sort(combined.ids), np.sort(ids[expected])),
              f"{combine} with a current mask: {len(combined)} ids = numpy's {expected.sum()}")
    other = scene.at(1600)
    again = other.select_rule(floaters.rule)
    other_views = np.round(other["ViewCoverage"].astype(np.float64) * other.views_used)
    check(other.iteration == 1600 and np.array_equal(
        np.sort(again.ids), np.sort(other.ids.astype(np.int64)[other_views <= 3])),
        f"the rule re-applied to iteration {other.iteration}: {len(again)} ids = numpy's")
    try:
        scene.select_rule("covrage<=0.1")
        check(False, "a misspelt rule raises")
    except vis4gs.Vis4GSError as e:
        check("covrage" in str(e), f"a misspelt rule raises, naming the word: {e}")

    # Before / after = the program's before-after.csv, byte for byte.
    effect = scene.measure_removal(ids=floaters.ids, threads=2)
    mine = effect.to_csv(os.path.join(output, "before-after.csv"))
    check(read_bytes(mine) == read_bytes(os.path.join(cleanup, "before-after.csv")),
          "measure_removal's figures write the program's before-after.csv byte for byte")
    check(effect.removed == len(floaters) and effect.kept == len(scene) - len(floaters),
          f"removed {effect.removed}, kept {effect.kept}")
    change = effect["psnr_after"] - effect["psnr_before"]
    finite = change[np.isfinite(change)]
    check(np.all(np.diff(finite) >= 0), "the worst PSNR change first")

    # One view recomputed in numpy float64: the layer's renders against the log's image.
    row = int(np.argmax(np.abs(np.nan_to_num(change))))
    camera = int(effect["camera"][row])
    name = effect["view"][row]
    image = log_images[name].astype(np.float32) / np.float32(255)
    before = np.clip(scene.render(camera=camera).astype(np.float64), 0, 1)
    after = np.clip(scene.select(mask=~floaters.mask).render(camera=camera).astype(np.float64),
                    0, 1)
    psnr = [-10 * np.log10(np.mean((r - image.astype(np.float64)) ** 2)) for r in (before, after)]
    check(abs(psnr[0] - effect["psnr_before"][row]) < 1e-6 and
          abs(psnr[1] - effect["psnr_after"][row]) < 1e-6,
          f"view {name}: PSNR {effect['psnr_before'][row]:.6f} -> {effect['psnr_after'][row]:.6f}"
          f" = numpy's {psnr[0]:.6f} -> {psnr[1]:.6f}")

    # Planted cases, found by their scores.
    visible = np.flatnonzero((opacity >= 0.1) & (coverage > 0))
    floater = ids[visible[np.argmin(coverage[visible])]]
    single = scene.measure_removal(ids=[floater], threads=2)
    same = single["affected"] == 0
    check(same.any() and np.array_equal(single["psnr_after"][same], single["psnr_before"][same])
          and np.array_equal(single["l1_after"][same], single["l1_before"][same]),
          f"the {same.sum()} views the floater takes no part in: after == before exactly")
    check(single.baseline_reused and single.views_rendered == (~same).sum(),
          f"the 'before' of the first measurement is reused: {single.views_rendered} views "
          "rendered, those the floater changes")
    test_rows = (single["split"] == "test") & (single["affected"] == 1)
    gains = single["psnr_after"][test_rows] - single["psnr_before"][test_rows]
    check(gains.size > 0 and gains.max() > 0,
          f"deleting the case-study floater {floater} raises the PSNR of a test view it took "
          f"part in (largest gain {gains.max() if gains.size else float('nan'):.2e} dB)")
    volume = np.exp(scene["LogScale"].astype(np.float64).sum(axis=1))
    surface = np.flatnonzero((coverage >= 0.9) & (opacity >= 0.9))
    gaussian = ids[surface[np.argmax(volume[surface])]] if surface.size else -1
    solid = scene.measure_removal(ids=[gaussian], threads=2)
    train = solid.totals["train"]
    check(surface.size > 0 and train["psnr_after"] < train["psnr_before"],
          f"deleting surface Gaussian {gaussian} lowers the training PSNR "
          f"({train['psnr_before']:.6f} -> {train['psnr_after']:.6f} dB)")

    # Comparison = `vis4gs compare`'s differences.csv, id for id.
    folder = os.path.join(output, "compare")
    thresholds = (0.01, 0.05, 0.1)
    subprocess.run([program, "compare", log_path, log_path, "--iteration-a=400",
                    "--iteration-b=1600", f"--move={thresholds[0]}",
                    f"--opacity={thresholds[1]}", f"--scale={thresholds[2]}", "--no-metrics",
                    f"--output={folder}"], check=True, stdout=subprocess.DEVNULL)
    diff = scene.at(400).compare(scene.at(1600), *thresholds)
    mine = diff.to_csv(os.path.join(output, "differences.csv"))
    theirs = os.path.join(folder, "differences.csv")
    check(read_bytes(mine) == read_bytes(theirs),
          "compare()'s table writes the program's differences.csv byte for byte")
    with open(theirs) as f:
        rows = list(csv.DictReader(f))
    kinds = {"born": "born", "died": "died", "moved": "moved",
             "opacity_changed": "opacity", "scale_changed": "scale"}
    for kind, word in kinds.items():
        expected = sorted(int(r["id"]) for r in rows if word in r["status"].split("+"))
        check(list(getattr(diff, kind)) == expected,
              f"{kind}: {len(getattr(diff, kind))} ids = differences.csv's {len(expected)}")
    expected = sorted(int(r["id"]) for r in rows if r["status"] == "unchanged")
    check(list(diff.unchanged) == expected, f"unchanged: {len(expected)} ids")
    print(f"CPU time {time.process_time() - cpu:.1f} s (this process)")
    if problems:
        print(f"FAILED: {len(problems)} checks")
        return 1
    print("clean-up layer = vis4gs analyze --report and vis4gs compare")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))

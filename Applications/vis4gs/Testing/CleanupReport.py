"""Checks the outputs of `vis4gs analyze --select=RULE --delete --report` (issue 20).

The files, not the program's text: the selection is compared with an independent numpy
evaluation of the rule over scores.csv and scores.ply, cleaned.ply (parsed here with numpy)
holds exactly the Gaussians not selected, before-after.csv has the direction the planted case
expects, its rows are sorted worst change first, unchanged views are identical, and the
report embeds the before/after images (valid PNGs of the views' size).

Usage: CleanupReport.py OUTPUT_DIR CASE LOG   CASE: floaters | surface; LOG: the analysed log
  floaters  rule "views<=3": training PSNR down, test PSNR up (Gaussians fitted to few views)
  surface   rule "coverage>=0.9 and opacity>=0.9" (the opaque Gaussians nearly every training
            view sees: the surfaces): training and test PSNR down, training L1 up
"""
import base64
import csv
import os
import re
import struct
import sys

import h5py
import numpy as np


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    assert header[1] == "format binary_little_endian 1.0", header[1]
    count = int(next(line.split()[2] for line in header if line.startswith("element vertex")))
    types = {"float": "<f4", "double": "<f8", "int": "<i4", "uchar": "u1", "uint": "<u4"}
    fields = [(line.split()[2], types[line.split()[1]])
              for line in header if line.startswith("property")]
    return np.frombuffer(data, dtype=np.dtype(fields), count=count, offset=end)


def png_size(raw):
    assert raw[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    return struct.unpack(">II", raw[16:24])


def main(folder, case, log):
    problems = []

    def check(ok, what):
        print(("ok: " if ok else "FAILED: ") + what)
        if not ok:
            problems.append(what)

    scores = np.genfromtxt(os.path.join(folder, "scores.csv"), delimiter=",", names=True)
    rows = list(csv.DictReader(open(os.path.join(folder, "before-after.csv"))))
    views = [r for r in rows if r["view"] != "mean"]
    means = {r["split"]: r for r in rows if r["view"] == "mean"}
    train_views = sum(1 for r in views if r["split"] == "train")
    ply = read_ply(os.path.join(folder, "scores.ply"))
    opacity = 1.0 / (1.0 + np.exp(-ply["opacity"].astype(np.float64)))
    coverage = scores["ViewCoverage"]
    if case == "floaters":
        expected = np.round(coverage * train_views) <= 3
    else:
        expected = (coverage >= 0.9) & (opacity >= 0.9)
    ids = scores["GaussianId"].astype(np.int64)
    selected = np.genfromtxt(os.path.join(folder, "selection.csv"), delimiter=",", skip_header=1,
                             dtype=np.int64).reshape(-1)
    check(np.array_equal(np.sort(selected), np.sort(ids[expected])),
          f"selection.csv ({selected.size} ids) equals numpy's evaluation ({expected.sum()})")
    check(0 < selected.size < ids.size, "the rule selects some but not all Gaussians")

    cleaned = read_ply(os.path.join(folder, "cleaned.ply"))
    kept = cleaned["id"].astype(np.int64)
    check(kept.size == ids.size - selected.size,
          f"cleaned.ply holds {kept.size} = {ids.size} - {selected.size} Gaussians")
    check(np.array_equal(kept, ids[~expected]), "cleaned.ply holds the others, in order")
    check(np.array_equal(cleaned["opacity"], ply["opacity"][~expected]),
          "their parameters are unchanged")

    change = [float(r["psnr_after"]) - float(r["psnr_before"]) for r in views]
    # The CSV holds 9 significant digits: order within their rounding.
    check(all(a <= b + 1e-6 for a, b in zip(change, change[1:])), "views sorted worst change first")
    for r in views:
        if r["affected"] == "0":
            same = all(r[f"{m}_before"] == r[f"{m}_after"] for m in ("psnr", "ssim", "l1"))
            if not same:
                check(False, f"{r['view']} unchanged but its figures differ")
    for split in ("train", "test"):
        subset = [r for r in views if r["split"] == split]
        mean_before = np.mean([float(r["psnr_before"]) for r in subset])
        check(abs(mean_before - float(means[split]["psnr_before"])) < 1e-6,
              f"{split} mean PSNR is the mean of its views")
    delta = {s: float(means[s]["psnr_after"]) - float(means[s]["psnr_before"]) for s in means}
    print(f"PSNR change: train {delta['train']:+.4f} dB, test {delta['test']:+.4f} dB")
    if case == "floaters":
        check(delta["train"] < 0, "deleting Gaussians fitted to few views lowers training PSNR")
        check(delta["test"] > 0, "and raises test PSNR")
    else:
        check(delta["train"] < 0 and delta["test"] < 0,
              "deleting surface Gaussians lowers training and test PSNR")
        check(float(means["train"]["l1_after"]) > float(means["train"]["l1_before"]),
              "and raises the training L1")

    html = open(os.path.join(folder, "report.html"), encoding="utf-8").read()
    section = html[html.index("Clean-up: deleting the selection"):]
    images = re.findall(r'src="data:image/png;base64,([^"]+)"', section)
    check(len(images) >= 4 and len(images) % 4 == 0,
          f"the report embeds image/before/after/change per view ({len(images)} images)")
    with h5py.File(log, "r") as f:
        sizes = set(zip(f["cameras/width"][()].tolist(), f["cameras/height"][()].tolist()))
    for raw in images:
        if png_size(base64.b64decode(raw)) not in sizes:
            check(False, f"an embedded image is not a PNG of a view's size {sorted(sizes)}")
            break
    for name in os.listdir(folder):
        if name.startswith("cleanup-") and name.endswith(".png"):
            png_size(open(os.path.join(folder, name), "rb").read())
    if problems:
        print(f"FAILED: {len(problems)} problems")
        return 1
    print("the clean-up outputs agree with numpy and have the expected direction")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2], sys.argv[3]))

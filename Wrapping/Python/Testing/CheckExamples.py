"""Runs a Python-layer example of Documentation/examples and checks what it prints (and
writes) against what we did not compute with the layer: the outputs of `vis4gs demo`
(scores.csv, scores.ply, root-cause.txt) and `vis4gs render`.

  CheckExamples.py scores  EXAMPLES DEMO_OUTPUT
  CheckExamples.py lineage EXAMPLES DEMO_OUTPUT
  CheckExamples.py render  EXAMPLES [VIS4GS]   (with VIS4GS: a PLY + COLMAP folder, SharedData)
  CheckExamples.py all-tested EXAMPLES BUILD    (every example has a CTest test)
"""
import csv
import os
import re
import subprocess
import sys
import tempfile

import numpy as np
from vtkmodules.numpy_interface import dataset_adapter as dsa
from vtkmodules.vtkIOImage import vtkPNGReader

import vis4gs

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def run(example, *args, cwd):
    """The example's standard output (it must succeed)."""
    done = subprocess.run([sys.executable, os.path.join(examples, example), *args], cwd=cwd,
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    sys.stdout.write(done.stdout)
    if done.returncode != 0:
        sys.stdout.write(done.stderr)
        print(f"FAILED: {example} exited with {done.returncode}")
        sys.exit(1)
    return done.stdout.splitlines()


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return rows[0], {int(r[0]): dict(zip(rows[0], r)) for r in rows[1:]}


def png(path):
    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    w, h, _ = reader.GetOutput().GetDimensions()
    return np.asarray(dsa.WrapDataObject(reader.GetOutput()).PointData[0]).reshape(h, w, -1)[::-1]


def scores(demo_output, tmp):
    lines = run("scripting_scores.py", f"--output={tmp}", cwd=tmp)
    _, app = read_csv(os.path.join(demo_output, "scores.csv"))
    ids = np.array(list(app))  # the rows' order, which is scores.ply's
    for line in lines:
        m = re.match(r"top 3 by (\w+): (.*)", line)
        if not m:
            continue
        name, listed = m.group(1), re.findall(r"(\d+) \(([^)]*)\)", m.group(2))
        values = np.array([float(app[i][name]) for i in ids])
        extreme = values.min() if name == "ViewCoverage" else values.max()
        check(len(listed) == 3, f"{line}: three Gaussians")
        check(float(app[int(listed[0][0])][name]) == extreme,
              f"{line}: the first is the most suspicious by vis4gs demo's scores.csv")
        for gid, shown in listed:
            check(f"{float(app[int(gid)][name]):.6g}" == shown,
                  f"{line}: {gid} has {app[int(gid)][name]} in vis4gs demo's scores.csv")
    # Its CSV: the application's numbers, column for column (it asked for three scores).
    header, mine = read_csv(os.path.join(tmp, "scores.csv"))
    check(header == ["GaussianId", "ViewCoverage", "BlurScore", "NeedleScore", "NoVisibleView"],
          f"the example's CSV columns: {header}")
    check(sorted(mine) == sorted(app) and all(mine[i][c] == app[i][c] for i in mine
                                              for c in header),
          "the example's scores.csv holds vis4gs demo's values, character for character")
    # The weakly covered Gaussians: the application's coverage and its scores.ply's opacity.
    ply = vis4gs.open(os.path.join(demo_output, "scores.ply"))
    coverage = np.array([float(app[i]["ViewCoverage"]) for i in ids])
    weak = (coverage < 0.1) & (ply["Opacity"] >= 0.1)
    expected = set(ids[weak].tolist())
    count = [int(m.group(1)) for m in map(re.compile(r"(\d+) visible Gaussians").match, lines)
             if m]
    check(count == [len(expected)], f"weakly covered: printed {count}, scores.ply {len(expected)}")
    saved = vis4gs.open(os.path.join(tmp, "weakly-covered.ply"), id_property="id")
    check(set(saved.ids.tolist()) == expected, "weakly-covered.ply holds those Gaussians")
    return "scripting_scores.py: top lists, scores.csv and the selection agree with vis4gs demo"


def lineage(demo_output, tmp):
    lines = run("scripting_lineage.py", cwd=tmp)
    with open(os.path.join(demo_output, "root-cause.txt")) as f:
        expected = [line.split() for line in f.read().split("\n")[2:] if line.strip()]
    got = []
    for line in lines[1:]:
        m = re.match(r"\s+(\d+)\s+born\s+(\d+) \(([\w-]+)\), (alive|died (\d+)); coverage "
                     r"(in no snapshot|([\d.]+) at (\d+))$", line)
        check(m is not None, f"unexpected line: {line}")
        if m:
            got.append([m.group(1), m.group(2), m.group(3), m.group(5) or "alive"]
                       + (["(in", "no", "snapshot)"] if m.group(7) is None
                          else [m.group(7), "at", m.group(8)]))
    check(got == expected, f"the trace differs from vis4gs demo's root-cause.txt:\n{got}")
    with open(os.path.join(demo_output, "root-cause.txt")) as f:
        floater = re.match(r"Root-cause trace of Gaussian (\d+)", f.readline()).group(1)
    check(f"Gaussian {floater}," in lines[0], f"{lines[0]}: the floater is {floater}")
    return f"scripting_lineage.py: the trace of {floater} is root-cause.txt's, step for step"


def render(tmp, vis4gs_exe=None):
    if vis4gs_exe is None:
        lines = run("scripting_render.py", "--size=96,64", f"--output={tmp}/view.png", cwd=tmp)
    else:
        sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "Testing",
                                        "Python"))
        from vis4gs_test_data import shared_data_dir
        data = shared_data_dir()
        ply = os.path.join(data, "inria_ply_tiny_kacytran", "point_cloud", "iteration_7000",
                           "point_cloud.ply")
        colmap = os.path.join(data, "colmap_statue_bartoszek")
        lines = run("scripting_render.py", ply, f"--cameras={colmap}", "--camera=DSC_5290",
                    "--size=100,66", f"--output={tmp}/view.png", cwd=tmp)
        subprocess.run([vis4gs_exe, "render", ply, f"--cameras={colmap}", "--camera=DSC_5290",
                        "--resolution=100,66", f"--output={tmp}/app.png"], check=True,
                       stdout=subprocess.DEVNULL)
        check(np.array_equal(png(f"{tmp}/view.png"), png(f"{tmp}/app.png")),
              "the example's PNG differs from vis4gs render's, pixel for pixel")
    for line in lines:
        m = re.match(r"(\S+\.png): (?:(\d+)x(\d+)|\d+ of \d+ Gaussians).*mean RGB ([\d.]+) "
                     r"([\d.]+) ([\d.]+)$", line)
        check(m is not None, f"unexpected line: {line}")
        if m:
            pixels = png(m.group(1)) / 255.0
            if m.group(2):
                check(pixels.shape[:2] == (int(m.group(3)), int(m.group(2))),
                      f"{line}: the PNG is {pixels.shape[1]}x{pixels.shape[0]}")
            # The printed mean is of the float image, the PNG's of its 8-bit rounding.
            mean = pixels.mean(axis=(0, 1))
            shown = np.array([float(m.group(k)) for k in (4, 5, 6)])
            check(np.all(np.abs(mean - shown) <= 0.5 / 255 + 0.5e-4),
                  f"{line}: the PNG's mean is {mean}")
    check(len(lines) == 2, "two images rendered")
    return "scripting_render.py: the PNGs hold what it printed" + \
        (" and equal vis4gs render's" if vis4gs_exe else "")


def all_tested(build):
    listed = subprocess.run(["ctest", "--test-dir", build, "-N"], stdout=subprocess.PIPE,
                            text=True, check=True).stdout
    names = os.listdir(examples)
    for name in sorted(n for n in names if n.endswith(".py")):
        stem = os.path.splitext(name)[0]
        check(re.search(rf"Vis4GSExample-{re.escape(stem)}\b", listed) is not None,
              f"{name} has no Vis4GSExample-{stem} test")
    return f"every example of {examples} has a CTest test"


if __name__ == "__main__":
    what, examples = sys.argv[1], os.path.abspath(sys.argv[2])
    with tempfile.TemporaryDirectory() as tmp:
        if what == "all-tested":
            message = all_tested(sys.argv[3])
        elif what == "render":
            message = render(tmp, *sys.argv[3:4])
        else:
            message = {"scores": scores, "lineage": lineage}[what](sys.argv[3], tmp)
    if failures:
        print("FAILED:", *failures, sep="\n  ")
        sys.exit(1)
    print(message)

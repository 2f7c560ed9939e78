"""Runs `vis4gs analyze` (or `vis4gs demo`, its batch form) and checks the files it claims
against an independent computation, not against a line of its output:

- the exit status is 0 and scores.csv, scores.ply and report.html exist;
- every score column of scores.csv equals the scores computed here from the same input
  through the wrapped VTK pipeline (the log or PLY reader, the camera reader, the score
  filter), row for row by GaussianId; NoVisibleView likewise;
- scores.ply reads back with numpy (binary little-endian): one row per CSV row, the
  Gaussian properties plus one float property per score (+ uchar NoVisibleView), positions
  equal to the input's and score properties equal to the CSV's values as float32;
- report.html names, for each score, the Gaussians that rank first by that score here
  (lowest View Coverage, highest other scores; ties at the K-th value accepted);
- demo only: root-cause.txt names the floater, a Gaussian of the last snapshot; it is the
  visible Gaussian (opacity >= 0.1 from the PLY's logit) with the lowest positive View
  Coverage of the CSV, its coverage and "n of m training views" figures equal the CSV's and
  the log's, every trace line at the last snapshot has the CSV's coverage, and report.html
  names it.

Usage: CheckAnalyzeOutputs.py VIS4GS OUTPUT_DIR analyze SCENE [OPTIONS...]
       CheckAnalyzeOutputs.py VIS4GS OUTPUT_DIR demo --log=LOG [OPTIONS...]
(the options are passed on; the ones that change the scores are read here too). Prints
"FAILED: ..." and exits 1 on a failed check.
"""
import csv
import html
import math
import os
import re
import shutil
import subprocess
import sys

import numpy as np

# The score filter's warnings (Gaussians seen by no view) are not this test's concern.
from vtkmodules.vtkCommonCore import vtkObject

vtkObject.GlobalWarningDisplayOff()



def registry():
    """The score registry as the Python layer reads it: {short name: array}, the default list,
    the short names that need cameras, the arrays whose suspicious end is low."""
    import vis4gs
    from vis4gs import scene
    reg = vis4gs.vtkGaussianScoreRegistry
    low = {reg.GetArrayName(i) for i in range(reg.GetNumberOfScores())
           if reg.GetSuspiciousEnd(i) < 0}
    return scene.SCORES, scene.DEFAULT_SCORES, scene._NEEDS_CAMERAS, low


PLY_TYPES = {"float": "<f4", "float32": "<f4", "double": "<f8", "float64": "<f8",
             "uchar": "u1", "uint8": "u1", "char": "i1", "int8": "i1", "short": "<i2",
             "int16": "<i2", "ushort": "<u2", "uint16": "<u2", "int": "<i4", "int32": "<i4",
             "uint": "<u4", "uint32": "<u4"}
failures = []


def summary(before, text):
    """Prints @p text as passed when no check failed since @p before failures."""
    print(("ok: " if len(failures) == before else "checked, with failures above: ") + text)


def check(ok, message):
    if not ok:
        failures.append(message)
        print("FAILED: " + message)
    return ok


def stop(message):
    print("FAILED: " + message)
    sys.exit(1)


def parse_options(words):
    positional = [w for w in words if not w.startswith("--")]
    options = {}
    for w in words:
        if w.startswith("--"):
            key, _, value = w[2:].partition("=")
            options[key] = value
    return positional, options


def compute_scores(scene, options, demo):
    """The scores of SCENE through the wrapped readers and the score filter."""
    import vis4gs
    from vtkmodules.util.numpy_support import vtk_to_numpy

    known = {"scores", "cameras", "view-stride", "loss-resolution", "coverage-resolution",
             "footprint", "output", "top", "overlay-views", "threads", "log", "no-gui",
             "occlusion-threshold", "images", "stop-after-stage"}
    unknown = set(options) - known
    if unknown:
        stop(f"this checker does not reproduce the option(s) {sorted(unknown)}")
    score_arrays, default, needs_cameras, _ = registry()
    wanted = options["scores"].split(",") if "scores" in options else list(default)
    need_cameras = any(s in needs_cameras for s in wanted)
    train_views = None
    if scene.endswith(".h5"):
        reader = vis4gs.vtkGaussianTrainingLogReader()
        reader.SetFileName(scene)
        reader.LoadSHRestOn()  # analyze renders every SH degree of the snapshot
        reader.UpdateInformation()
        n = reader.GetNumberOfSnapshots()
        reader.SetIteration(reader.GetSnapshotIteration(n - 1))
        points_port, cameras_port = reader.GetOutputPort(0), reader.GetOutputPort(1)
    else:
        reader = vis4gs.vtkGaussianSceneReader()
        reader.SetFileName(scene)
        points_port, cameras_port = reader.GetOutputPort(0), None
        if need_cameras:
            if "cameras" not in options:
                stop("this checker needs --cameras for a scene file")
            camera_reader = vis4gs.vtkGaussianCameraReader()
            camera_reader.SetFileName(options["cameras"])
            camera_reader.SetRequireImages(False)
            if "images" in options:
                camera_reader.SetImageFolder(os.path.abspath(options["images"]))
            cameras_port = camera_reader.GetOutputPort(0)
    score_filter = vis4gs.vtkGaussianArtifactScoreFilter()
    score_filter.SetInputConnection(points_port)
    if need_cameras:
        score_filter.SetCamerasConnection(cameras_port)
    score_filter.SetScores(",".join(wanted))
    loss = int(options.get("loss-resolution", 1))
    coverage = int(options.get("coverage-resolution", 1))
    stride = int(options.get("view-stride", 1))
    if options.get("stop-after-stage") == "1":
        # The first stage of progressive scores (vis4gs analyze --help): every 8th of the
        # views, maps at 1/4 of the resolution (at most 1/8).
        loss, coverage, stride = min(8, 4 * loss), min(8, 4 * coverage), 8 * stride
    score_filter.SetLossResolution(loss)
    score_filter.SetCoverageResolution(coverage)
    score_filter.SetViewStride(stride)
    score_filter.SetFootprintMode(1 if options.get("footprint") == "ellipse" else 0)
    if "occlusion-threshold" in options:
        score_filter.SetOcclusionThreshold(float(options["occlusion-threshold"]))
    score_filter.Update()
    out = score_filter.GetOutput()
    pd = out.GetPointData()
    result = {"GaussianId": vtk_to_numpy(pd.GetPedigreeIds()).astype(np.int64),
              "points": vtk_to_numpy(out.GetPoints().GetData()).astype(np.float64)}
    for key in wanted:
        array = pd.GetArray(score_arrays[key])
        if array is None:
            stop(f"the score filter computed no {score_arrays[key]}")
        result[score_arrays[key]] = vtk_to_numpy(array).astype(np.float64)
    if need_cameras and pd.GetArray("NoVisibleView") is not None:
        result["NoVisibleView"] = vtk_to_numpy(pd.GetArray("NoVisibleView")).astype(np.int64)
    if demo:
        cameras = score_filter.GetInputDataObject(1, 0)
        split = cameras.GetColumnByName("Split")
        train_views = sum(1 for r in range(cameras.GetNumberOfRows()) if split.GetValue(r) == 0)
        result["snapshot"] = reader.GetIteration()

        def coverage_at(iteration):
            """View Coverage of every Gaussian of the snapshot of @p iteration."""
            reader.SetIteration(iteration)
            coverage_filter = vis4gs.vtkGaussianArtifactScoreFilter()
            coverage_filter.SetInputConnection(reader.GetOutputPort(0))
            coverage_filter.SetCamerasConnection(reader.GetOutputPort(1))
            coverage_filter.SetComputeBlurScore(False)
            coverage_filter.SetComputeNeedleScore(False)
            coverage_filter.SetComputeNeedleShape(False)
            coverage_filter.Update()
            pd = coverage_filter.GetOutput().GetPointData()
            return (vtk_to_numpy(pd.GetPedigreeIds()).astype(np.int64),
                    vtk_to_numpy(pd.GetArray("ViewCoverage")).astype(np.float64))
        result["coverage_at"] = coverage_at
    result["train_views"] = train_views
    return wanted, result


def read_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        stop(f"{path} is empty")
    header, body = rows[0], rows[1:]
    columns = {name: np.array([float(r[c]) for r in body]) for c, name in enumerate(header)}
    return header, columns


def read_ply(path):
    """numpy's reading of a binary little-endian PLY with one vertex element."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\n") or end < 0:
        stop(f"{path}: not a PLY file (no 'ply' magic or no end_header)")
    lines = data[:end].decode("ascii").splitlines()
    if "format binary_little_endian 1.0" not in lines:
        stop(f"{path}: not binary little-endian")
    elements = [l.split() for l in lines if l.startswith("element ")]
    if len(elements) != 1 or elements[0][1] != "vertex":
        stop(f"{path}: expected one vertex element, got {elements}")
    count = int(elements[0][2])
    fields = []
    for l in lines:
        if l.startswith("property "):
            words = l.split()
            if words[1] == "list" or words[1] not in PLY_TYPES:
                stop(f"{path}: unexpected property line '{l}'")
            fields.append((words[2], PLY_TYPES[words[1]]))
    dtype = np.dtype(fields)
    body = data[end + len(b"end_header\n"):]
    if len(body) != count * dtype.itemsize:
        stop(f"{path}: {len(body)} bytes of vertex data, the header says {count} x "
             f"{dtype.itemsize}")
    return np.frombuffer(body, dtype=dtype, count=count)


def report_tables(text):
    """The GaussianIds of each 'Most suspicious' table of report.html, by score name."""
    tables = {}
    for m in re.finditer(r"<h3>(\w+)[^<]*</h3><table>(.*?)</table>", text, re.S):
        ids = [int(i) for i in re.findall(r"<tr><td>\d+</td><td>(-?\d+)</td>", m.group(2))]
        tables[m.group(1)] = ids
    return tables


def check_outputs(output, wanted, ref, top):
    for name in ("scores.csv", "scores.ply", "report.html"):
        check(os.path.isfile(os.path.join(output, name)), f"{name} was not written")
    if failures:
        stop("outputs missing")
    before = len(failures)
    header, csv_cols = read_csv(os.path.join(output, "scores.csv"))
    score_arrays, _, _, lowest_first = registry()
    # Registry order, whatever the order asked.
    names = [a for k, a in score_arrays.items() if k in wanted]
    expected_header = ["GaussianId"] + names + (["NoVisibleView"] if "NoVisibleView" in ref
                                                else [])
    check(header == expected_header, f"scores.csv header {header}, expected {expected_header}")
    ids = csv_cols["GaussianId"].astype(np.int64)
    check(np.array_equal(ids, ref["GaussianId"]),
          f"scores.csv has {len(ids)} Gaussians (ids {ids[:5]}...), the input has "
          f"{len(ref['GaussianId'])} ({ref['GaussianId'][:5]}...)")
    if len(ids) != len(ref["GaussianId"]):
        stop("row counts differ")
    for name in names + (["NoVisibleView"] if "NoVisibleView" in ref else []):
        if name not in csv_cols:
            continue
        got, exp = csv_cols[name], ref[name]
        # The CSV prints 9 significant digits: a relative 1e-8 covers the printing only.
        same = np.isclose(got, exp, rtol=1e-8, atol=1e-300) | (np.isnan(got) & np.isnan(exp)) | \
            (np.isinf(got) & (got == exp))
        bad = np.flatnonzero(~same)
        check(bad.size == 0,
              f"scores.csv {name} differs from the score filter's at {bad.size} of {len(got)} "
              f"Gaussians" + (f", e.g. Gaussian {ids[bad[0]]}: {got[bad[0]]!r} vs "
                              f"{exp[bad[0]]!r}" if bad.size else ""))
    summary(before, f"scores.csv: {len(ids)} Gaussians x {len(header) - 1} columns equal the "
            f"score filter's ({', '.join(names)})")
    before = len(failures)

    ply = read_ply(os.path.join(output, "scores.ply"))
    props = list(ply.dtype.names)
    check(len(ply) == len(ids), f"scores.ply has {len(ply)} rows, scores.csv {len(ids)}")
    for p in ("x", "y", "z", "opacity", "scale_0", "rot_0", "f_dc_0"):
        check(p in props, f"scores.ply lacks the Gaussian property {p}")
    for name in names:
        if check(name in props and ply.dtype[name] == np.dtype("<f4"),
                 f"scores.ply lacks the float property {name}"):
            got = ply[name].astype(np.float64)
            exp = csv_cols[name].astype(np.float32).astype(np.float64)
            # float32 of the CSV's 9 digits may round the other way than float32 of the
            # double: one float32 step apart at most.
            same = (np.abs(got - exp) <= np.spacing(np.abs(exp).astype(np.float32))) | \
                (np.isnan(got) & np.isnan(exp)) | (np.isinf(got) & (got == exp))
            check(same.all(), f"scores.ply {name} differs from scores.csv's at "
                  f"{int((~same).sum())} rows")
    if "NoVisibleView" in ref:
        if check("NoVisibleView" in props and ply.dtype["NoVisibleView"] == np.dtype("u1"),
                 "scores.ply lacks the uchar property NoVisibleView"):
            check(np.array_equal(ply["NoVisibleView"].astype(np.int64), ref["NoVisibleView"]),
                  "scores.ply NoVisibleView differs from the score filter's")
    xyz = np.stack([ply["x"], ply["y"], ply["z"]], axis=1).astype(np.float64)
    check(np.array_equal(xyz, ref["points"].astype(np.float32).astype(np.float64)),
          "scores.ply positions differ from the input's")
    summary(before, f"scores.ply: {len(ply)} rows, {len(props)} properties "
            f"(..., {', '.join(props[-5:])}) read back")
    before = len(failures)

    with open(os.path.join(output, "report.html"), encoding="utf-8") as f:
        report = f.read()
    check(report.rstrip().endswith("</html>"), "report.html is not complete")
    tables = report_tables(report)
    for name in names:
        values = ref[name]
        # NaN ranks nowhere; +inf (a cost for no contribution) ranks first.
        finite = ~np.isnan(values)
        key = np.where(finite, values if name in lowest_first else -values, np.inf)
        listed = tables.get(name)
        if not check(listed is not None, f"report.html has no table of the {name} ranking"):
            continue
        k = min(top, int(finite.sum()))
        check(len(listed) == k, f"report.html lists {len(listed)} Gaussians by {name}, "
              f"expected {k}")
        if k == 0:
            continue
        kth = np.sort(key)[k - 1]
        row_of = {int(g): r for r, g in enumerate(ref["GaussianId"])}
        outside = [g for g in listed if g not in row_of or key[row_of[g]] > kth]
        check(not outside, f"report.html's {name} table names Gaussians {outside} that do not "
              f"rank in the first {k} here")
    summary(before, f"report.html: the first {top} by each of {', '.join(names)} are the ones "
            "ranked here")
    return report, csv_cols, ply


def check_root_cause(output, ref, report, csv_cols, ply, min_opacity):
    before = len(failures)
    path = os.path.join(output, "root-cause.txt")
    if not check(os.path.isfile(path), "root-cause.txt was not written"):
        return
    with open(path) as f:
        text = f.read()
    m = re.match(r"Root-cause trace of Gaussian (\d+), a visible floater \(View Coverage "
                 r"([0-9.eE+-]+) = (\d+) of (\d+) training views; lowest among Gaussians with "
                 r"opacity >= ([0-9.]+) at iteration (\d+)\):\n", text)
    if not check(m is not None, "root-cause.txt does not start with its headline"):
        return
    floater, coverage, seen, views = int(m.group(1)), float(m.group(2)), int(m.group(3)), \
        int(m.group(4))
    ids = csv_cols["GaussianId"].astype(np.int64)
    rows = np.flatnonzero(ids == floater)
    if not check(rows.size == 1, f"Gaussian {floater} of root-cause.txt is not a Gaussian of "
                 "the last snapshot (scores.csv)"):
        return
    row = rows[0]
    cov = csv_cols["ViewCoverage"]
    check(int(m.group(6)) == ref["snapshot"], f"root-cause.txt traces iteration {m.group(6)}, "
          f"the last snapshot is {ref['snapshot']}")
    check(views == ref["train_views"], f"root-cause.txt counts {views} training views, the log "
          f"has {ref['train_views']}")
    check(math.isclose(coverage, cov[row], rel_tol=1e-5),
          f"root-cause.txt gives View Coverage {coverage}, scores.csv {cov[row]}")
    check(seen == round(cov[row] * ref["train_views"]),
          f"root-cause.txt: {seen} of {views} views, scores.csv: {cov[row]} x {views}")
    opacity = 1.0 / (1.0 + np.exp(-ply["opacity"].astype(np.float64)))
    candidates = np.flatnonzero((opacity >= min_opacity) & (cov > 0))
    lowest = candidates[np.argmin(cov[candidates])] if candidates.size else -1
    check(lowest >= 0 and cov[row] == cov[lowest],
          f"Gaussian {floater} (coverage {cov[row]}) is not the visible Gaussian with the "
          f"lowest positive coverage (Gaussian {ids[lowest]}, {cov[lowest]})")
    # The trace: the floater first, then its ancestors, each with its View Coverage at a
    # logged snapshot, which the score filter gives here for that snapshot.
    trace = [l.split() for l in text.splitlines()[2:] if l.strip()]
    check(trace and int(trace[0][0]) == floater, "the trace does not start with the floater")
    at = {}
    for words in trace:
        if words[-2] == "at":
            at.setdefault(int(words[-1]), []).append((int(words[0]), float(words[-3])))
    for iteration, steps in sorted(at.items()):
        gids, values = ref["coverage_at"](iteration)
        for gid, value in steps:
            r = np.flatnonzero(gids == gid)
            check(r.size == 1 and abs(values[r[0]] - value) <= 5e-4,
                  f"root-cause.txt: Gaussian {gid} has coverage {value} at iteration "
                  f"{iteration}, the score filter "
                  f"{values[r[0]] if r.size else 'has no such Gaussian there'}")
    check(len(at) >= 1, "root-cause.txt gives no coverage at any snapshot")
    check(f"Root-cause trace of Gaussian {floater}," in html.unescape(report),
          f"report.html does not name the traced Gaussian {floater}")
    summary(before, f"root-cause.txt: Gaussian {floater}, coverage {cov[row]:g} = {seen} of "
            f"{views} training views, the lowest visible one; report.html names it")


def main(argv):
    if len(argv) < 3 or argv[2] not in ("analyze", "demo"):
        stop("usage: CheckAnalyzeOutputs.py VIS4GS OUTPUT_DIR analyze|demo ARGS...")
    vis4gs_exe, output, command, rest = argv[0], argv[1], argv[2], argv[3:]
    positional, options = parse_options(rest)
    demo = command == "demo"
    scene = options.get("log") if demo else (positional[0] if positional else None)
    if not scene:
        stop("give the input (analyze SCENE, demo --log=LOG)")
    if os.path.isdir(output):
        shutil.rmtree(output)  # an old report must not pass for a new one
    cmd = [vis4gs_exe, command] + rest + ["--output=" + output] + (["--no-gui"] if demo else [])
    run = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                         errors="replace")
    print(run.stdout, end="")
    if run.returncode != 0:
        stop(f"vis4gs {command} exited with status {run.returncode}")
    wanted, ref = compute_scores(scene, options, demo)
    top = int(options.get("top", 10 if demo else 20))  # the commands' defaults
    report, csv_cols, ply = check_outputs(output, wanted, ref, top)
    if demo:
        check_root_cause(output, ref, report, csv_cols, ply, float(options.get("min-opacity",
                                                                               0.1)))
    if failures:
        stop(f"{len(failures)} checks failed")
    print(f"vis4gs {command}: exit status 0 and its files checked")


if __name__ == "__main__":
    main(sys.argv[1:])

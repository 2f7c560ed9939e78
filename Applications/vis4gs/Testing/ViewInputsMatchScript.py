"""The application and a VTK Python script are one program (issue 22): `vis4gs view LOG
--dump-inputs=DIR` writes what the window gives its views (the scene with its scores, the
genealogy tree and family bands, the metrics table, and the property history the timeline
gets for a selection); this script builds the four views from
the same VTK classes a user connects (training-log reader, genealogy filter on its events
port, score filter on its Gaussians and cameras ports, tree / timeline / histogram views) and
requires every array to be equal, value for value (NaN equal to NaN) and name for name.
A vtkGaussianSession on the same log (the selection on its input) must give the same arrays on
every port. Independently of all, the Gaussians, the metrics and the selection's history (ids, snapshots,
position, opacity, largest scale) are compared with the log read by h5py and the tree's size
with the log's events.

Usage: ViewInputsMatchScript.py VIS4GS LOG OUTPUT_DIR"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdTypeArray
from vtkmodules.vtkCommonDataModel import vtkTable
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLTableReader

import vis4gs

program, log, output = sys.argv[1:4]
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def values(array):
    if array is None:
        return None
    if array.IsA("vtkStringArray"):
        return np.array([array.GetValue(i) for i in range(array.GetNumberOfValues())])
    return vtk_to_numpy(array)


def same(a, b):
    """Equal shapes and values, NaN equal to NaN (integers compared exactly too)."""
    if a is None or b is None or a.shape != b.shape:
        return False
    if a.dtype.kind == "f" or b.dtype.kind == "f":
        return np.array_equal(a.astype(np.float64), b.astype(np.float64), equal_nan=True)
    return np.array_equal(a, b)


def compare_fields(what, app, script, names=None):
    """Every array of the application's field data equals the script's of the same name."""
    app_names = [app.GetArrayName(i) for i in range(app.GetNumberOfArrays())]
    script_names = [script.GetArrayName(i) for i in range(script.GetNumberOfArrays())]
    if names is None:
        check(sorted(app_names) == sorted(script_names),
              f"{what}: the application has {app_names}, the script {script_names}")
        names = app_names
    for name in names:
        a = values(app.GetAbstractArray(name))
        b = values(script.GetAbstractArray(name))
        ok = same(a, b)
        detail = ""
        if not ok and a is not None and b is not None and a.shape == b.shape:
            detail = f" ({int(np.sum(~((a == b) | (a != a) & (b != b))))} values differ)"
        check(ok, f"{what}: array {name} differs between the application and the script{detail}")


def read_table(name):
    reader = vtkXMLTableReader()
    reader.SetFileName(os.path.join(output, name))
    reader.Update()
    return reader.GetOutput()


# The log as h5py reads it, before any VTK reader opens it (they keep the file open with
# other HDF5 locking flags).
with h5py.File(log, "r") as h5:
    names = sorted(h5["snapshots"].keys())
    h5_log = {"last": names[-1],
              "position": h5["snapshots"][names[-1]]["position"][()],
              "id": h5["snapshots"][names[-1]]["id"][()]}
    for dataset in ("metrics/psnr", "metrics/test/psnr", "metrics/ssim", "metrics/iteration"):
        h5_log[dataset] = h5[dataset][()]
    h5_log["plots"] = 1 + sum(
        int(np.any(np.isfinite(h5[f"metrics/{test}{m}"][()])))
        for test in ("", "test/") for m in ("psnr", "ssim", "lpips"))
    # Every snapshot's ids and the parameters the timeline's history draws, for the
    # selection history below (the demo log is small: a few MB in all).
    h5_log["snapshots"] = {
        int(h5["snapshots"][name].attrs["iteration"]): {
            key: h5["snapshots"][name][key][()]
            for key in ("id", "position", "log_scale", "opacity_logit")}
        for name in names}
    kinds = h5["events/kind"][()]
    births = int(np.sum((kinds == 1) | (kinds == 2)))
    h5_log["vertices"] = 1 + h5["snapshots"][names[0]]["id"].shape[0] + births

# The application's inputs.
shutil.rmtree(output, ignore_errors=True)
run = subprocess.run([program, "view", log, f"--dump-inputs={output}"],
                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
if run.returncode != 0:
    print(run.stdout)
    print(f"FAILED: vis4gs view --dump-inputs exited with {run.returncode}")
    sys.exit(1)
for name in ("scene.vtp", "metrics.vtt", "tree-vertices.vtt", "tree-edges.vtt", "bands.vtt",
             "history.vtt"):
    check(os.path.isfile(os.path.join(output, name)), f"--dump-inputs wrote no {name}")
if failures:
    print("FAILED: " + "; ".join(failures))
    sys.exit(1)
scene_reader = vtkXMLPolyDataReader()
scene_reader.SetFileName(os.path.join(output, "scene.vtp"))
scene_reader.Update()
app_scene = scene_reader.GetOutput()

# The script: the pipeline a user builds, and the four views fed from it.
reader = vis4gs.vtkGaussianTrainingLogReader()
reader.SetFileName(log)
scores = vis4gs.vtkGaussianArtifactScoreFilter()
scores.SetInputConnection(reader.GetOutputPort(0))
scores.SetCamerasConnection(reader.GetOutputPort(1))
# The application computes every registered score its inputs allow; the demo log has cameras
# and images, so all of them.
scores.SetScores(",".join(vis4gs.SCORES))
genealogy = vis4gs.vtkGaussianGenealogyTreeFilter()
genealogy.SetInputConnection(reader.GetOutputPort(3))
genealogy.SetRepairUnknownParents(True)
scores.Update()
genealogy.Update()
reader.Update(2)
script_scene = scores.GetOutput()
tree = genealogy.GetOutput()
bands = genealogy.GetFamilyBands()
metrics = reader.GetMetricsOutput()

tree_view = vis4gs.vtkGaussianTreeView()
tree_view.SetTree(tree)
tree_view.SetFamilyBands(bands)
timeline = vis4gs.vtkGaussianTimelineView()
timeline.SetMetrics(metrics)
timeline.UpdatePlots()
# Train and test PSNR, SSIM, LPIPS (those the log measured) and the count: the reader's
# merged table plugs in as is.
check(timeline.GetNumberOfMetricPlots() == h5_log["plots"],
      f"the timeline draws {timeline.GetNumberOfMetricPlots()} metric plots from the log "
      f"reader's metrics port, expected {h5_log['plots']} (the measured train and test PSNR, "
      "SSIM, LPIPS; Gaussians)")
check(tree_view.GetTree() is tree, "the tree view holds the genealogy filter's output")

# Scene (the splat mapper's and the selector's input): points and every point-data array.
check(same(vtk_to_numpy(app_scene.GetPoints().GetData()),
           vtk_to_numpy(script_scene.GetPoints().GetData())), "scene: positions differ")
compare_fields("scene", app_scene.GetPointData(), script_scene.GetPointData())
for score in vis4gs.SCORES.values():
    a = values(app_scene.GetPointData().GetArray(score))
    check(a is not None and np.count_nonzero(np.nan_to_num(a)) > 0.5 * a.size,
          f"scene: the application's {score} is computed (mostly non-zero)")

# Histograms of the same arrays from both inputs: the same bins.
for score in ("BlurScore", "ViewCoverage", "Opacity"):
    counts = []
    for data in (app_scene, script_scene):
        view = vis4gs.vtkGaussianHistogramView()
        view.SetInputData(data)
        view.SetArrayName(score)
        view.UpdateHistogram()
        counts.append([view.GetBinCount(b) for b in range(view.GetNumberOfBins())])
    check(counts[0] == counts[1] and sum(counts[0]) == app_scene.GetNumberOfPoints(),
          f"histogram of {score}: the application's bins {counts[0]} vs the script's {counts[1]}")

# Tree (view B): vertex data, parents, edge data, family bands.
app_vertices = read_table("tree-vertices.vtt")
compare_fields("tree vertices", app_vertices.GetRowData(), tree.GetVertexData(),
               [n for n in (app_vertices.GetColumnName(i)
                            for i in range(app_vertices.GetNumberOfColumns()))
                if n != "ParentVertex"])
check(app_vertices.GetNumberOfRows() == tree.GetNumberOfVertices(),
      "tree: the same number of vertices")
parents = np.array([tree.GetParent(v) for v in range(tree.GetNumberOfVertices())])
check(same(values(app_vertices.GetColumnByName("ParentVertex")), parents),
      "tree: the same parent of every vertex")
compare_fields("tree edges", read_table("tree-edges.vtt").GetRowData(), tree.GetEdgeData())
compare_fields("family bands", read_table("bands.vtt").GetRowData(), bands.GetRowData())

# Metrics (view D): one table, the reader's column names.
app_metrics = read_table("metrics.vtt")
compare_fields("metrics", app_metrics.GetRowData(), metrics.GetRowData())
check(not os.path.exists(os.path.join(output, "test-metrics.vtt")),
      "the application has no separate test-metrics table (its metrics hold TestPSNR...)")

# History (view D's bottom chart): the application's table for its selection (16 Gaussians
# of the scene at rows k * n / 16) is the reader's GetPropertyHistory, column for column, and
# the timeline draws the same lines from either.
app_history = read_table("history.vtt")
n = app_scene.GetNumberOfPoints()
scene_ids = values(app_scene.GetPointData().GetArray("GaussianId"))
selection = [int(scene_ids[k * n // 16]) for k in range(min(16, n))]
history_ids = values(app_history.GetColumnByName("GaussianId"))
check(history_ids is not None and sorted(set(history_ids.tolist())) == sorted(selection),
      f"history: the application's table holds the ids {sorted(set(history_ids.tolist())) if history_ids is not None else None}, "
      f"expected its selection {sorted(selection)}")
id_array = vtkIdTypeArray()
for gid in selection:
    id_array.InsertNextValue(gid)
script_history = vtkTable()
check(reader.GetPropertyHistory(id_array, script_history) == 1,
      "the script's reader gives the selection's history")
compare_fields("history", app_history.GetRowData(), script_history.GetRowData())

# The session (vtkGaussianSession: the pipeline object of the Python layer, the ParaView plugin
# and vis4gs analyze's reading) on the same file, the selection on its input: every port holds
# the application's arrays.
session = vis4gs.vtkGaussianSession()
session.SetFileName(log)
session.GetGenealogyFilter().SetRepairUnknownParents(True)
session.GetScoreFilter().SetScores(",".join(vis4gs.SCORES))  # every score, as the application
session.SetSelectedIds(id_array)
for port in range(session.NumberOfPorts):
    if port < session.RemovalViewsPort:  # (the removal effect is the clean-up's, not a view's)
        check(session.Update(port, None) == 1, f"the session's port {port} updates")
session_scene = session.GetGaussiansOutput()
check(same(vtk_to_numpy(app_scene.GetPoints().GetData()),
           vtk_to_numpy(session_scene.GetPoints().GetData())), "session: the same points")
compare_fields("session scene", app_scene.GetPointData(), session_scene.GetPointData())
compare_fields("session metrics", app_metrics.GetRowData(), session.GetMetricsOutput().GetRowData())
session_tree = session.GetOutputDataObject(session.TreePort)
compare_fields("session tree vertices", app_vertices.GetRowData(), session_tree.GetVertexData(),
               [n for n in (app_vertices.GetColumnName(i)
                            for i in range(app_vertices.GetNumberOfColumns()))
                if n != "ParentVertex"])
compare_fields("session family bands", read_table("bands.vtt").GetRowData(),
               session.GetOutputDataObject(session.BandsPort).GetRowData())
compare_fields("session history", app_history.GetRowData(),
               session.GetHistoryOutput().GetRowData())

# (No selection hub: a hub renders its views on a change, and this test has no display; the
# history holds the selection only, at most MaximumHistoryLines = 16 Gaussians.)
lines = []
for history in (app_history, script_history):
    view = vis4gs.vtkGaussianTimelineView()
    view.SetHistory(history)
    drawn = {}
    for prop, component in (("Opacity", -1), ("Scale", -1), ("Position", 1)):
        view.SetHistoryProperty(prop)
        view.SetHistoryComponent(component)
        view.UpdatePlots()
        table = view.GetHistoryLines()
        drawn[prop] = {table.GetColumnName(c): values(table.GetColumn(c))
                       for c in range(table.GetNumberOfColumns())}
    check(view.GetNumberOfHistoryLines() == len(selection),
          f"the timeline draws {view.GetNumberOfHistoryLines()} history lines, expected "
          f"{len(selection)}")
    lines.append(drawn)
for prop in ("Opacity", "Scale", "Position"):
    a, b = lines[0][prop], lines[1][prop]
    check(sorted(a) == sorted(b) and all(same(a[k], b[k]) for k in a),
          f"the timeline's {prop} lines differ between the application's history and the script's")
# Independently of VTK: the log as h5py reads it (read first, see above).
check(same(vtk_to_numpy(app_scene.GetPoints().GetData()), h5_log["position"]),
      f"scene: positions are those of the last snapshot ({h5_log['last']})")
check(same(values(app_scene.GetPointData().GetArray("GaussianId")), h5_log["id"]),
      "scene: GaussianId is the last snapshot's id")
for column, dataset in (("PSNR", "metrics/psnr"), ("TestPSNR", "metrics/test/psnr"),
                        ("SSIM", "metrics/ssim"), ("Iteration", "metrics/iteration")):
    check(same(values(app_metrics.GetColumnByName(column)), h5_log[dataset]),
          f"metrics: {column} is the log's {dataset}")
check(app_vertices.GetNumberOfRows() == h5_log["vertices"],
      f"tree: {app_vertices.GetNumberOfRows()} vertices, expected 1 + initial + births = "
      f"{h5_log['vertices']}")

# The selection's history against h5py: a row for every (Gaussian, snapshot holding it), the
# position, the opacity (sigmoid of the logit) and the largest scale (exp of the largest log
# scale), and the lines the timeline drew (Position by its Y component).
expected_rows = 0
for iteration, snap in h5_log["snapshots"].items():
    for gid in selection:
        rows = np.nonzero(snap["id"] == gid)[0]
        if rows.size == 0:
            continue
        expected_rows += 1
        r = rows[0]
        opacity = 1.0 / (1.0 + np.exp(-np.float64(snap["opacity_logit"][r])))
        scale = np.exp(np.float64(np.max(snap["log_scale"][r])))
        column = f"Gaussian {gid}"
        at = np.nonzero(lines[0]["Opacity"]["Iteration"] == iteration)[0]
        ok = at.size == 1 and column in lines[0]["Opacity"]
        check(ok, f"history: the timeline has no point of Gaussian {gid} at iteration {iteration}")
        if not ok:
            continue
        k = at[0]
        check(abs(lines[0]["Opacity"][column][k] - opacity) <= 1e-6 and
              abs(lines[0]["Scale"][column][k] - scale) <= 1e-6 * max(1.0, scale) and
              lines[0]["Position"][column][k] == np.float64(snap["position"][r][1]),
              f"history: Gaussian {gid} at iteration {iteration}: the timeline draws opacity "
              f"{lines[0]['Opacity'][column][k]}, scale {lines[0]['Scale'][column][k]}, y "
              f"{lines[0]['Position'][column][k]}; h5py gives {opacity}, {scale}, "
              f"{snap['position'][r][1]}")
check(app_history.GetNumberOfRows() == expected_rows,
      f"history: {app_history.GetNumberOfRows()} rows, h5py finds the selection in "
      f"{expected_rows} (Gaussian, snapshot) pairs")

if failures:
    for f in failures:
        print("FAILED: " + f)
    sys.exit(1)
print(f"the application's view inputs equal the script's: {app_scene.GetNumberOfPoints()} "
      f"Gaussians with {app_scene.GetPointData().GetNumberOfArrays()} arrays, "
      f"{tree.GetNumberOfVertices()} tree vertices, {app_metrics.GetNumberOfRows()} metrics rows, "
      f"{app_history.GetNumberOfRows()} history rows of {len(selection)} selected Gaussians")

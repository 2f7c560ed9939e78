"""vtkGaussianSession from Python (issue 33): on the demo log, its Gaussians, metrics and tree
ports hold what the readers and filters connected by hand give, and its history port follows
the selection hub: the session's selection input is the hub's annotation link, so selecting
Gaussians in the hub changes the history the session gives, with no copying in between. The
history's values are checked against h5py's reading of the snapshots when h5py is present."""
import os

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkTable

import vis4gs

log = os.path.join(os.environ["VIS4GS_SOURCE_DIR"], "Data", "Demo", "vis4gs-demo.h5")
failures = []


def check(cond, what):
    print(("ok: " if cond else "FAILED: ") + what)
    if not cond:
        failures.append(what)


def columns(attributes):
    out = {}
    for i in range(attributes.GetNumberOfArrays()):
        array = attributes.GetAbstractArray(i)
        if array.IsA("vtkDataArray"):
            out[array.GetName()] = vtk_to_numpy(array)
    return out


def same(a, b, what):
    ca, cb = columns(a), columns(b)
    check(ca.keys() == cb.keys() and len(ca) > 0, f"{what}: the same arrays ({sorted(ca)})")
    for name in ca:
        if name in cb:
            check(np.array_equal(ca[name], cb[name], equal_nan=True), f"{what}: {name} equal")


try:
    import h5py
except ImportError:
    h5py = None
h5_snapshots = {}
if h5py is not None:
    with h5py.File(log, "r") as f:
        for name in f["snapshots"]:
            group = f["snapshots"][name]
            h5_snapshots[int(group.attrs["iteration"])] = (group["id"][()],
                                                           group["opacity_logit"][()])

session = vis4gs.vtkGaussianSession()
session.SetFileName(log)
# Coverage and shape: the blur and needle scores cost most of the time and go the same way.
session.GetScoreFilter().ComputeBlurScoreOff()
session.GetScoreFilter().ComputeNeedleScoreOff()
session.Update(session.GaussiansPort, None)
gaussians = session.GetGaussiansOutput()

reader = vis4gs.vtkGaussianTrainingLogReader()
reader.SetFileName(log)
scores = vis4gs.vtkGaussianArtifactScoreFilter()
scores.SetInputConnection(reader.GetOutputPort(0))
scores.SetCamerasConnection(reader.GetOutputPort(1))
scores.ComputeBlurScoreOff()
scores.ComputeNeedleScoreOff()
scores.Update()
same(scores.GetOutput().GetPointData(), gaussians.GetPointData(), "Gaussians")

session.Update(session.MetricsPort, None)
reader.Update(2)
same(reader.GetMetricsOutput().GetRowData(), session.GetMetricsOutput().GetRowData(), "metrics")

events = vis4gs.vtkGaussianTrainingLogReader()
events.SetFileName(log)
genealogy = vis4gs.vtkGaussianGenealogyTreeFilter()
genealogy.SetInputConnection(events.GetOutputPort(3))
genealogy.Update()
session.Update(session.TreePort, None)
same(genealogy.GetOutput().GetVertexData(),
     session.GetOutputDataObject(session.TreePort).GetVertexData(), "tree")

# The hub's selection feeds the session: port 2 of its annotation link is the current selection.
hub = vis4gs.vtkGaussianSelectionHub()
session.SetSelectionConnection(hub.GetAnnotationLink().GetOutputPort(2))
ids = vtk_to_numpy(gaussians.GetPointData().GetArray("GaussianId")).astype(np.int64)
for picked in (ids[[0, len(ids) // 2, len(ids) - 1]], ids[5:12]):
    hub.SelectIds(numpy_to_vtkIdTypeArray(np.ascontiguousarray(picked), deep=1))
    session.Update(session.HistoryPort, None)
    history = session.GetHistoryOutput()
    expected = vtkTable()
    reader.GetPropertyHistory(numpy_to_vtkIdTypeArray(np.sort(picked), deep=1), expected)
    check(history.GetNumberOfRows() == expected.GetNumberOfRows() > 0,
          f"history of {len(picked)} selected: {history.GetNumberOfRows()} rows")
    same(expected.GetRowData(), history.GetRowData(), f"history of {len(picked)} selected")
    got = set(vtk_to_numpy(history.GetRowData().GetArray("GaussianId")).tolist())
    check(got == set(picked.tolist()), "the history holds exactly the selected Gaussians")

if h5py is not None:
    # Independently: the opacity logits h5py reads (read before any VTK reader opened the log,
    # which HDF5's file locking needs), for the last selection.
    ok = True
    gid = vtk_to_numpy(history.GetRowData().GetArray("GaussianId"))
    rows = vtk_to_numpy(history.GetRowData().GetArray("Iteration"))
    logit = vtk_to_numpy(history.GetRowData().GetArray("OpacityLogit"))
    for it, (snap_ids, snap_logit) in h5_snapshots.items():
        for g in picked:
            hit = np.flatnonzero(snap_ids == g)
            mine = np.flatnonzero((rows == it) & (gid == g))
            if hit.size != mine.size or (hit.size and snap_logit[hit[0]] != logit[mine[0]]):
                ok = False
    check(ok, "the history's opacity logits are those h5py reads")

hub.ClearSelection()
session.Update(session.HistoryPort, None)
check(session.GetHistoryOutput().GetNumberOfRows() == 0, "no selection, no history")

if failures:
    raise SystemExit(f"{len(failures)} checks failed")

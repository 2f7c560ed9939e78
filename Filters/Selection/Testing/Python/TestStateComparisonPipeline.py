"""Comparing two states from Python (issue 20): the demo log read at iterations 400 and 1600
(two vtkGaussianTrainingLogReader outputs) into vtkGaussianStateComparisonFilter. Its table
equals a numpy computation over the readers' arrays (ids matched with np.intersect1d, float64
distances, strict thresholds); a scene against its cleaned copy (vtkGaussianRuleSelectionFilter,
Remove) shows exactly the removed ids as died and every other as unchanged."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

import vis4gs

log = os.path.join(os.environ["VIS4GS_SOURCE_DIR"], "Data", "Demo", "vis4gs-demo.h5")
failures = []


def check(cond, what):
    print(("ok: " if cond else "FAILED: ") + what)
    if not cond:
        failures.append(what)


def read(iteration):
    reader = vis4gs.vtkGaussianTrainingLogReader()
    reader.SetFileName(log)
    reader.SetIteration(iteration)
    reader.Update()
    return reader


def arrays(reader):
    pd = reader.GetOutputDataObject(0)
    p = pd.GetPointData()
    return (vtk_to_numpy(p.GetArray("GaussianId")).astype(np.int64),
            vtk_to_numpy(pd.GetPoints().GetData()).astype(np.float64),
            vtk_to_numpy(p.GetArray("OpacityLogit")).astype(np.float64),
            vtk_to_numpy(p.GetArray("LogScale")).astype(np.float64))


ra, rb = read(400), read(1600)
ida, pa, oa, sa = arrays(ra)
idb, pb, ob, sb = arrays(rb)
common, ia, ib = np.intersect1d(ida, idb, return_indices=True)
move = np.linalg.norm(pb[ib] - pa[ia], axis=1)
sig = lambda x: 1.0 / (1.0 + np.exp(-x))
opacity = sig(ob[ib]) - sig(oa[ia])
ds = sb[ib] - sa[ia]
scale = ds[np.arange(len(ds)), np.argmax(np.abs(ds), axis=1)]

compare = vis4gs.vtkGaussianStateComparisonFilter()
compare.SetInputConnection(0, ra.GetOutputPort(0))
compare.SetSecondStateConnection(rb.GetOutputPort(0))
thresholds = (0.01, 0.05, 0.1)
compare.SetMoveThreshold(thresholds[0])
compare.SetOpacityThreshold(thresholds[1])
compare.SetScaleThreshold(thresholds[2])
compare.Update()
table = compare.GetOutput()
ids = vtk_to_numpy(table.GetColumnByName("GaussianId")).astype(np.int64)
status = np.array([table.GetColumnByName("Status").GetValue(i)
                   for i in range(table.GetNumberOfRows())])
check(np.array_equal(ids, np.union1d(ida, idb)), f"{ids.size} rows: every id of either state")
born, died = np.setdiff1d(idb, ida), np.setdiff1d(ida, idb)
check(np.array_equal(ids[status == "born"], born) and np.array_equal(ids[status == "died"], died),
      f"born {born.size} and died {died.size} as numpy")
check(compare.GetNumberBorn() == born.size and compare.GetNumberDied() == died.size and
      compare.GetNumberMatched() == common.size, "the counts")
rows = np.searchsorted(ids, common)
for name, mine, t, flag in (("Move", move, thresholds[0], 1),
                            ("OpacityChange", opacity, thresholds[1], 2),
                            ("ScaleChange", scale, thresholds[2], 4)):
    got = vtk_to_numpy(table.GetColumnByName(name))[rows]
    check(np.allclose(got, mine, rtol=1e-6, atol=1e-12), f"{name} agrees with numpy")
    flags = vtk_to_numpy(table.GetColumnByName("Change"))[rows]
    check(np.array_equal((flags & flag) != 0, np.abs(mine) > t),
          f"{name} beyond {t}: {int((np.abs(mine) > t).sum())} Gaussians, as numpy")
unchanged = (move <= thresholds[0]) & (np.abs(opacity) <= thresholds[1]) & \
    (np.abs(scale) <= thresholds[2])
check(compare.GetNumberUnchanged() == unchanged.sum(),
      f"{unchanged.sum()} unchanged under the thresholds")

# A scene against its cleaned copy: the removed ids died, the others are unchanged.
rule = vis4gs.vtkGaussianRuleSelectionFilter()
rule.SetInputConnection(rb.GetOutputPort(0))
rule.SetRule("opacity<0.1")
rule.SetOutputMode(rule.Remove)
rule.Update()
removed = vtk_to_numpy(rule.GetSelectedIds()).astype(np.int64)
compare.SetInputConnection(0, rb.GetOutputPort(0))
compare.SetSecondStateConnection(rule.GetOutputPort())
compare.SetMoveThreshold(0)
compare.SetOpacityThreshold(0)
compare.SetScaleThreshold(0)
compare.Update()
table = compare.GetOutput()
ids = vtk_to_numpy(table.GetColumnByName("GaussianId")).astype(np.int64)
status = np.array([table.GetColumnByName("Status").GetValue(i)
                   for i in range(table.GetNumberOfRows())])
check(removed.size > 0 and np.array_equal(ids[status == "died"], removed),
      f"the {removed.size} removed ids died")
check(np.all(status[status != "died"] == "unchanged") and compare.GetNumberBorn() == 0,
      f"the other {int((status != 'died').sum())} are unchanged")

if failures:
    sys.exit(1)

"""The paper's case study as a VTK Python pipeline: a floater traced to its weakly covered
ancestors, with the same classes the application uses and nothing else.

  build/bin/vis4gs-python Documentation/examples/case_study.py [LOG.h5] [--min-opacity=0.1]
      [--compare=root-cause.txt]

1. The training-log reader gives each snapshot's Gaussians and the cameras; the score filter
   gives their View Coverage (no images needed).
2. The floater: the visible Gaussian (opacity >= min-opacity) of the last snapshot that the
   fewest training views see (coverage > 0).
3. The reader's events port gives the genealogy tree; the lineage object traces the floater
   to its root with each ancestor's coverage at the snapshot nearest its birth.
It prints the trace in the format of `vis4gs demo`'s root-cause.txt; with --compare=FILE it
checks that the trace is that file's, line for line (CTest runs it so).
"""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdTypeArray, vtkObject
from vtkmodules.vtkCommonDataModel import vtkTable

import vis4gs

# The score filter's warnings (Gaussians seen by no view, per snapshot) also travel in its
# output's field data (ScoreWarnings); the console need not repeat them here.
vtkObject.GlobalWarningDisplayOff()

args = [a for a in sys.argv[1:] if not a.startswith("--")]
options = dict(a[2:].split("=", 1) for a in sys.argv[1:] if a.startswith("--") and "=" in a)
log = args[0] if args else os.path.join(os.path.dirname(__file__), "..", "..", "Data", "Demo",
                                        "vis4gs-demo.h5")
min_opacity = float(options.get("min-opacity", 0.1))

reader = vis4gs.vtkGaussianTrainingLogReader()
reader.SetFileName(log)
reader.UpdateInformation()
snapshots = [reader.GetSnapshotIteration(i) for i in range(reader.GetNumberOfSnapshots())]

coverage_filter = vis4gs.vtkGaussianArtifactScoreFilter()
coverage_filter.SetInputConnection(reader.GetOutputPort(0))
coverage_filter.SetCamerasConnection(reader.GetOutputPort(1))
coverage_filter.SetComputeBlurScore(False)
coverage_filter.SetComputeNeedleScore(False)
coverage_filter.SetComputeNeedleShape(False)

lineage = vis4gs.vtkGaussianGenealogyLineage()
coverage = {}
for iteration in snapshots:
    reader.SetIteration(iteration)
    coverage_filter.Update()
    out = coverage_filter.GetOutput()
    ids = vtk_to_numpy(out.GetPointData().GetPedigreeIds()).copy()
    values = vtk_to_numpy(out.GetPointData().GetArray("ViewCoverage")).copy()
    coverage[iteration] = (ids, values)
    id_array = vtkIdTypeArray()
    id_array.SetNumberOfTuples(len(ids))
    for i, v in enumerate(ids):
        id_array.SetValue(i, int(v))
    lineage.AddSnapshotValues(iteration, id_array, numpy_to_vtk(values, deep=1))

# The floater, in the last snapshot (the filter's output still holds it).
ids, values = coverage[snapshots[-1]]
opacity = vtk_to_numpy(out.GetPointData().GetArray("Opacity"))
candidates = np.flatnonzero((opacity >= min_opacity) & (values > 0))
floater_row = candidates[np.argmin(values[candidates])]  # first of the lowest, as the demo
floater, best = int(ids[floater_row]), float(values[floater_row])
cameras = reader.GetOutputDataObject(1)
split = cameras.GetColumnByName("Split")
train_views = sum(1 for r in range(cameras.GetNumberOfRows()) if split.GetValue(r) == 0)

tree_filter = vis4gs.vtkGaussianGenealogyTreeFilter()
tree_filter.SetInputConnection(reader.GetOutputPort(3))
tree_filter.Update()
lineage.SetTree(tree_filter.GetOutput())
trace = vtkTable()
if not lineage.TraceToRoot(floater, trace):
    sys.exit(f"FAILED: no trace for Gaussian {floater}")

kinds = {0: "root", 1: "clone", 2: "split", 3: "clone-split"}
lines = [f"Root-cause trace of Gaussian {floater}, a visible floater (View Coverage {best:g} = "
         f"{round(best * train_views)} of {train_views} training views; lowest among Gaussians "
         f"with opacity >= {min_opacity:g} at iteration {snapshots[-1]}):",
         "  GaussianId  born   kind         died   coverage at snapshot"]
col = {trace.GetColumnName(c): trace.GetColumn(c) for c in range(trace.GetNumberOfColumns())}
for r in range(trace.GetNumberOfRows()):
    death = col["DeathIteration"].GetValue(r)
    snapshot = col["SnapshotIteration"].GetValue(r)
    where = ("(in no snapshot)" if snapshot < 0 else
             f"{col['Value'].GetValue(r):.3f} at {snapshot}")
    lines.append(f"  {col['GaussianId'].GetValue(r):>10}  {col['BirthIteration'].GetValue(r):>5}"
                 f"  {kinds[col['BirthKind'].GetValue(r)]:<11}  "
                 f"{'alive' if death < 0 else str(death):>5}  {where}")
print("\n".join(lines))

if "compare" in options:
    with open(options["compare"]) as f:
        expected = f.read().rstrip("\n").split("\n")
    if expected != lines:
        print("FAILED: the trace differs from", options["compare"])
        for a, b in zip(expected + [""] * len(lines), lines + [""] * len(expected)):
            if a != b:
                print(f"  expected: {a}\n  got:      {b}")
        sys.exit(1)
    print(f"the same trace as {options['compare']}")

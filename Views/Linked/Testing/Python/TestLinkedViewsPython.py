"""Builds the linked views from `import vis4gs` and checks that a selection reaches them."""
import sys

import vis4gs
import vtkmodules.vtkRenderingContextOpenGL2  # noqa: F401  (context views need its device)
from vtkmodules.vtkCommonCore import vtkIdTypeArray
from vtkmodules.vtkCommonDataModel import vtkMutableDirectedGraph, vtkTree, vtkTable
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray


def fail(msg):
    print("FAILED: " + msg)
    sys.exit(1)


def make_tree():
    # virtual root, then 0 -clone-> 1 -split-> 2, 3 and a second root 4.
    rows = [(-1, -1, 0, -1, 0, -1, -1.0), (0, 0, 0, -1, 0, 0, 1.0), (1, 1, 500, 900, 1, 1, 0.5),
            (2, 2, 900, -1, 2, 2, 0.4), (3, 2, 900, -1, 2, 3, 0.4), (4, 0, 0, -1, 0, 4, 1.0)]
    g = vtkMutableDirectedGraph()
    arrays = {}
    for name, cls in (("GaussianId", vtkIdTypeArray), ("LayoutX", vtkIntArray),
                      ("DeathIteration", vtkIntArray), ("BirthKind", vtkIntArray),
                      ("LayoutY", vtkDoubleArray), ("PerceptionValue", vtkDoubleArray)):
        arrays[name] = cls()
        arrays[name].SetName(name)
    for gid, parent, birth, death, kind, row, p in rows:
        if parent < 0:
            g.AddVertex()
        else:
            g.AddChild(parent)
        arrays["GaussianId"].InsertNextValue(gid)
        arrays["LayoutX"].InsertNextValue(birth)
        arrays["DeathIteration"].InsertNextValue(death)
        arrays["BirthKind"].InsertNextValue(kind)
        arrays["LayoutY"].InsertNextValue(row)
        arrays["PerceptionValue"].InsertNextValue(p)
    for name, a in arrays.items():
        if name == "GaussianId":
            g.GetVertexData().SetPedigreeIds(a)
        else:
            g.GetVertexData().AddArray(a)
    tree = vtkTree()
    if not tree.CheckedShallowCopy(g):
        fail("not a tree")
    return tree


hub = vis4gs.vtkGaussianSelectionHub()
hub.RenderOnChangeOff()
tree_view = vis4gs.vtkGaussianTreeView()
tree_view.SetTree(make_tree())
tree_view.SetSelectionHub(hub)

metrics = vtkTable()
it, psnr = vtkIntArray(), vtkDoubleArray()
it.SetName("Iteration")
psnr.SetName("PSNR")
for k in range(5):
    it.InsertNextValue(250 * k)
    psnr.InsertNextValue(20.0 + k)
metrics.AddColumn(it)
metrics.AddColumn(psnr)
timeline = vis4gs.vtkGaussianTimelineView()
timeline.SetMetrics(metrics)
timeline.SetSelectionHub(hub)

ids = vtkIdTypeArray()
ids.InsertNextValue(2)
hub.SelectIds(ids)

item = tree_view.GetTreeItem()
item.UpdateLevelOfDetail()
lineage = vtkIdTypeArray()
item.GetLineageVertices(lineage)
got = sorted(lineage.GetValue(i) for i in range(lineage.GetNumberOfTuples()))
# GaussianId 2 is vertex 3; its ancestors are vertices 2 and 1.
if got != [1, 2, 3]:
    fail("lineage of Gaussian 2 should be vertices [1, 2, 3], got %s" % got)
if timeline.GetNumberOfMetricPlots() != 1:
    fail("one metric plot expected (psnr), got %d" % timeline.GetNumberOfMetricPlots())
hub.SetIteration(480)
if timeline.GetIteration() != 480:
    fail("the timeline cursor did not follow the hub")
if timeline.SnapIteration(480) != 500:
    fail("snap to the nearest logged iteration")
# A second run (issue 20): its PSNR beside the first's, both named in the legend.
timeline.SetRunName("A: run 1")
timeline.SetComparisonRunName("B: run 2")
timeline.SetComparisonMetrics(metrics)
timeline.SetComparisonIteration(750)
quality = timeline.GetChart(vis4gs.vtkGaussianTimelineView.QUALITY)
labels = sorted(quality.GetPlot(k).GetLabel() for k in range(quality.GetNumberOfPlots()))
if timeline.GetNumberOfComparisonPlots() != 1 or labels != ["PSNR [A: run 1]", "PSNR [B: run 2]"]:
    fail("the second run's PSNR should be named beside the first's, got %s" % labels)
if quality.GetComparisonCursorIteration() != 750:
    fail("the second cursor should be at 750")
print("linked views from Python: OK")

"""Linked views from a VTK Python script: genealogy tree (view B), timeline (view D) and an
attribute histogram, all linked through one vtkGaussianSelectionHub.

Usage (build tree):  build/bin/vis4gs-python Documentation/examples/linked_views.py LOG.h5
Without a log argument it builds a tiny hand-made genealogy so that it runs anywhere (that
path is what was run and checked). The LOG.h5 path assumes the IO/TrainingLog reader's class
name and port order (events on port 3) and had not been run when this example was written.
Close each window to go on.
"""
import sys

import vis4gs
import vtkmodules.vtkRenderingContextOpenGL2  # noqa: F401  (the context views' device)
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIdTypeArray, vtkIntArray
from vtkmodules.vtkCommonDataModel import vtkMutableDirectedGraph, vtkTable, vtkTree


def tiny_tree():
    """virtual root; Gaussian 0 clones 1 at 500, 1 splits into 2 and 3 at 900."""
    g = vtkMutableDirectedGraph()
    cols = {n: c() for n, c in (("GaussianId", vtkIdTypeArray), ("LayoutX", vtkIntArray),
                                ("DeathIteration", vtkIntArray), ("BirthKind", vtkIntArray),
                                ("LayoutY", vtkDoubleArray), ("PerceptionValue", vtkDoubleArray))}
    for name, a in cols.items():
        a.SetName(name)
    for gid, parent, birth, death, kind, row, p in [(-1, -1, 0, -1, 255, -1, -1), (0, 0, 0, -1, 0, 0, 1),
                                                    (1, 1, 500, 900, 1, 1, .5), (2, 2, 900, -1, 2, 2, .4),
                                                    (3, 2, 900, -1, 2, 3, .4)]:
        g.AddVertex() if parent < 0 else g.AddChild(parent)
        for name, v in zip(cols, (gid, birth, death, kind, row, p)):
            cols[name].InsertNextValue(v)
    for name, a in cols.items():
        (g.GetVertexData().SetPedigreeIds if name == "GaussianId" else g.GetVertexData().AddArray)(a)
    tree = vtkTree()
    tree.CheckedShallowCopy(g)
    return tree, None


def log_tree(path):
    """Genealogy of a training log through the Filters/Genealogy and IO/TrainingLog modules."""
    reader = vis4gs.vtkGaussianTrainingLogReader()
    reader.SetFileName(path)
    reader.Update()
    genealogy = vis4gs.vtkGaussianGenealogyTreeFilter()
    genealogy.SetInputConnection(reader.GetOutputPort(3))  # events table
    genealogy.Update()
    return genealogy.GetOutput(), genealogy.GetFamilyBands()


files = [a for a in sys.argv[1:] if not a.startswith("--")]
tree, bands = log_tree(files[0]) if files else tiny_tree()

hub = vis4gs.vtkGaussianSelectionHub()
tree_view = vis4gs.vtkGaussianTreeView()
tree_view.SetTree(tree)
if bands is not None:
    tree_view.SetFamilyBands(bands)
tree_view.SetSelectionHub(hub)
tree_view.GetRenderWindow().SetSize(800, 400)

metrics = vtkTable()
it, psnr = vtkIntArray(), vtkDoubleArray()
it.SetName("iteration")
psnr.SetName("psnr")
for k in range(7):
    it.InsertNextValue(500 * k)
    psnr.InsertNextValue(20 + 2 * k ** 0.5)
metrics.AddColumn(it)
metrics.AddColumn(psnr)
timeline = vis4gs.vtkGaussianTimelineView()
timeline.SetMetrics(metrics)
timeline.SetSelectionHub(hub)
timeline.GetRenderWindow().SetSize(800, 400)

# Select Gaussian 2 as the scene view would: the tree highlights its lineage 0 -> 1 -> 2.
ids = vtkIdTypeArray()
ids.InsertNextValue(2)
hub.SelectIds(ids)
hub.SetIteration(1000)  # moves the cursor of every view
print("selected:", hub.GetNumberOfSelectedIds(), "Gaussian(s)")

for view in (tree_view, timeline):
    view.Render()
    if "--no-interaction" not in sys.argv:
        view.GetInteractor().Start()

"""Linked views from a VTK Python script: genealogy tree (view B), timeline (view D) and an
attribute histogram, all linked through one vtkGaussianSelectionHub.

Usage (build tree):  build/bin/vis4gs-python Documentation/examples/linked_views.py [LOG.h5]
With a log (e.g. Data/Demo/vis4gs-demo.h5) the tree and the metrics come straight from the
training-log reader's ports (events on port 3, metrics on port 2), with nothing set by hand;
without one, a tiny hand-made genealogy and metrics table. Close each window to go on;
`--no-interaction` renders once and exits (CTest runs both forms this way).
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
    metrics = vtkTable()
    it, psnr = vtkIntArray(), vtkDoubleArray()
    it.SetName("Iteration")
    psnr.SetName("PSNR")
    for k in range(7):
        it.InsertNextValue(500 * k)
        psnr.InsertNextValue(20 + 2 * k ** 0.5)
    metrics.AddColumn(it)
    metrics.AddColumn(psnr)
    return tree, None, metrics


def log_tree(path):
    """Genealogy of a training log through the Filters/Genealogy and IO/TrainingLog modules."""
    reader = vis4gs.vtkGaussianTrainingLogReader()
    reader.SetFileName(path)
    reader.Update()
    genealogy = vis4gs.vtkGaussianGenealogyTreeFilter()
    genealogy.SetInputConnection(reader.GetOutputPort(3))  # events table
    genealogy.Update()
    reader.Update(2)  # the metrics port (each port is read only when asked for)
    return genealogy.GetOutput(), genealogy.GetFamilyBands(), reader.GetOutputDataObject(2)


files = [a for a in sys.argv[1:] if not a.startswith("--")]
tree, bands, metrics = log_tree(files[0]) if files else tiny_tree()

hub = vis4gs.vtkGaussianSelectionHub()
tree_view = vis4gs.vtkGaussianTreeView()
tree_view.SetTree(tree)
if bands is not None:
    tree_view.SetFamilyBands(bands)
tree_view.SetSelectionHub(hub)
tree_view.GetRenderWindow().SetSize(800, 400)

timeline = vis4gs.vtkGaussianTimelineView()
timeline.SetMetrics(metrics)
timeline.SetSelectionHub(hub)
timeline.GetRenderWindow().SetSize(800, 400)

# Select a Gaussian as the scene view would: the tree highlights its lineage (in the tiny
# tree, 3: 0 -> 1 -> 3; in a log, the last Gaussian born).
pedigree = tree.GetVertexData().GetPedigreeIds()
chosen = pedigree.GetValue(tree.GetNumberOfVertices() - 1)
ids = vtkIdTypeArray()
ids.InsertNextValue(chosen)
hub.SelectIds(ids)
hub.SetIteration(1000)  # moves the cursor of every view
print(f"tree: {tree.GetNumberOfVertices()} vertices; metrics: {metrics.GetNumberOfRows()} rows;",
      f"selected: {hub.GetNumberOfSelectedIds()} Gaussian(s), id {chosen}")

for view in (tree_view, timeline):
    view.Render()
    if "--no-interaction" not in sys.argv:
        view.GetInteractor().Start()

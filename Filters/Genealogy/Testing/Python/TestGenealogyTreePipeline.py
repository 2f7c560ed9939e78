"""A Python pipeline from `vis4gs`: events table -> genealogy vtkTree -> level of detail,
plus lineage queries, on the hand-computed log of Core/Genealogy/Testing/TestGenealogy.cxx."""
import math
import sys

from vtkmodules.vtkCommonCore import vtkIdTypeArray, vtkIntArray, vtkUnsignedCharArray
from vtkmodules.vtkCommonDataModel import vtkTable

import vis4gs

EVENTS = [  # iteration, kind (1 clone, 2 split, 3 prune), parent, child
    (100, 1, 0, 2), (200, 2, 0, 3), (200, 2, 0, 4), (300, 1, 3, 5),
    (400, 3, 4, -1), (500, 3, 1, -1), (600, 2, 5, 6), (600, 2, 5, 7)]

table = vtkTable()
columns = [("Iteration", vtkIntArray()), ("Kind", vtkUnsignedCharArray()),
           ("Parent", vtkIdTypeArray()), ("Child", vtkIdTypeArray())]
for c, (name, array) in enumerate(columns):
    array.SetName(name)
    for row in EVENTS:
        array.InsertNextValue(row[c])
    table.AddColumn(array)

tree_filter = vis4gs.vtkGaussianGenealogyTreeFilter()
tree_filter.SetInputData(table)
tree_filter.SetNumberOfInitialGaussians(2)
tree_filter.SetLastIteration(1000)
tree_filter.Update()
tree = tree_filter.GetOutput()

failures = []
def check(cond, what):
    if not cond:
        failures.append(what)

check(tree.GetNumberOfVertices() == 9, "9 vertices")
p = tree.GetVertexData().GetArray("PerceptionValue")
rows = tree.GetVertexData().GetArray("LayoutY")
expected_p = [0.4 + 0.6 * 200 / 900, 0.6, 0.6, 0.2 + 0.6 * 800 / 900, 0.6 * 200 / 900,
              0.4 * 2 / 6 + 0.6 * 300 / 900, 0.6 * 400 / 900, 0.6 * 400 / 900]
for i, e in enumerate(expected_p):
    check(math.isclose(p.GetValue(i + 1), e, abs_tol=1e-15), f"P of node {i}")
check([int(rows.GetValue(i + 1)) for i in range(8)] == [0, 7, 1, 2, 6, 3, 4, 5], "rows")
check(tree_filter.GetFamilyBands().GetNumberOfRows() == 2, "two families")

lod = vis4gs.vtkGaussianTreeLevelOfDetail()
lod.SetInputConnection(tree_filter.GetOutputPort())
selected = vtkIdTypeArray()
selected.InsertNextValue(6)
lod.SetSelectedGaussianIds(selected)
lod.SetZoom(0.1)  # tau = 1: only the lineage of 6 (0, 3, 5, 6)
lod.Update()
visible = lod.GetVisibleSelection().GetNode(0).GetSelectionList()
check([visible.GetValue(k) for k in range(visible.GetNumberOfTuples())] == [1, 4, 6, 7],
      "lineage of 6 at the coarsest zoom")
check(lod.GetOutput().GetNumberOfVertices() == 5, "visible subtree: root + 4")
lod.SetSelectedGaussianIds(None)
lod.SetZoom(2.0)  # tau = 0: everything
lod.Update()
check(lod.GetNumberOfVisibleVertices() == 8, "all nodes at the finest zoom")
check(lod.GetIndexSeconds() == 0.0, "index cached")

lineage = vis4gs.vtkGaussianGenealogyLineage()
lineage.SetTree(tree)
result = vtkIdTypeArray()
query = vtkIdTypeArray()
query.InsertNextValue(3)
lineage.GetDescendants(query, result)
check([result.GetValue(k) for k in range(result.GetNumberOfTuples())] == [5, 6, 7],
      "descendants of 3")
trace = vtkTable()
check(lineage.TraceToRoot(7, trace), "trace")
check([trace.GetValueByName(r, "GaussianId").ToInt() for r in range(trace.GetNumberOfRows())]
      == [7, 5, 3, 0], "trace chain")

# The compact output (CompactTree): same structure through vtkTree's accessors, same lineage.
compact_filter = vis4gs.vtkGaussianGenealogyTreeFilter()
compact_filter.SetInputData(table)
compact_filter.SetNumberOfInitialGaussians(2)
compact_filter.SetLastIteration(1000)
compact_filter.CompactTreeOn()
compact_filter.Update()
compact = compact_filter.GetOutput()
check(compact.IsA("vtkGaussianCompactTree"), "compact output type")
check(not tree.IsA("vtkGaussianCompactTree"), "plain output by default")
# Parents by hand: nodes 2, 3, 4 of node 0; 5 of 3; 6, 7 of 5 (vertex = node + 1).
check([compact.GetParent(v) for v in range(1, 9)] == [0, 0, 1, 1, 1, 4, 6, 6], "compact parents")
check([tree.GetParent(v) for v in range(1, 9)] == [0, 0, 1, 1, 1, 4, 6, 6], "parents")
check([[compact.GetChild(v, c) for c in range(compact.GetNumberOfChildren(v))] for v in range(9)]
      == [[tree.GetChild(v, c) for c in range(tree.GetNumberOfChildren(v))] for v in range(9)],
      "compact children")
compact_lineage = vis4gs.vtkGaussianGenealogyLineage()
compact_lineage.SetTree(compact)
result.Initialize()
compact_lineage.GetDescendants(query, result)
check([result.GetValue(k) for k in range(result.GetNumberOfTuples())] == [5, 6, 7],
      "descendants of 3 in the compact tree")

if failures:
    print("FAILED:", "; ".join(failures))
sys.exit(1 if failures else 0)

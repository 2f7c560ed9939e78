"""A log with lineage breaks (the Python logger's /lineage_breaks) through the obvious
pipeline: the training-log reader's events port, with the breaks in its field data, into the
genealogy filter. The new roots of each break are roots of the tree marked LineageBreakRoot,
born at the break; a break that placed no row ends every id alive there; events name the new
roots like any other Gaussian. The log is written here with the logger's own writer."""
import os
import sys
import tempfile

import numpy as np

import vis4gs

sys.path.insert(0, os.path.join(os.environ["VIS4GS_SOURCE_DIR"], "Applications", "TrainingLogger"))
from vis4gs_logger import CLONE, PRUNE, TrainingLogWriter  # noqa: E402


def snapshot(w, iteration, ids):
    n = len(ids)
    w.write_snapshot(iteration, np.array(ids), np.zeros((n, 3)), np.zeros((n, 3)),
                     np.tile([1.0, 0, 0, 0], (n, 1)), np.zeros(n), np.zeros((n, 1, 3)))


folder = tempfile.mkdtemp(prefix="vis4gs-breaks-")
log = os.path.join(folder, "breaks.h5")
with TrainingLogWriter(log, iterations=60, sh_degree=0) as w:
    snapshot(w, 0, [0, 1, 2, 3])
    w.append_metrics(10, num_gaussians=5)
    w.append_events(10, CLONE, [0], [4])
    # 20: two rows appended outside the logger: ids 5, 6 are new roots, 0..4 kept
    w.append_lineage_break(20, tracked=5, rows=7, kept=5, first_new_id=5, new_roots=2, where="t")
    w.append_events(30, CLONE, [5], [7])
    # 40: rows removed outside the logger: 0..7 end, the 3 rows are new roots 8, 9, 10
    w.append_lineage_break(40, tracked=8, rows=3, kept=0, first_new_id=8, new_roots=3, where="t")
    w.append_events(50, PRUNE, [9])
    snapshot(w, 50, [8, 10])

reader = vis4gs.vtkGaussianTrainingLogReader()
reader.SetFileName(log)
tree_filter = vis4gs.vtkGaussianGenealogyTreeFilter()
tree_filter.SetInputConnection(reader.GetOutputPort(3))
tree_filter.Update()
tree = tree_filter.GetOutput()

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


fd = reader.GetOutputDataObject(3).GetFieldData()
first = fd.GetArray("LineageBreakFirstNewId")
check(first is not None and [first.GetValue(i) for i in range(first.GetNumberOfTuples())] == [5, 8],
      "the events port's field data carries the breaks")
vd = tree.GetVertexData()
check(tree.GetNumberOfVertices() == 1 + 11, f"{tree.GetNumberOfVertices()} vertices, expected 12")
pedigree = vd.GetPedigreeIds()
node = {int(pedigree.GetValue(v)): v for v in range(1, tree.GetNumberOfVertices())}
check(sorted(node) == list(range(11)), f"ids {sorted(node)}")
mark = vd.GetArray("LineageBreakRoot")
check(mark is not None, "no LineageBreakRoot vertex array")
if mark is not None:
    marked = sorted(i for i, v in node.items() if mark.GetValue(v))
    check(marked == [5, 6, 8, 9, 10], f"break roots {marked}")
birth = vd.GetArray("BirthIteration")
death = vd.GetArray("DeathIteration")
pruned = vd.GetArray("Pruned")
expected_birth = {0: 0, 1: 0, 2: 0, 3: 0, 4: 10, 5: 20, 6: 20, 7: 30, 8: 40, 9: 40, 10: 40}
expected_death = {i: 40 for i in range(8)}
expected_death.update({8: -1, 9: 50, 10: -1})
for i in range(11):
    check(birth.GetValue(node[i]) == expected_birth[i], f"id {i} born {birth.GetValue(node[i])}")
    check(death.GetValue(node[i]) == expected_death[i], f"id {i} died {death.GetValue(node[i])}")
    check(pruned.GetValue(node[i]) == (1 if i == 9 else 0), f"id {i} pruned flag")
check(tree.GetParent(node[7]) == node[5], "7 is the clone of the new root 5")
check(tree.GetParent(node[4]) == node[0], "4 is the clone of 0")
for i in (5, 6, 8, 9, 10):
    check(tree.GetParent(node[i]) == 0, f"new root {i} hangs under the virtual root")

if failures:
    print("FAILED:", *failures, sep="\n  ")
    sys.exit(1)
print("lineage breaks in the tree agree")

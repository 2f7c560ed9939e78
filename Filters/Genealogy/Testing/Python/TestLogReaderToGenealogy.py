"""The obvious pipeline needs no glue: the training-log reader's events port connected to
the genealogy filter builds the demo log's tree with no parameter set by hand. Checked
against the log read independently with h5py: one vertex per initial Gaussian and per birth
(plus the virtual root), every child under the parent the log records, and the last iteration
the log plans."""
import os
import sys

import h5py
import numpy as np

import vis4gs

log = os.path.join(os.environ["VIS4GS_SOURCE_DIR"], "Data", "Demo", "vis4gs-demo.h5")

# h5py first: the reader keeps the file open with other HDF5 locking flags.
with h5py.File(log, "r") as f:
    snapshots = sorted(f["snapshots"])
    initial = f["snapshots"][snapshots[0]]["id"][()]
    kind = f["events/kind"][()]
    parent = f["events/parent"][()]
    child = f["events/child"][()]
    last = max(int(f.attrs["iterations"]), int(f["snapshots"][snapshots[-1]].attrs["iteration"]))

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


births = np.flatnonzero(kind != 3)
check(len(initial) > 0 and len(births) > 0, "the demo log has initial Gaussians and births")
check(tree.GetNumberOfVertices() == 1 + len(initial) + len(births),
      f"{tree.GetNumberOfVertices()} vertices, expected 1 + {len(initial)} + {len(births)}")
fd = reader.GetOutputDataObject(3).GetFieldData()
ids = fd.GetArray("InitialIds")
check(ids is not None and ids.GetNumberOfTuples() == len(initial)
      and all(ids.GetValue(i) == initial[i] for i in range(len(initial))),
      "InitialIds equals the first snapshot's ids")
check(fd.GetArray("LastIteration").GetValue(0) == last, f"LastIteration {last}")

# Node i + 1 is Gaussian creation i: the initial ones, then one per birth in log order.
pedigree = tree.GetVertexData().GetPedigreeIds()
node_of = {int(pedigree.GetValue(v)): v for v in range(1, tree.GetNumberOfVertices())}
check(sorted(node_of) == sorted(list(initial) + list(child[births])), "one node per Gaussian id")
wrong = sum(1 for e in births
            if tree.GetParent(node_of[int(child[e])]) != node_of[int(parent[e])])
check(wrong == 0, f"{wrong} children not under their logged parent")

if failures:
    print("FAILED:", *failures, sep="\n  ")
    sys.exit(1)
print(f"reader -> genealogy: {tree.GetNumberOfVertices()} vertices, {len(births)} births, "
      f"last iteration {last}")

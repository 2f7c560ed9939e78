"""`vis4gs view` opens what is intact in a damaged training log (issue 35, part 4).

  CheckDamagedLog.py CASE VIS4GS DEMO_LOG WORKDIR [--self-test]

Copies the demo log and damages it (h5py):
  events    /events/parent of one row names an id no Gaussian ever had;
  snapshot  the last snapshot's position dataset loses its last row (its lengths disagree).

Then `vis4gs view LOG --dump-inputs=DIR` (or, with --self-test, the window's scripted session
under the run's X server) must exit 0 with the views whose data is intact, each checked against
the log read here with h5py: the scene (the last snapshot; for "snapshot" the one before, the
last that can be read), the metrics; for "events" the history of selected Gaussians and no tree
(the tree view says why); for "snapshot" the whole tree, and no history (it reads every
snapshot; it says so, and with --self-test the window's status bar says so when a pick selects
Gaussians). The reason is said once on standard
error, naming the log and the damaged part.
"""
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from Checks import check, finish  # noqa: E402


def damage(case, source, log):
    shutil.copyfile(source, log)
    with h5py.File(log, "r+") as f:
        snapshots = sorted(f["snapshots"].keys())
        if case == "events":
            parent = f["events/parent"]
            row = parent.shape[0] // 2
            bad = int(max(f["events/child"][:].max(), 0)) + 1000000
            parent[row] = bad
            return {"scene": snapshots[-1], "tree": False,
                    "reason": rf"/events row {row} .*names the unknown id {bad}"}
        group = f["snapshots"][snapshots[-1]]
        position = group["position"][:-1]
        del group["position"]
        group.create_dataset("position", data=position)
        return {"scene": snapshots[-2], "tree": True,
                "reason": rf"snapshots that cannot be read are left out \(.*"
                          rf"{int(snapshots[-1])}.*showing iteration {int(snapshots[-2])}"}


def read_vtk(path):
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLTableReader
    reader = vtkXMLPolyDataReader() if path.endswith(".vtp") else vtkXMLTableReader()
    reader.SetFileName(path)
    reader.Update()
    return reader.GetOutput()


def main():
    if len(sys.argv) < 5:
        sys.exit("usage: CheckDamagedLog.py events|snapshot VIS4GS DEMO_LOG WORKDIR [--self-test]")
    case, vis4gs, source, work = sys.argv[1:5]
    self_test = "--self-test" in sys.argv[5:]
    os.makedirs(work, exist_ok=True)
    log = os.path.join(work, f"damaged-{case}.h5")
    expect = damage(case, source, log)
    out = os.path.join(work, f"{case}-{'self-test' if self_test else 'inputs'}")
    shutil.rmtree(out, ignore_errors=True)
    command = [vis4gs, "view", log, ("--self-test=" if self_test else "--dump-inputs=") + out]
    if self_test:
        command.append("--resolution=1200,800")
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         timeout=900)
    print(run.stdout[-4000:], run.stderr[-4000:], sep="\n")
    check(run.returncode == 0, f"{case}: vis4gs view opens the damaged log (status {run.returncode})")
    said = [line for line in run.stderr.splitlines() if re.search(expect["reason"], line)]
    check(len(said) == 1, f"{case}: the reason is said once on standard error ({len(said)} times)")
    check(all(log in line for line in said), f"{case}: the message names {log}")
    if self_test:
        check("self-test passed" in run.stdout + run.stderr, f"{case}: the scripted session passes")
        if expect["tree"]:
            # The history reads every snapshot: the timeline, which pulls it from the session
            # when the pick selects, has none, and the status bar says why (issue 33).
            said = [line for line in run.stdout.splitlines()
                    if line.startswith("ok: the status bar says why the timeline has no history")]
            check(len(said) == 1 and log in said[0] and "the property history" in said[0] and
                  not re.search(r"0x[0-9a-fA-F]{6,}", said[0]),
                  f"{case}: the status bar names the log and the history, no object address: "
                  f"{said[0] if said else 'not said'}")
        finish(f"{case}: the window opens the intact views of the damaged log")
        return

    with h5py.File(log, "r") as f:
        ids = f["snapshots"][expect["scene"]]["id"][:]
        position = f["snapshots"][expect["scene"]]["position"][:]
        metrics = f["metrics/iteration"].shape[0]
        events = f["events/iteration"].shape[0]
        initial = int(f["snapshots"]["000000"]["id"].shape[0])
    scene = read_vtk(os.path.join(out, "scene.vtp"))
    from vtkmodules.util.numpy_support import vtk_to_numpy
    got_ids = vtk_to_numpy(scene.GetPointData().GetArray("GaussianId"))
    check(np.array_equal(got_ids, ids) and
          np.array_equal(vtk_to_numpy(scene.GetPoints().GetData()), position),
          f"{case}: the scene is snapshot {expect['scene']} ({len(ids)} Gaussians, ids and "
          "positions as h5py reads them)")
    table = read_vtk(os.path.join(out, "metrics.vtt"))
    check(table.GetNumberOfRows() == metrics, f"{case}: the metrics ({table.GetNumberOfRows()} "
          f"rows, the log {metrics})")
    history = os.path.join(out, "history.vtt")
    if expect["tree"]:
        # The history reads every snapshot: a damaged one leaves it out, saying so.
        said = [line for line in run.stderr.splitlines() if "no property history" in line]
        check(not os.path.exists(history) and len(said) == 1 and
              f"{log}: the property history: " in said[0],
              f"{case}: no property history, and it says so once, naming the log: "
              f"{said[0] if said else 'not said'}")
    else:
        check(os.path.exists(history) and read_vtk(history).GetNumberOfRows() > 0,
              f"{case}: the history of selected Gaussians is there")
    tree = os.path.join(out, "tree-vertices.vtt")
    if expect["tree"]:
        # One vertex per initial Gaussian and per birth, plus the virtual root.
        births = events - int(np.count_nonzero(h5py.File(log, "r")["events/kind"][:] == 3))
        vertices = read_vtk(tree).GetNumberOfRows() if os.path.exists(tree) else 0
        check(vertices == initial + births + 1,
              f"{case}: the whole tree is there ({vertices} vertices, the log's events give "
              f"{initial + births + 1})")
    else:
        check(not os.path.exists(tree), f"{case}: no tree (its events are damaged)")
    finish(f"{case}: the intact views of the damaged log open")


if __name__ == "__main__":
    main()

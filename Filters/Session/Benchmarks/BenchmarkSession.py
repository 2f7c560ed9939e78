"""vtkGaussianSession against the readers and filters connected by hand, in one process and
alternately (Documentation/performance-history.md, "The session object against the filters
connected by hand"): wall and CPU time of the Gaussians with the four scores, the cameras, the
metrics, the genealogy tree and bands, and of asking every session port again (cached).

Usage: PYTHONPATH=build/lib/python3/dist-packages /usr/bin/python3 BenchmarkSession.py LOG.h5"""
import sys
import time

from vtkmodules.vtkCommonCore import vtkObject

import vis4gs

vtkObject.GlobalWarningDisplayOff()
log = sys.argv[1]
again = (0.0, 0.0)


def timed(f):
    wall, cpu = time.perf_counter(), time.process_time()
    f()
    return time.perf_counter() - wall, time.process_time() - cpu


def by_hand():
    """The straightforward way: the readers and filters a script connects."""
    reader = vis4gs.vtkGaussianTrainingLogReader()
    reader.SetFileName(log)
    scores = vis4gs.vtkGaussianArtifactScoreFilter()
    scores.SetInputConnection(reader.GetOutputPort(0))
    scores.SetCamerasConnection(reader.GetOutputPort(1))
    scores.Update()
    events = vis4gs.vtkGaussianTrainingLogReader()
    events.SetFileName(log)
    genealogy = vis4gs.vtkGaussianGenealogyTreeFilter()
    genealogy.SetInputConnection(events.GetOutputPort(3))
    genealogy.Update()
    reader.Update(2)


def session():
    global again
    s = vis4gs.vtkGaussianSession()
    s.SetFileName(log)
    for port in (0, 1, 2, 3, 4):
        s.Update(port, None)
    # Every port again: cached, nothing re-executes.
    again = timed(lambda: [s.Update(port, None) for port in (0, 1, 2, 3, 4)])


for name, f in (("by hand", by_hand), ("session", session), ("by hand", by_hand),
                ("session", session)):
    w, c = timed(f)
    extra = f"; every port again {again[0] * 1000:.1f} ms" if name == "session" else ""
    print(f"{name}: {w:.2f} s wall, {c:.2f} s CPU{extra}")

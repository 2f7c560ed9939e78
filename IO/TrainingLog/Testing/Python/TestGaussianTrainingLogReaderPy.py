# SPDX-License-Identifier: BSD-3-Clause
"""A log written with plain h5py (the example of Documentation/file-formats.md) read by
vtkGaussianTrainingLogReader from Python: time steps, snapshot arrays, history."""

import atexit
import math
import os
import shutil
import sys
import tempfile

import h5py
import numpy as np

from vis4gs.vis4gsIOTrainingLog import vtkGaussianTrainingLogReader
from vtkmodules.vtkCommonCore import vtkIdTypeArray
from vtkmodules.vtkCommonDataModel import vtkTable
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline

workdir = tempfile.mkdtemp()
atexit.register(shutil.rmtree, workdir, ignore_errors=True)
path = os.path.join(workdir, "h5py_log.h5")
gz = dict(compression="gzip", compression_opts=1, shuffle=True)
with h5py.File(path, "w") as f:
    f.attrs["format"] = "vis4gs-training-log"
    f.attrs["format_version"] = 1
    f.attrs["producer"] = "h5py example"
    f.attrs["scene"] = "toy"
    f.attrs["sh_degree"] = 1
    f.attrs["iterations"] = 1000
    m = f.create_group("metrics")
    its = np.arange(1, 11, dtype=np.int32) * 100
    m.create_dataset("iteration", data=its, maxshape=(None,), chunks=(1024,), **gz)
    m.create_dataset("num_gaussians", data=np.full(10, 5, np.int64), maxshape=(None,), chunks=(1024,), **gz)
    for c in ("loss", "l1", "psnr", "ssim", "lpips", "elapsed_s"):
        m.create_dataset(c, data=np.full(10, np.nan), maxshape=(None,), chunks=(1024,), **gz)
    m["loss"][:] = 1.0 / its
    e = f.create_group("events")
    e.create_dataset("iteration", data=np.array([500, 500], np.int32))
    e.create_dataset("kind", data=np.array([2, 2], np.uint8))
    e.create_dataset("parent", data=np.array([1, 1], np.int64))
    e.create_dataset("child", data=np.array([5, 6], np.int64))
    for it, ids in ((300, [0, 1, 2, 3, 4]), (600, [0, 2, 3, 4, 5, 6])):
        g = f.create_group("snapshots/%06d" % it)
        g.attrs["iteration"] = it
        n = len(ids)
        g.create_dataset("id", data=np.array(ids, np.int64), chunks=(16384,), maxshape=(None,), **gz)
        pos = np.array([[i, it, 0] for i in ids], np.float32)
        g.create_dataset("position", data=pos, chunks=(16384, 3), maxshape=(None, 3), **gz)
        g.create_dataset("log_scale", data=np.full((n, 3), -2, np.float32), **gz)
        g.create_dataset("rotation", data=np.tile(np.float32([1, 0, 0, 0]), (n, 1)), **gz)
        g.create_dataset("opacity_logit", data=np.array(ids, np.float32) * 0.5, **gz)
        g.create_dataset("sh", data=np.arange(n * 4 * 3, dtype=np.float32).reshape(n, 4, 3),
                         chunks=(16384, 1, 3), maxshape=(None, 4, 3), **gz)

reader = vtkGaussianTrainingLogReader()
reader.SetFileName(path)
reader.UpdateInformation()
steps = reader.GetOutputInformation(0).Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS())
assert list(steps) == [300.0, 600.0], steps
lacks = [reader.GetLack(i) for i in range(reader.GetNumberOfLacks())]
assert any("/cameras" in l for l in lacks) and any("/metrics/test" in l for l in lacks), lacks

assert reader.GetLoadSHRest()  # the default: every SH degree, as vis4gs analyze reads
reader.LoadSHRestOff()
reader.UpdateTimeStep(400)
g = reader.GetGaussiansOutput()
assert reader.GetLoadedIteration() == 300
assert g.GetNumberOfPoints() == 5
assert g.GetPoint(4) == (4.0, 300.0, 0.0)
assert g.GetPointData().GetArray("SH").GetNumberOfComponents() == 3

reader.LoadSHRestOn()
reader.UpdateTimeStep(600)
assert g.GetNumberOfPoints() == 6
sh = g.GetPointData().GetArray("SH")
assert sh.GetNumberOfComponents() == 12 and sh.GetComponent(1, 11) == 23.0

reader.Update(3)
assert reader.GetEventsOutput().GetNumberOfRows() == 2
reader.Update(2)
metrics = reader.GetMetricsOutput()
assert metrics.GetNumberOfRows() == 10
assert math.isclose(metrics.GetValueByName(0, "Loss").ToDouble(), 0.01)

ids = vtkIdTypeArray()
for i in (1, 5):
    ids.InsertNextValue(i)
history = vtkTable()
assert reader.GetPropertyHistory(ids, history) == 1
rows = [(history.GetValueByName(r, "GaussianId").ToInt(), history.GetValueByName(r, "Iteration").ToInt())
        for r in range(history.GetNumberOfRows())]
assert rows == [(1, 300), (5, 600)], rows
print("ok")
sys.exit(0)

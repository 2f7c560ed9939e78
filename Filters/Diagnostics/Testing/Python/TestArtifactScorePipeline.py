"""A Python pipeline from `vis4gs`: Gaussians + a camera table through the coverage and the
score filters (needle shape alone needs no cameras; coverage needs no images)."""
import math
import sys

from vtkmodules.vtkCommonCore import (vtkDoubleArray, vtkFloatArray, vtkIntArray, vtkPoints,
                                      vtkStringArray)
from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkTable

import vis4gs

failures = []


def check(ok, what):
    if not ok:
        print("FAILED:", what)
        failures.append(what)


# Two Gaussians in front of the camera at the origin, one behind it.
scene = vtkPolyData()
points = vtkPoints()
arrays = {}
for name, comps in (("LogScale", 3), ("Rotation", 4), ("OpacityLogit", 1), ("SH", 3)):
    a = vtkFloatArray()
    a.SetName(name)
    a.SetNumberOfComponents(comps)
    arrays[name] = a
for x, z in ((0.0, 5.0), (0.3, 4.0), (0.0, -3.0)):
    points.InsertNextPoint(x, 0.0, z)
    arrays["LogScale"].InsertNextTuple3(-1.5, -2.5, -2.5)
    arrays["Rotation"].InsertNextTuple4(1.0, 0.0, 0.0, 0.0)
    arrays["OpacityLogit"].InsertNextTuple1(1.5)
    arrays["SH"].InsertNextTuple3(0.1, 0.2, 0.3)
scene.SetPoints(points)
for a in arrays.values():
    scene.GetPointData().AddArray(a)

cameras = vtkTable()
columns = []
for name, cls, comps in (("Name", vtkStringArray, 1), ("Width", vtkIntArray, 1),
                         ("Height", vtkIntArray, 1), ("Fx", vtkDoubleArray, 1),
                         ("Fy", vtkDoubleArray, 1), ("WorldToCamera", vtkDoubleArray, 16)):
    c = cls()
    c.SetName(name)
    c.SetNumberOfComponents(comps)
    columns.append(c)
columns[0].InsertNextValue("view0")
columns[1].InsertNextValue(48)
columns[2].InsertNextValue(32)
columns[3].InsertNextValue(40.0)
columns[4].InsertNextValue(40.0)
columns[5].InsertNextTuple([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1])
for c in columns:
    cameras.AddColumn(c)

coverage = vis4gs.vtkGaussianViewCoverageFilter()
coverage.SetInputData(scene)
coverage.SetCamerasData(cameras)
coverage.Update()
pd = coverage.GetOutput().GetPointData()
vc = pd.GetArray("ViewCoverage")
flags = pd.GetArray("NoVisibleView")
check(vc is not None and flags is not None, "ViewCoverage and NoVisibleView added")
if vc is not None and flags is not None:
    check([vc.GetValue(i) for i in range(3)] == [1.0, 1.0, 0.0], "coverage 1, 1, 0")
    check([flags.GetValue(i) for i in range(3)] == [0, 0, 1], "only the hidden one flagged")
check(pd.GetArray("BlurScore") is None, "no blur computed by the coverage filter")

shape = vis4gs.vtkGaussianArtifactScoreFilter()
shape.SetInputData(scene)
shape.ComputeViewCoverageOff()
shape.ComputeBlurScoreOff()
shape.ComputeNeedleScoreOff()
shape.Update()
s = shape.GetOutput().GetPointData().GetArray("NeedleShape")
check(s is not None, "NeedleShape without cameras")
if s is not None:
    # scales e^-1.5, e^-2.5, e^-2.5: q = softmax(2 * log-scale)
    w = [math.exp(-3.0), math.exp(-5.0), math.exp(-5.0)]
    q = [v / sum(w) for v in w]
    h = -sum(v * math.log(v) for v in q)
    check(abs(s.GetValue(0) - (3 - math.exp(h)) / 2) < 1e-12, "needle shape value")
sys.exit(1 if failures else 0)

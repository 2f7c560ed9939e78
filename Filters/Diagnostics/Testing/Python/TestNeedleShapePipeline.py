"""A Python pipeline from `vis4gs`: a Gaussian scene through vtkGaussianNeedleShapeFilter."""
import math
import sys

from vtkmodules.vtkCommonCore import vtkFloatArray, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData

import vis4gs

scene = vtkPolyData()
points = vtkPoints()
log_scale = vtkFloatArray()
log_scale.SetName("LogScale")
log_scale.SetNumberOfComponents(3)
for i, ls in enumerate([(0.0, 0.0, 0.0), (700.0, -700.0, -700.0), (5.0, 5.0, -30.0)]):
    points.InsertNextPoint(i, 0, 0)
    log_scale.InsertNextTuple3(*ls)
scene.SetPoints(points)
scene.GetPointData().AddArray(log_scale)

f = vis4gs.vtkGaussianNeedleShapeFilter()
f.SetInputData(scene)
f.Update()
s = f.GetOutput().GetPointData().GetArray("NeedleShape")
values = [s.GetValue(i) for i in range(3)]
expected = [0.0, 1.0, 0.5]
ok = all(math.isclose(v, e, abs_tol=1e-12) for v, e in zip(values, expected))
if not ok:
    print("FAILED: NeedleShape", values, "expected", expected)
sys.exit(0 if ok else 1)

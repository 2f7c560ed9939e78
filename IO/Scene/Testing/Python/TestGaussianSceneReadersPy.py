"""Builds reader pipelines from `import vis4gs`: a 3DGS PLY through the reader and back out
through the writer (bytes identical), the .splat file, and the COLMAP cameras as a table.
Exits non-zero and prints FAILED on any mismatch."""
import os
import sys
import tempfile

import vis4gs
from vtkmodules.util.numpy_support import vtk_to_numpy

import numpy as np
from vis4gs_test_data import shared_data_dir

failures = []


def check(ok, what):
    if not ok:
        print("FAILED: " + what)
        failures.append(what)


data = shared_data_dir()
ply = os.path.join(data, "inria_ply_tiny_kacytran/point_cloud/iteration_7000/point_cloud.ply")

# Independent decode of the file with numpy: 62 little-endian floats per row.
raw = open(ply, "rb").read()
start = raw.index(b"end_header\n") + len(b"end_header\n")
rows = np.frombuffer(raw[start:], dtype="<f4").reshape(-1, 62)

reader = vis4gs.vtkGaussianSceneReader()
reader.SetFileName(ply)
reader.Update()
pd = reader.GetOutput()
check(pd.GetNumberOfPoints() == 9080, "9080 Gaussians")
points = vtk_to_numpy(pd.GetPoints().GetData())
check(np.array_equal(points.view(np.uint32), rows[:, 0:3].view(np.uint32)), "positions bit-exact")
sh = vtk_to_numpy(pd.GetPointData().GetArray("SH")).reshape(-1, 16, 3)
check(np.array_equal(sh[:, 0, :], rows[:, 6:9]), "SH DC")
# f_rest is channel-major in the file: f_rest[c*15 + k-1] -> SH[k][c].
rest = rows[:, 9:54].reshape(-1, 3, 15).transpose(0, 2, 1)
check(np.array_equal(sh[:, 1:, :], rest), "SH rest reordered to coefficient-major")
opacity = vtk_to_numpy(pd.GetPointData().GetArray("Opacity"))
check(np.allclose(opacity, 1 / (1 + np.exp(-rows[:, 54].astype(np.float64))), atol=1e-6), "opacity")
check(pd.GetPointData().GetPedigreeIds().GetName() == "GaussianId", "pedigree ids")

with tempfile.TemporaryDirectory() as tmp:
    out = os.path.join(tmp, "out.ply")
    writer = vis4gs.vtkGaussianPLYWriter()
    writer.SetInputConnection(reader.GetOutputPort())
    writer.SetFileName(out)
    writer.Write()
    check(open(out, "rb").read() == raw, "reader -> writer reproduces the file")

reader.SetMaxSHDegree(0)
reader.LoadExtrasOff()
reader.Update()
check(reader.GetOutput().GetPointData().GetArray("SH").GetNumberOfComponents() == 3, "MaxSHDegree 0")
check(reader.GetOutput().GetPointData().GetArray("nx") is None, "LoadExtras off")

splat = vis4gs.vtkGaussianSceneReader()
splat.SetFileName(os.path.join(data, "inria_ply_tiny_kacytran/model_1.splat"))
splat.Update()
check(splat.GetOutput().GetNumberOfPoints() == 22764, "22764 splats")

cameras = vis4gs.vtkGaussianCameraReader()
cameras.SetFileName(os.path.join(data, "colmap_statue_bartoszek"))
cameras.EvalOn()
cameras.Update()
table = cameras.GetOutput()
check(table.GetNumberOfRows() == 23, "23 cameras")
split = vtk_to_numpy(table.GetColumnByName("Split"))
check(list(np.nonzero(split)[0]) == [0, 8, 16], "test views every 8th")
w2c = vtk_to_numpy(table.GetColumnByName("WorldToCamera")).reshape(-1, 4, 4)
r = w2c[:, :3, :3]
check(np.allclose(r @ r.transpose(0, 2, 1), np.eye(3), atol=1e-9), "rotations orthonormal")

sys.exit(1 if failures else 0)

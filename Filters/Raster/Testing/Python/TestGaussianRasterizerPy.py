"""Renders the donut scene through `import vis4gs` (PLY reader -> vtkGaussianRasterizer with a
camera table built in Python) and checks the image against an independent numpy rendering of
the same Gaussians (SH degree 0, straight formulas of the reference rasteriser, double
precision, global depth sort; no tiles), plus the documented row flip.
Exits non-zero and prints FAILED on any mismatch."""
import os
import sys

import numpy as np
import vis4gs
from vtkmodules.util.numpy_support import vtk_to_numpy, numpy_to_vtk
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkTable
from vis4gs_test_data import shared_data_dir

failures = []


def check(ok, what):
    if not ok:
        print("FAILED: " + what)
        failures.append(what)


data = shared_data_dir()
ply = os.path.join(data, "gs_ply_sh0_variant_donut_v3dg/fused.ply")

W, H, F, TZ = 40, 28, 50.0, 0.5
table = vtkTable()
name = vtkStringArray()
name.SetName("Name")
name.InsertNextValue("cam0")
table.AddColumn(name)
for col, value in (("Width", W), ("Height", H)):
    a = vtkIntArray()
    a.SetName(col)
    a.InsertNextValue(value)
    table.AddColumn(a)
for col, value in (("Fx", F), ("Fy", F)):
    a = vtkDoubleArray()
    a.SetName(col)
    a.InsertNextValue(value)
    table.AddColumn(a)
w2c = np.eye(4)
w2c[2, 3] = TZ
m = vtkDoubleArray()
m.SetName("WorldToCamera")
m.SetNumberOfComponents(16)
m.InsertNextTuple(list(w2c.ravel()))
table.AddColumn(m)

reader = vis4gs.vtkGaussianSceneReader()
reader.SetFileName(ply)
raster = vis4gs.vtkGaussianRasterizer()
raster.SetInputConnection(0, reader.GetOutputPort())
raster.SetCamerasData(table)
raster.SetBackground(0.0, 0.0, 1.0)
raster.SetPrecisionToDouble()
raster.Update()
img = raster.GetOutput()
check(img.GetDimensions() == (W, H, 1), "image size")
rgb = vtk_to_numpy(img.GetPointData().GetArray("RGB")).reshape(H, W, 3)[::-1]  # top row first
alpha = vtk_to_numpy(img.GetPointData().GetArray("Alpha")).reshape(H, W)[::-1]
contrib = vtk_to_numpy(img.GetPointData().GetArray("Contributors")).reshape(H, W)[::-1]

# Independent numpy rendering.
pd = reader.GetOutput()
mu = vtk_to_numpy(pd.GetPoints().GetData()).astype(np.float64)
ls = vtk_to_numpy(pd.GetPointData().GetArray("LogScale")).astype(np.float64)
q = vtk_to_numpy(pd.GetPointData().GetArray("Rotation")).astype(np.float64)
logit = vtk_to_numpy(pd.GetPointData().GetArray("OpacityLogit")).astype(np.float64)
sh = vtk_to_numpy(pd.GetPointData().GetArray("SH")).astype(np.float64).reshape(-1, 3)
t = mu + np.array([0, 0, TZ])
keep = t[:, 2] > 0.2
q = q / np.maximum(np.linalg.norm(q, axis=1, keepdims=True), 1e-12)
w, x, y, z = q.T
R = np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
              2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
              2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], 1).reshape(-1, 3, 3)
S2 = np.exp(2 * ls)
Sig = np.einsum("nik,nk,njk->nij", R, S2, R)
tanx, tany = W / (2 * F), H / (2 * F)
tx = np.clip(t[:, 0] / t[:, 2], -1.3 * tanx, 1.3 * tanx) * t[:, 2]
ty = np.clip(t[:, 1] / t[:, 2], -1.3 * tany, 1.3 * tany) * t[:, 2]
J = np.zeros((len(t), 2, 3))
J[:, 0, 0] = F / t[:, 2]
J[:, 0, 2] = -F * tx / t[:, 2] ** 2
J[:, 1, 1] = F / t[:, 2]
J[:, 1, 2] = -F * ty / t[:, 2] ** 2
cov = np.einsum("nia,nab,njb->nij", J, Sig, J)
a, b, c = cov[:, 0, 0] + 0.3, cov[:, 0, 1], cov[:, 1, 1] + 0.3
det = a * c - b * b
keep &= det != 0
A, B, C = c / det, -b / det, a / det
mid = 0.5 * (a + c)
radius = np.ceil(3 * np.sqrt(mid + np.sqrt(np.maximum(0.1, mid * mid - det))))
u = F * t[:, 0] / (t[:, 2] + 1e-7) + (W - 1) / 2
v = F * t[:, 1] / (t[:, 2] + 1e-7) + (H - 1) / 2
gx, gy = (W + 15) // 16, (H + 15) // 16
x0 = np.clip(np.trunc((u - radius) / 16), 0, gx)
x1 = np.clip(np.trunc((u + radius + 15) / 16), 0, gx)
y0 = np.clip(np.trunc((v - radius) / 16), 0, gy)
y1 = np.clip(np.trunc((v + radius + 15) / 16), 0, gy)
keep &= (x1 - x0) * (y1 - y0) > 0
o = 1 / (1 + np.exp(-logit))
col = np.maximum(0.28209479177387814 * sh + 0.5, 0)
order = np.array([i for i in np.argsort(t[:, 2], kind="stable") if keep[i]])
ref = np.zeros((H, W, 3))
refT = np.ones((H, W))
for py in range(H):
    for px in range(W):
        ids = order[(x0[order] <= px // 16) & (px // 16 < x1[order]) &
                    (y0[order] <= py // 16) & (py // 16 < y1[order])]
        dx, dy = u[ids] - px, v[ids] - py
        power = -0.5 * (A[ids] * dx * dx + C[ids] * dy * dy) - B[ids] * dx * dy
        al = np.minimum(0.99, o[ids] * np.exp(np.minimum(power, 0)))
        ok = (power <= 0) & (al >= 1 / 255)
        ids, al = ids[ok], al[ok]
        Tafter = np.cumprod(1 - al)
        stop = np.nonzero(Tafter < 1e-4)[0]
        n = stop[0] if len(stop) else len(al)  # the stopping Gaussian is not blended
        Tbefore = np.concatenate([[1.0], Tafter[:-1]])[:n]
        T = Tafter[n - 1] if n > 0 else 1.0
        ref[py, px] = (col[ids[:n]] * (al[:n] * Tbefore)[:, None]).sum(0) + T * np.array([0, 0, 1.0])
        refT[py, px] = T
err = np.abs(rgb - ref).max()
check(err < 1e-8, "vtkGaussianRasterizer matches the numpy reference (max error %g)" % err)
check(np.abs(alpha - (1 - refT)).max() < 1e-8, "alpha")
check((alpha > 0.5).sum() > 50, "the donut covers the view")
check(contrib.max() > 1, "contributors")
if failures:
    sys.exit(1)
print("ok")

"""View A from VTK Python without Qt (issue 22): vtkGaussianSceneView on the demo log's last
snapshot and cameras, linked to a selection hub. A Ray selection through the pixel of an opaque
Gaussian publishes the Gaussians on the ray to the hub, the view highlights as many, and their
depths are those numpy computes from the VTK camera; a Frame selects only Gaussians whose
centres VTK projects into the rectangle; a Single pick draws the orange marker at its pixel;
the overlay's legend spans the array's range as numpy finds it."""
import os
import sys

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdTypeArray
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter
import vtkmodules.vtkInteractionStyle  # noqa: F401  (the view's interactor style)
import vtkmodules.vtkRenderingAnnotation  # noqa: F401  (the legend, a vtkScalarBarActor)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the render window)
import vtkmodules.vtkRenderingFreeType  # noqa: F401  (the legend's text)

import vis4gs

log = os.path.join(os.environ["VIS4GS_SOURCE_DIR"], "Data", "Demo", "vis4gs-demo.h5")
failures = []


def check(cond, what):
    print(("ok: " if cond else "FAILED: ") + what)
    if not cond:
        failures.append(what)


reader = vis4gs.vtkGaussianTrainingLogReader()
reader.SetFileName(log)
reader.Update(0)
reader.Update(1)
scene = reader.GetOutputDataObject(0)
cameras = reader.GetOutputDataObject(1)
pd = scene.GetPointData()
ids = vtk_to_numpy(pd.GetArray("GaussianId")).astype(np.int64)
centres = vtk_to_numpy(scene.GetPoints().GetData()).astype(np.float64)
logit = vtk_to_numpy(pd.GetArray("OpacityLogit")).astype(np.float64)

hub = vis4gs.vtkGaussianSelectionHub()
hub.RenderOnChangeOff()
view = vis4gs.vtkGaussianSceneView()
window = view.GetRenderWindow()
window.SetSize(320, 240)
window.SetMultiSamples(0)
window.OffScreenRenderingOn()
view.SetSelectionHub(hub)
view.SetScene(scene)
view.SetCameras(cameras)
view.SetMaximumNumberOfSplats(0)
check(view.JumpToCamera(0), "the view jumps to the log's first camera")
view.Render()
renderer = view.GetRenderer()


def project(i):
    renderer.SetWorldPoint(*centres[i], 1.0)
    renderer.WorldToDisplay()
    return renderer.GetDisplayPoint()


def hub_ids():
    a = vtkIdTypeArray()
    hub.GetSelectedIds(a)
    return vtk_to_numpy(a).astype(np.int64) if a.GetNumberOfTuples() else np.zeros(0, np.int64)


# An opaque Gaussian near the image centre that Single picks at the pixel of its centre.
candidates = []
for i in np.nonzero(logit > 2.0)[0]:
    x, y, z = project(i)
    if 0 < z < 1:
        candidates.append((np.hypot(x - 160, y - 120), i, round(x), round(y)))
candidates.sort()
target = None
for _, i, x, y in candidates[:200]:
    if view.PickAt(x, y) == ids[i]:
        target, px, py = i, x, y
        break
check(target is not None, "Single picks a Gaussian at the pixel of its centre")
if target is None:
    sys.exit(1)
check(np.array_equal(hub_ids(), [ids[target]]) and view.GetHighlightCount() == 1,
      f"the hub holds Gaussian {ids[target]} and the view highlights one")

# What it draws: the orange centre marker (1, 0.35, 0) at the pick, over the splats.
grab = vtkWindowToImageFilter()
grab.SetInput(window)
grab.ReadFrontBufferOff()
grab.Update()
image = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).reshape(240, 320, -1)[:, :, :3]
around = image[max(0, py - 6):py + 7, max(0, px - 6):px + 7].astype(int)
orange = np.all(np.abs(around - [255, 89, 0]) <= 8, axis=2)
check(orange.sum() >= 9, f"the marker is drawn at ({px}, {py}) ({orange.sum()} orange pixels)")
check((image.max(axis=2) > 20).mean() > 0.2, "the splats fill the view")

# Ray: the Gaussians on the ray go to the hub, depth-ordered by the camera's view depth.
count = view.SelectRay(px, py)
hits = vtk_to_numpy(view.GetLastRayHitIds()).astype(np.int64)
depths = vtk_to_numpy(view.GetSelector().GetRayHitDistances()).astype(np.float64)
check(count == hits.size >= 1 and ids[target] in hits, f"Ray lists it among {count}")
check(np.array_equal(hub_ids(), np.unique(hits)) and view.GetHighlightCount() == np.unique(hits).size,
      "the hub holds the ray's Gaussians and the view highlights as many")
camera = renderer.GetActiveCamera()
position = np.array(camera.GetPosition())
direction = np.array(camera.GetFocalPoint()) - position
direction /= np.linalg.norm(direction)
row = {g: k for k, g in enumerate(ids)}
expected = np.array([(centres[row[g]] - position) @ direction for g in hits])
check(np.all(np.diff(depths) >= 0) and np.allclose(depths, expected, rtol=1e-4, atol=1e-4),
      "the ray's depths ascend and equal numpy's view depths of the centres "
      f"(max error {np.abs(depths - expected).max():.2e})")
mapper_ids = vtk_to_numpy(view.GetSplatMapper().GetSelectedIds()).astype(np.int64)
check(np.array_equal(np.sort(mapper_ids), hub_ids()), "the mapper highlights the hub's selection")

# Frame: every selected centre projects into the rectangle (VTK's projection).
half = 15
framed = view.SelectFrame(px - half, py - half, px + half, py + half)
inside = all(abs(project(row[g])[0] - px) <= half + 1 and abs(project(row[g])[1] - py) <= half + 1
             for g in hub_ids())
check(framed == hub_ids().size >= 1 and inside,
      f"Frame selects {framed} Gaussians, all centred inside the rectangle")

# The overlay's legend spans the array's own range.
view.SetOverlayArrayName("OpacityLogit")
view.Render()
lut = view.GetLegend().GetLookupTable()
check(view.GetLegend().GetVisibility() and np.allclose(lut.GetRange(), [logit.min(), logit.max()],
                                                       atol=1e-5),
      f"the legend spans OpacityLogit's range [{logit.min():.4f}, {logit.max():.4f}]")

view.SetSelectionHub(None)
check(hub.GetNumberOfViews() == 0, "the view unlinks from the hub")
if failures:
    sys.exit(1)

"""Resident memory of view A with and without the shared copy of the Gaussians (issue 22).

Usage: vis4gs-python BenchmarkSceneViewMemory.py LOG.h5 {read|view|separate}

Reads the log's last snapshot (vtkGaussianTrainingLogReader), then
  read      stops (the polydata alone),
  view      draws it with vtkGaussianSceneView and runs a Single, Ray and Frame selection
            (the mapper and the selector share the view's one Core copy),
  separate  does the same with a vtkGaussianSplatMapper, a vtkGaussianSelector and the
            frustums of their own, as the application's window did before the scene view
            class (the mapper and the selector each take the polydata's Core form: a
            conversion each before the reader's arrays became a shared cloud, none now).
Prints the CPU seconds; run each under `/usr/bin/time -v` for the peak resident set size
(Documentation/performance-history.md). Not run by CTest.
"""
import sys
import time

import vtkmodules.vtkInteractionStyle  # noqa: F401
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingFreeType  # noqa: F401
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow

import vis4gs

path, mode = sys.argv[1], sys.argv[2]
cpu = time.process_time()
reader = vis4gs.vtkGaussianTrainingLogReader()
reader.SetFileName(path)
reader.Update(0)
reader.Update(1)
scene = reader.GetOutputDataObject(0)
cameras = reader.GetOutputDataObject(1)
print(f"{scene.GetNumberOfPoints()} Gaussians read in {time.process_time() - cpu:.2f} s CPU")
if mode == "read":
    sys.exit(0)

width, height = 640, 480
x, y = width / 2, height / 2
cpu = time.process_time()
if mode == "view":
    hub = vis4gs.vtkGaussianSelectionHub()
    hub.RenderOnChangeOff()
    view = vis4gs.vtkGaussianSceneView()
    view.GetRenderWindow().SetSize(width, height)
    view.GetRenderWindow().OffScreenRenderingOn()
    view.SetSelectionHub(hub)
    view.SetScene(scene)
    view.SetCameras(cameras)
    view.ResetCamera()  # the whole scene in view: the selections hit Gaussians
    view.Render()
    counts = [view.SelectSingle(x, y), view.SelectRay(x, y),
              view.SelectFrame(x - 150, y - 150, x + 150, y + 150)]
elif mode == "separate":
    window = vtkRenderWindow()
    window.SetSize(width, height)
    window.OffScreenRenderingOn()
    renderer = vtkRenderer()
    window.AddRenderer(renderer)
    mapper = vis4gs.vtkGaussianSplatMapper()
    mapper.SetInputData(scene)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer.AddActor(actor)
    renderer.ResetCamera()
    window.Render()
    selector = vis4gs.vtkGaussianSelector()
    selector.SetRenderer(renderer)
    selector.SetSplatMapper(mapper)
    selector.SetScene(scene)
    frustums = vis4gs.vtkGaussianCameraFrustums()  # coloured by each selection, as in the view
    frustums.SetInputData(0, cameras)
    frustums.SetInputData(1, scene)
    counts = []
    for select in (lambda: selector.SelectSingle(x, y), lambda: selector.SelectRay(x, y),
                   lambda: selector.SelectFrame(x - 150, y - 150, x + 150, y + 150)):
        counts.append(select())
        frustums.SetSelectedIds(selector.GetSelectedIds())
        frustums.Update()
else:
    sys.exit(f"unknown mode {mode}")
print(f"{mode}: drawn and selected (Single {counts[0]}, Ray {counts[1]}, Frame {counts[2]}) "
      f"in {time.process_time() - cpu:.2f} s CPU")

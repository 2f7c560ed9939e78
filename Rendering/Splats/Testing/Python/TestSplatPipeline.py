"""A Python pipeline from `vis4gs`: a real 3DGS PLY through the splat mapper, a ray selection
published as GaussianId pedigree ids, the selection highlighted, and the training-camera
frustums coloured by how many selected Gaussians each view sees."""
import os
import sys

from vtkmodules.vtkCommonDataModel import vtkSelectionNode, vtkTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

import vis4gs
from vis4gs_test_data import shared_data_dir

data = shared_data_dir()
ply = os.path.join(data, "gs_ply_sh0_variant_donut_v3dg", "fused.ply")

reader = vis4gs.vtkGaussianSceneReader()
reader.SetFileName(ply)
reader.Update()
scene = reader.GetOutput()
if scene.GetNumberOfPoints() != 45624:
    print("FAILED: read", scene.GetNumberOfPoints(), "Gaussians")
    sys.exit(1)

mapper = vis4gs.vtkGaussianSplatMapper()
mapper.SetInputConnection(reader.GetOutputPort())
actor = vtkActor()
actor.SetMapper(mapper)
ren = vtkRenderer()
ren.AddActor(actor)
win = vtkRenderWindow()
win.SetOffScreenRendering(1)
win.SetMultiSamples(0)
win.SetSize(160, 120)
win.AddRenderer(ren)
ren.ResetCamera()
win.Render()
if mapper.GetLastDrawnCount() <= 0:
    print("FAILED: the mapper drew nothing")
    sys.exit(1)

def lit_pixels():
    grab = vtkWindowToImageFilter()
    grab.SetInput(win)
    grab.ReadFrontBufferOff()
    grab.Update()
    rgb = grab.GetOutput().GetPointData().GetScalars()
    # Image rows start at the bottom, like VTK display coordinates.
    return [(i % 160, i // 160) for i in range(rgb.GetNumberOfTuples()) if max(rgb.GetTuple(i)) > 20]


lit = lit_pixels()
if len(lit) < 50:
    print("FAILED: only", len(lit), "lit pixels")
    sys.exit(1)
x, y = lit[len(lit) // 2]

selector = vis4gs.vtkGaussianSelector()
selector.SetScene(scene)
selector.SetRenderer(ren)
hits = selector.SelectRay(x, y)
node = selector.GetSelection().GetNode(0)
if hits <= 0 or node.GetContentType() != vtkSelectionNode.PEDIGREEIDS:
    print("FAILED: the ray through lit pixel", (x, y), "selected", hits, "Gaussians")
    sys.exit(1)
if selector.SelectSingle(x, y) != 1:
    print("FAILED: no Gaussian under lit pixel", (x, y))
    sys.exit(1)
selector.SetModifier(selector.ADD)
selector.SelectRay(x, y)
if selector.GetSelectedIds().GetNumberOfTuples() < hits:
    print("FAILED: ADD lost Gaussians")
    sys.exit(1)
mapper.SetSelection(selector.GetSelection())
mapper.DimUnselectedOn()
win.Render()
dimmed = lit_pixels()
if len(dimmed) >= len(lit):
    print("FAILED: dimming did not darken the picture", len(dimmed), len(lit))
    sys.exit(1)

# One camera: the current view, from the VTK camera, through a camera table.
cam = ren.GetActiveCamera()
frustums = vis4gs.vtkGaussianCameraFrustums()
table = vtkTable()
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray, vtkStringArray, vtkUnsignedCharArray
def column(cls, name, values, comps=1):
    """A one-row column, filled before it joins the table."""
    a = cls()
    a.SetName(name)
    a.SetNumberOfComponents(comps)
    if comps == 1:
        a.InsertNextValue(values)
    else:
        a.InsertNextTuple(values)
    table.AddColumn(a)


m = cam.GetModelViewTransformMatrix()
# OpenCV world-to-camera = diag(1, -1, -1, 1) * OpenGL view.
w2c = [m.GetElement(r, c) * (1 if r in (0, 3) else -1) for r in range(4) for c in range(4)]
angle = cam.GetViewAngle()
import math
f = 120 / (2 * math.tan(math.radians(angle) / 2))
column(vtkStringArray, "Name", "view")
column(vtkUnsignedCharArray, "Split", 0)
column(vtkIntArray, "Width", 160)
column(vtkIntArray, "Height", 120)
for c, v in (("Fx", f), ("Fy", f), ("Cx", 80.0), ("Cy", 60.0)):
    column(vtkDoubleArray, c, v)
column(vtkDoubleArray, "WorldToCamera", w2c, 16)
column(vtkStringArray, "Image", "")
column(vtkStringArray, "Model", "PINHOLE")
frustums.SetInputData(0, table)
frustums.SetInputData(1, scene)
frustums.SetSelection(selector.GetSelection())
frustums.Update()
out = frustums.GetOutput()
count = out.GetCellData().GetArray("VisibleSelectedCount").GetValue(0)
# The view is the one the selection was made in: nearly every selected Gaussian has a
# footprint there (ray hits that are too transparent to reach alpha 1/255 have none).
selected = selector.GetSelectedIds().GetNumberOfTuples()
if out.GetNumberOfLines() != 8 or not (0.8 * selected <= count <= selected):
    print("FAILED: frustum lines", out.GetNumberOfLines(), "count", count, "of",
          selector.GetSelectedIds().GetNumberOfTuples())
    sys.exit(1)
print("ok:", hits, "ray hits,", len(lit), "lit pixels,", len(dimmed), "after dimming; the view sees", count)

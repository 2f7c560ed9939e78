"""Renders a scene file with Vis4GS (vtkGaussianSceneReader -> vtkGaussianRasterizer, float and
double arithmetic) and with the independent numpy float64 reference (reference_render.py,
which parses the file itself) from given cameras, and reports the PSNR of each image.
Used by the reference-check tests (Filters/Raster/Testing/Python/TestReferenceRender*.py)."""
import time

import numpy as np
import vis4gs
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkIntArray, vtkStringArray
from vtkmodules.vtkCommonDataModel import vtkTable

import reference_render as rr

MIN_PSNR = 50.0


def camera_table(world_to_camera, width, height, fx, fy):
    table = vtkTable()
    name = vtkStringArray()
    name.SetName("Name")
    name.InsertNextValue("cam")
    table.AddColumn(name)
    for col, value, kind in (("Width", width, vtkIntArray), ("Height", height, vtkIntArray),
                             ("Fx", fx, vtkDoubleArray), ("Fy", fy, vtkDoubleArray),
                             ("Cx", width / 2.0, vtkDoubleArray),
                             ("Cy", height / 2.0, vtkDoubleArray)):
        a = kind()
        a.SetName(col)
        a.InsertNextValue(value)
        table.AddColumn(a)
    m = vtkDoubleArray()
    m.SetName("WorldToCamera")
    m.SetNumberOfComponents(16)
    m.InsertNextTuple(list(np.asarray(world_to_camera, dtype=np.float64).ravel()))
    table.AddColumn(m)
    return table


def compare_file(path, scene, cameras, width, height, fov_x_deg=60.0, background=(0.1, 0.2, 0.3),
                 label=None, report=None):
    """Renders @p path with Vis4GS and @p scene (reference_render.Scene of the same file) with
    the reference from every world-to-camera matrix of @p cameras. Returns a list of
    (label, camera index, PSNR float, PSNR double, seconds of the reference)."""
    reader = vis4gs.vtkGaussianSceneReader()
    reader.SetFileName(path)
    reader.Update()
    raster = vis4gs.vtkGaussianRasterizer()
    raster.SetInputConnection(0, reader.GetOutputPort())
    raster.SetBackground(*background)
    fx = width / (2.0 * np.tan(np.radians(fov_x_deg) / 2.0))
    fy = fx
    rows = []
    for k, w2c in enumerate(cameras):
        raster.SetCamerasData(camera_table(w2c, width, height, fx, fy))
        images = []
        for precision in (raster.FLOAT, raster.DOUBLE):
            raster.SetPrecision(precision)
            raster.Modified()
            raster.Update()
            img = raster.GetOutput()
            rgb = vtk_to_numpy(img.GetPointData().GetArray("RGB"))
            images.append(rgb.reshape(height, width, 3)[::-1].astype(np.float64))
        t0 = time.time()
        ref, _ = rr.render(scene, w2c, width, height, fx, fy, background)
        seconds = time.time() - t0
        covered = float(np.mean(np.abs(ref - np.asarray(background)).sum(2) > 1e-3))
        row = (label or path, k, rr.psnr(images[0], ref), rr.psnr(images[1], ref), seconds,
               covered, float(np.abs(images[0] - ref).max()))
        rows.append(row)
        if report is not None:
            report(row)
    return rows


def print_row(row):
    label, k, p_float, p_double, seconds, covered, max_err = row
    print(f"{label} camera {k}: PSNR float {p_float:.1f} dB, double {p_double:.1f} dB, "
          f"max |error| float {max_err:.2g}, {100 * covered:.0f}% of pixels covered, "
          f"reference {seconds:.1f} s")

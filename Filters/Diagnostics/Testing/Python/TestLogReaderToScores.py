"""The obvious pipeline needs no glue: the training-log reader's Gaussians and cameras
connected to the score filter give the blur and needle scores of the embedded demo log, with
its training images read from inside the log. They are compared bit for bit with the
application's way of getting the same images (each embedded image written to a PNG file and
read back, the path vis4gs analyze takes), and a camera table without any image gives NaN
scores with the reason in the field data, never zeros."""
import math
import os
import sys
import tempfile

import h5py
import numpy as np
from vtkmodules.vtkCommonDataModel import vtkImageData, vtkTable
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy

import vis4gs

log = os.path.join(os.environ["VIS4GS_SOURCE_DIR"], "Data", "Demo", "vis4gs-demo.h5")
failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


def scores(configure):
    f = vis4gs.vtkGaussianArtifactScoreFilter()
    f.SetInputConnection(reader.GetOutputPort(0))
    f.SetLossResolution(2)
    configure(f)
    f.Update()
    pd = f.GetOutput().GetPointData()
    notes = f.GetOutput().GetFieldData().GetAbstractArray("ScoreWarnings")
    return ({n: vtk_to_numpy(pd.GetArray(n)).copy()
             for n in ("ViewCoverage", "BlurScore", "NeedleScore")},
            [notes.GetValue(i) for i in range(notes.GetNumberOfValues())])


# The embedded images as PNG files, as the application extracts them (h5py first: the reader
# keeps the file open with other HDF5 locking flags).
folder = tempfile.mkdtemp(prefix="vis4gs-log-images-")
with h5py.File(log, "r") as h5:
    for name in h5["images"]:
        pixels = h5["images"][name][()]  # [H, W, 3] u8, top row first
        image = vtkImageData()
        image.SetDimensions(pixels.shape[1], pixels.shape[0], 1)
        flat = np.ascontiguousarray(pixels[::-1]).reshape(-1, 3)  # VTK rows bottom-up
        image.GetPointData().SetScalars(numpy_to_vtk(flat, deep=1))
        writer = vtkPNGWriter()
        writer.SetFileName(os.path.join(folder, name + ".png"))
        writer.SetInputData(image)
        writer.Write()

reader = vis4gs.vtkGaussianTrainingLogReader()
reader.SetFileName(log)

embedded, notes = scores(lambda f: f.SetCamerasConnection(reader.GetOutputPort(1)))
files, _ = scores(lambda f: (f.SetCamerasConnection(reader.GetOutputPort(1)),
                             f.SetImageDirectory(folder)))
for name in ("ViewCoverage", "BlurScore", "NeedleScore"):
    a, b = embedded[name], files[name]
    check(a.shape == b.shape and np.array_equal(a, b),
          f"{name}: images from the log differ from the PNG files on "
          f"{int(np.sum(a != b)) if a.shape == b.shape else 'all'} Gaussians")
blur = embedded["BlurScore"]
check(np.all(np.isfinite(blur)) and np.count_nonzero(blur) > 0.9 * blur.size,
      f"BlurScore from the log is computed ({np.count_nonzero(blur)} of {blur.size} non-zero)")
check(not any("have no image" in n for n in notes), f"no view lacks its image: {notes}")

# Cameras that name no log and no image file: the scores cannot be computed.
cameras = vtkTable()
cameras.DeepCopy(reader.GetOutputDataObject(1))
cameras.GetFieldData().RemoveArray("TrainingLogFile")
missing, notes = scores(lambda f: f.SetCamerasData(cameras))
check(np.all(np.isnan(missing["BlurScore"])) and np.all(np.isnan(missing["NeedleScore"])),
      "without images BlurScore and NeedleScore are NaN")
check(np.array_equal(missing["ViewCoverage"], embedded["ViewCoverage"]),
      "View Coverage needs no image and is unchanged")
check(any("cannot be computed" in n for n in notes), f"the reason is in ScoreWarnings: {notes}")

if failures:
    print("FAILED:", *failures, sep="\n  ")
    sys.exit(1)
print(f"reader -> scores: {blur.size} Gaussians, blur from the log equals the PNG path bit for "
      f"bit; without images NaN with the reason")

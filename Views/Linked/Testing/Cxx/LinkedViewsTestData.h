// SPDX-License-Identifier: BSD-3-Clause
// Small hand-built stand-ins for the outputs of other modules, used by the linked-view tests:
// a genealogy vtkTree with the arrays of Filters/Genealogy (values derived by hand in the
// .cxx), its family bands, a metrics table as /metrics holds it, a Gaussian scene and a
// property history in the log reader's long format.
#ifndef LinkedViewsTestData_h
#define LinkedViewsTestData_h

#include "vtkSmartPointer.h"

class vtkGaussianSelectionHub;
class vtkPolyData;
class vtkRenderWindow;
class vtkTable;
class vtkTree;

namespace linkedtest
{
/// 3 families, 8 Gaussians (ids 0..7) under a virtual root (vertex 0, GaussianId -1).
vtkSmartPointer<vtkTree> MakeTree();
vtkSmartPointer<vtkTable> MakeBands();
/// Iteration 0, 500, ..., 3000 with PSNR, SSIM, LPIPS (NaN), NumGaussians.
vtkSmartPointer<vtkTable> MakeMetrics();
/// Gaussians 0..7 alive or not, with GaussianId, Opacity (id / 10 + 0.05), Scale.
vtkSmartPointer<vtkPolyData> MakeScene();
/// Iteration, GaussianId, Opacity for ids 0..7 at 0, 1000, 2000, 3000.
vtkSmartPointer<vtkTable> MakeHistory();
/// Vertex of a GaussianId (0..7) in MakeTree().
inline long long VertexOf(long long id)
{
  const long long vertex[8] = { 1, 5, 7, 2, 3, 4, 6, 8 };
  return vertex[id];
}
/// Expected P of vertex v (derived in the .cxx from D and T per DESIGN §4).
double ExpectedPerception(long long v);
/// Writes @p window as <name>-selected.png, then clears @p hub's selection, renders and
/// writes <name>-unselected.png, both in the working directory: the masked baseline
/// comparison (Testing/Python/vis4gs_image_compare.py) must pass on the first and fail on the
/// second. Returns false when a file could not be written.
bool WriteSelectionImages(vtkRenderWindow* window, vtkGaussianSelectionHub* hub, const char* name);
}

#endif

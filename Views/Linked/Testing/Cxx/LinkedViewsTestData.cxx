// SPDX-License-Identifier: BSD-3-Clause
#include "LinkedViewsTestData.h"

#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkGaussianSelectionHub.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMutableDirectedGraph.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkRenderWindow.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkUnsignedCharArray.h"
#include "vtkWindowToImageFilter.h"

#include <cmath>
#include <limits>
#include <string>

namespace linkedtest
{
namespace
{
// One row per vertex: id, parent vertex, birth, death (-1 alive), kind, pruned, row.
// Family A: 0 -clone@600-> 3 -split@1000-> 4, 5 (5 pruned @1500)
// Family B: 1 (pruned @2000) -clone@700-> 6
// Family C: 2 -clone-split@800-> 7
// Last iteration 3000.
struct NodeRow
{
  long long Id;
  int Parent;
  int Birth, Death, Kind, Pruned, Row;
};
const NodeRow Nodes[9] = {
  { -1, -1, 0, -1, 0, 0, -1 }, // virtual root
  { 0, 0, 0, -1, 0, 0, 0 },
  { 3, 1, 600, 1000, 1, 0, 1 },
  { 4, 2, 1000, -1, 2, 0, 2 },
  { 5, 2, 1000, 1500, 2, 1, 3 },
  { 1, 0, 0, 2000, 0, 1, 4 },
  { 6, 5, 700, -1, 1, 0, 5 },
  { 2, 0, 0, -1, 0, 0, 6 },
  { 7, 7, 800, -1, 4, 0, 7 },
};
}

//------------------------------------------------------------------------------
double ExpectedPerception(long long v)
{
  // P = 0.4 D / maxD + 0.6 T / maxT over the family (DESIGN §4), by hand:
  // A: D = 3, 2, 0, 0; T = 3000, 400, 2000, 500; maxD 3, maxT 3000.
  // B: D = 1, 0; T = 2000, 2300; maxD 1, maxT 2300.
  // C: D = 1, 0; T = 3000, 2200; maxD 1, maxT 3000.
  switch (v)
  {
    case 1:
      return 1.0;
    case 2:
      return 0.4 * 2.0 / 3.0 + 0.6 * 400.0 / 3000.0;
    case 3:
      return 0.6 * 2000.0 / 3000.0;
    case 4:
      return 0.6 * 500.0 / 3000.0;
    case 5:
      return 0.4 + 0.6 * 2000.0 / 2300.0;
    case 6:
      return 0.6;
    case 7:
      return 1.0;
    case 8:
      return 0.6 * 2200.0 / 3000.0;
    default:
      return -1.0;
  }
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTree> MakeTree()
{
  vtkNew<vtkMutableDirectedGraph> g;
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("GaussianId");
  vtkNew<vtkIntArray> x, death, row;
  x->SetName("LayoutX");
  death->SetName("DeathIteration");
  vtkNew<vtkDoubleArray> y, p;
  y->SetName("LayoutY");
  p->SetName("PerceptionValue");
  vtkNew<vtkUnsignedCharArray> kind, pruned;
  kind->SetName("BirthKind");
  pruned->SetName("Pruned");
  for (int v = 0; v < 9; ++v)
  {
    const NodeRow& n = Nodes[v];
    if (n.Parent < 0)
    {
      g->AddVertex();
    }
    else
    {
      g->AddChild(n.Parent);
    }
    ids->InsertNextValue(n.Id);
    x->InsertNextValue(n.Birth);
    death->InsertNextValue(n.Death);
    y->InsertNextValue(n.Row);
    p->InsertNextValue(v == 0 ? -1.0 : ExpectedPerception(v));
    kind->InsertNextValue(static_cast<unsigned char>(n.Kind));
    pruned->InsertNextValue(static_cast<unsigned char>(n.Pruned));
  }
  g->GetVertexData()->AddArray(x);
  g->GetVertexData()->AddArray(y);
  g->GetVertexData()->AddArray(death);
  g->GetVertexData()->AddArray(p);
  g->GetVertexData()->AddArray(kind);
  g->GetVertexData()->AddArray(pruned);
  g->GetVertexData()->SetPedigreeIds(ids);
  vtkNew<vtkIntArray> last;
  last->SetName("LastIteration");
  last->InsertNextValue(3000);
  g->GetFieldData()->AddArray(last);
  auto tree = vtkSmartPointer<vtkTree>::New();
  if (!tree->CheckedShallowCopy(g))
  {
    return nullptr;
  }
  return tree;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTable> MakeBands()
{
  auto table = vtkSmartPointer<vtkTable>::New();
  const char* names[4] = { "MinIteration", "MaxIteration", "MinRow", "MaxRow" };
  const int values[3][4] = { { 0, 3000, 0, 3 }, { 0, 3000, 4, 5 }, { 0, 3000, 6, 7 } };
  for (int c = 0; c < 4; ++c)
  {
    vtkNew<vtkIntArray> a;
    a->SetName(names[c]);
    for (int r = 0; r < 3; ++r)
    {
      a->InsertNextValue(values[r][c]);
    }
    table->AddColumn(a);
  }
  return table;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTable> MakeMetrics()
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkIntArray> it;
  it->SetName("Iteration");
  vtkNew<vtkDoubleArray> psnr, ssim, lpips, count;
  psnr->SetName("PSNR");
  ssim->SetName("SSIM");
  lpips->SetName("LPIPS");
  count->SetName("NumGaussians");
  for (int k = 0; k <= 6; ++k)
  {
    it->InsertNextValue(500 * k);
    psnr->InsertNextValue(18.0 + 10.0 * (1.0 - std::exp(-0.6 * k)));
    ssim->InsertNextValue(0.5 + 0.4 * (1.0 - std::exp(-0.5 * k)));
    lpips->InsertNextValue(std::numeric_limits<double>::quiet_NaN());
    count->InsertNextValue(k == 0 ? 3 : (k < 3 ? 5 : 6));
  }
  table->AddColumn(it);
  table->AddColumn(psnr);
  table->AddColumn(ssim);
  table->AddColumn(lpips);
  table->AddColumn(count);
  return table;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> MakeScene()
{
  auto scene = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("GaussianId");
  vtkNew<vtkFloatArray> opacity, scale;
  opacity->SetName("Opacity");
  scale->SetName("Scale");
  scale->SetNumberOfComponents(3);
  for (int id = 0; id < 8; ++id)
  {
    points->InsertNextPoint(std::cos(id * 0.8), std::sin(id * 0.8), 0.1 * id);
    ids->InsertNextValue(id);
    opacity->InsertNextValue(static_cast<float>(id / 10.0 + 0.05));
    scale->InsertNextTuple3(0.01 * (id + 1), 0.02, 0.005);
  }
  scene->SetPoints(points);
  scene->GetPointData()->SetPedigreeIds(ids);
  scene->GetPointData()->AddArray(opacity);
  scene->GetPointData()->AddArray(scale);
  return scene;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTable> MakeHistory()
{
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkIntArray> it;
  it->SetName("Iteration");
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("GaussianId");
  vtkNew<vtkFloatArray> opacity;
  opacity->SetName("Opacity");
  for (int t = 0; t <= 3000; t += 1000)
  {
    for (int id = 0; id < 8; ++id)
    {
      it->InsertNextValue(t);
      ids->InsertNextValue(id);
      opacity->InsertNextValue(static_cast<float>(0.1 + 0.1 * id + 0.05 * t / 1000.0));
    }
  }
  table->AddColumn(it);
  table->AddColumn(ids);
  table->AddColumn(opacity);
  return table;
}

//------------------------------------------------------------------------------
bool WriteSelectionImages(vtkRenderWindow* window, vtkGaussianSelectionHub* hub, const char* name)
{
  auto write = [window](const std::string& path)
  {
    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    vtkNew<vtkPNGWriter> writer;
    writer->SetInputConnection(grab->GetOutputPort());
    writer->SetFileName(path.c_str());
    writer->Write();
    return writer->GetErrorCode() == 0;
  };
  bool ok = write(std::string(name) + "-selected.png");
  hub->ClearSelection();
  window->Render();
  ok = write(std::string(name) + "-unselected.png") && ok;
  return ok;
}
}

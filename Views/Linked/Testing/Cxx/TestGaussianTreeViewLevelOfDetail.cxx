// SPDX-License-Identifier: BSD-3-Clause
// Tree view level of detail (DESIGN §4) against a brute-force reference on a random tree of
// 20,000 nodes: visible = (P >= tau(z) or in the selected lineage) and inside the viewport,
// for several zooms, viewports and selections; the zoom mapping; pan/zoom; then a regression
// image of the hand-built genealogy with a selected lineage, the cursor and the legend (and
// the same without the selection, for the masked comparison's negative test).
#include "LinkedViewsTestData.h"

#include "vtkGaussianSelectionHub.h"
#include "vtkGaussianTreeItem.h"
#include "vtkGaussianTreeView.h"

#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkMath.h"
#include "vtkMutableDirectedGraph.h"
#include "vtkNew.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <set>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "ERROR: check failed: " << what << "\n";
    ++failures;
  }
}

// tau(z) written out independently of Core (DESIGN §4).
double Tau(double z)
{
  z = std::min(2.0, std::max(0.1, z));
  return std::pow(1.0 - (z - 0.1) / 1.9, 1.2);
}

struct RandomTree
{
  vtkSmartPointer<vtkTree> Tree;
  std::vector<int> Parent, Birth, End;
  std::vector<double> Row, P;
};

RandomTree MakeRandomTree(int n)
{
  RandomTree t;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  vtkNew<vtkMutableDirectedGraph> g;
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("GaussianId");
  vtkNew<vtkIntArray> x, death;
  x->SetName("LayoutX");
  death->SetName("DeathIteration");
  vtkNew<vtkDoubleArray> y, p;
  y->SetName("LayoutY");
  p->SetName("PerceptionValue");
  vtkNew<vtkUnsignedCharArray> kind;
  kind->SetName("BirthKind");
  g->AddVertex(); // virtual root
  ids->InsertNextValue(-1);
  x->InsertNextValue(0);
  death->InsertNextValue(-1);
  y->InsertNextValue(-1);
  p->InsertNextValue(-1);
  kind->InsertNextValue(0);
  t.Parent.push_back(-1);
  t.Birth.push_back(0);
  t.End.push_back(0);
  t.Row.push_back(-1);
  t.P.push_back(-1);
  // Rows: a random permutation; P: quantised to many ties and exact 1.0 values.
  std::vector<int> rows(n);
  for (int i = 0; i < n; ++i)
  {
    rows[i] = i;
  }
  std::shuffle(rows.begin(), rows.end(), rng);
  for (int i = 1; i <= n; ++i)
  {
    const bool root = i <= 50;
    const int parent = root ? 0 : 1 + static_cast<int>(u(rng) * (i - 1));
    g->AddChild(parent);
    const int birth = root ? 0 : std::max(t.Birth[parent], static_cast<int>(u(rng) * 15000));
    const int d = u(rng) < 0.5 ? -1 : birth + static_cast<int>(u(rng) * 10000);
    const double pv = root ? 1.0 : std::floor(u(rng) * 1000.0) / 1000.0;
    ids->InsertNextValue(1000 + 3 * i); // sparse-ish, increasing
    x->InsertNextValue(birth);
    death->InsertNextValue(d);
    y->InsertNextValue(rows[i - 1]);
    p->InsertNextValue(pv);
    kind->InsertNextValue(root ? 0 : static_cast<unsigned char>(1 + (i % 2)));
    t.Parent.push_back(parent);
    t.Birth.push_back(birth);
    t.End.push_back(d < 0 ? 30000 : d);
    t.Row.push_back(rows[i - 1]);
    t.P.push_back(pv);
  }
  for (vtkAbstractArray* a : std::vector<vtkAbstractArray*>{ x, death, y, p, kind })
  {
    g->GetVertexData()->AddArray(a);
  }
  g->GetVertexData()->SetPedigreeIds(ids);
  vtkNew<vtkIntArray> last;
  last->SetName("LastIteration");
  last->InsertNextValue(30000);
  g->GetFieldData()->AddArray(last);
  t.Tree = vtkSmartPointer<vtkTree>::New();
  t.Tree->CheckedShallowCopy(g);
  return t;
}

std::vector<vtkIdType> BruteForce(const RandomTree& t,
  double tau,
  const std::vector<vtkIdType>& selected,
  const double vp[4])
{
  const int n = static_cast<int>(t.Parent.size());
  std::vector<char> lineage(n, 0);
  for (vtkIdType s : selected)
  {
    for (int a = static_cast<int>(s); a > 0; a = t.Parent[a])
    {
      lineage[a] = 1;
    }
  }
  // Descendants: a node is in the lineage if any ancestor-or-self is selected.
  std::set<vtkIdType> sel(selected.begin(), selected.end());
  for (int v = 1; v < n; ++v)
  {
    for (int a = v; a > 0; a = t.Parent[a])
    {
      if (sel.count(a))
      {
        lineage[v] = 1;
        break;
      }
    }
  }
  std::vector<vtkIdType> out;
  for (int v = 1; v < n; ++v)
  {
    const bool inView =
      t.Row[v] >= vp[2] && t.Row[v] <= vp[3] && t.Birth[v] <= vp[1] && t.End[v] >= vp[0];
    if (inView && (t.P[v] >= tau || lineage[v]))
    {
      out.push_back(v);
    }
  }
  return out;
}
}

int TestGaussianTreeViewLevelOfDetail(int argc, char* argv[])
{
  // --- Level of detail against brute force.
  const int n = 20000;
  RandomTree t = MakeRandomTree(n);
  vtkNew<vtkGaussianSelectionHub> hub;
  hub->RenderOnChangeOff();
  vtkNew<vtkGaussianTreeItem> item;
  item->SetTree(t.Tree);
  item->SetSelectionHub(hub);
  Check(std::abs(item->GetZoom() - 0.1) < 1e-12, "fit-all is z = zmin");
  Check(std::abs(item->GetZoomThreshold() - 1.0) < 1e-12, "tau(zmin) = 1");
  for (double z : { 0.1, 0.5, 1.0, 1.5, 2.0 })
  {
    item->SetZoom(z);
    Check(std::abs(item->GetZoom() - z) < 1e-9, "SetZoom/GetZoom round trip");
    Check(std::abs(item->GetZoomThreshold() - Tau(z)) < 1e-12, "tau(z) as DESIGN §4");
  }
  vtkNew<vtkIdTypeArray> got;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> pick(1, n);
  for (int trial = 0; trial < 12; ++trial)
  {
    item->ResetViewport();
    const double z = 0.1 + 1.9 * (trial % 4) / 3.0;
    item->SetZoom(z);
    if (trial % 3 == 1)
    {
      item->Pan(3000.0, 1500.0);
    }
    if (trial % 3 == 2)
    {
      item->ZoomIterations(3.0, 5000.0);
    }
    std::vector<vtkIdType> ids;
    std::vector<vtkIdType> selected;
    for (int k = 0; k < trial % 4; ++k)
    {
      const int v = pick(rng);
      selected.push_back(v);
      ids.push_back(1000 + 3 * v);
    }
    hub->SelectIds(ids.data(), static_cast<vtkIdType>(ids.size()));
    item->UpdateLevelOfDetail();
    item->GetVisibleVertices(got);
    double vp[4];
    item->GetViewport(vp);
    const auto expected = BruteForce(t, Tau(item->GetZoom()), selected, vp);
    const std::vector<vtkIdType> actual(
      got->GetPointer(0), got->GetPointer(0) + got->GetNumberOfTuples());
    Check(actual == expected,
      "LOD trial " + std::to_string(trial) + ": " + std::to_string(actual.size()) + " vs " +
        std::to_string(expected.size()) + " expected");
    Check(item->GetLastLevelOfDetailWork() <= n + static_cast<vtkIdType>(expected.size()),
      "LOD work bounded");
  }
  // At fit-all only P >= 1 shows: the 50 roots.
  hub->ClearSelection();
  item->ResetViewport();
  Check(item->UpdateLevelOfDetail() == 50, "fit-all shows the 50 P = 1 roots");
  Check(item->GetLastLevelOfDetailWork() <= 60, "fit-all scans only the P prefix");
  // Pan and zoom keep the row span.
  double before[4], after[4];
  item->GetViewport(before);
  item->ZoomRows(4.0, 0.5 * (before[2] + before[3]));
  item->GetViewport(after);
  Check(std::abs((after[3] - after[2]) * 4.0 - (before[3] - before[2])) < 1e-6, "zoom rows x4");
  item->Pan(0, 100);
  double panned[4];
  item->GetViewport(panned);
  Check(std::abs(panned[2] - after[2] - 100) < 1e-9, "pan rows");

  // --- Image: the hand-built genealogy, Gaussian 5 selected, cursor at 1500.
  vtkNew<vtkGaussianSelectionHub> hub2;
  vtkNew<vtkGaussianTreeView> view;
  view->SetTree(linkedtest::MakeTree());
  view->SetFamilyBands(linkedtest::MakeBands());
  view->SetSelectionHub(hub2);
  view->GetRenderWindow()->SetSize(420, 260);
  view->GetRenderWindow()->SetMultiSamples(0);
  const vtkIdType floater = 5;
  hub2->SelectIds(&floater, 1);
  hub2->SetIteration(1500);
  view->Render();
  int retVal = vtkRegressionTestImage(view->GetRenderWindow());
  if (retVal == vtkRegressionTester::DO_INTERACTOR)
  {
    retVal = vtkRegressionTester::PASSED;
  }
  Check(linkedtest::WriteSelectionImages(
          view->GetRenderWindow(), hub2, "TestGaussianTreeViewLevelOfDetail"),
    "the pictures with and without the selection are written");
  hub2->RemoveAllViews();
  return (failures == 0 && retVal == vtkRegressionTester::PASSED) ? 0 : 1;
}

// vtkGaussianGenealogyTreeFilter: hand-computed arrays and structure, bands, naive
// construction identical, field-data parameters, bad input as errors, a 10k-deep chain.
#include "vtkGaussianGenealogyTreeFilter.h"

#include "GenealogyTestHelpers.h"

#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkTree.h"

#include <cmath>

namespace
{
vtkDataArray* VArray(vtkTree* t, const char* name)
{
  return vtkDataArray::SafeDownCast(t->GetVertexData()->GetAbstractArray(name));
}
} // namespace

int TestGaussianGenealogyTreeFilter(int, char*[])
{
  int failures = 0;
  auto table = EventsTable(HandEvents());
  vtkNew<vtkGaussianGenealogyTreeFilter> filter;
  filter->SetInputData(table);
  filter->SetNumberOfInitialGaussians(2);
  filter->SetLastIteration(1000);
  filter->Update();
  vtkTree* tree = filter->GetOutput();
  GT_CHECK(tree->GetNumberOfVertices() == 9);
  GT_CHECK(tree->GetNumberOfEdges() == 8);
  GT_CHECK(tree->GetRoot() == 0);
  // Node i is vertex i + 1 (node = GaussianId here).
  const double birth[8] = { 0, 0, 100, 200, 200, 300, 600, 600 };
  const double death[8] = { 200, 500, -1, -1, 400, 600, -1, -1 };
  const double kind[8] = { 0, 0, 1, 2, 2, 1, 2, 2 };
  const double pruned[8] = { 0, 1, 0, 0, 1, 0, 0, 0 };
  const double family[8] = { 0, 1, 0, 0, 0, 0, 0, 0 };
  const double d[8] = { 6, 0, 0, 3, 0, 2, 0, 0 };
  const double t[8] = { 200, 500, 900, 800, 200, 300, 400, 400 };
  const double row[8] = { 0, 7, 1, 2, 6, 3, 4, 5 };
  const double p[8] = { 0.4 + 0.6 * 200.0 / 900.0,
    0.6,
    0.6,
    0.4 * 3.0 / 6.0 + 0.6 * 800.0 / 900.0,
    0.6 * 200.0 / 900.0,
    0.4 * 2.0 / 6.0 + 0.6 * 300.0 / 900.0,
    0.6 * 400.0 / 900.0,
    0.6 * 400.0 / 900.0 };
  const vtkIdType parentVertex[8] = { 0, 0, 1, 1, 1, 4, 6, 6 };
  for (vtkIdType i = 0; i < 8; ++i)
  {
    const vtkIdType v = i + 1;
    GT_CHECK(VArray(tree, "GaussianId")->GetComponent(v, 0) == i);
    GT_CHECK(VArray(tree, "BirthIteration")->GetComponent(v, 0) == birth[i]);
    GT_CHECK(VArray(tree, "DeathIteration")->GetComponent(v, 0) == death[i]);
    GT_CHECK(VArray(tree, "BirthKind")->GetComponent(v, 0) == kind[i]);
    GT_CHECK(VArray(tree, "Pruned")->GetComponent(v, 0) == pruned[i]);
    GT_CHECK(VArray(tree, "FamilyId")->GetComponent(v, 0) == family[i]);
    GT_CHECK(VArray(tree, "DescendantCount")->GetComponent(v, 0) == d[i]);
    GT_CHECK(VArray(tree, "Lifespan")->GetComponent(v, 0) == t[i]);
    GT_CHECK(std::abs(VArray(tree, "PerceptionValue")->GetComponent(v, 0) - p[i]) < 1e-15);
    GT_CHECK(VArray(tree, "LayoutX")->GetComponent(v, 0) == birth[i]);
    GT_CHECK(VArray(tree, "LayoutY")->GetComponent(v, 0) == row[i]);
    GT_CHECK(tree->GetParent(v) == parentVertex[i]);
    // Edge i enters vertex i + 1 and carries the birth kind (255 for the virtual root).
    GT_CHECK(tree->GetTargetVertex(i) == v);
    const double edgeKind =
      vtkDataArray::SafeDownCast(tree->GetEdgeData()->GetAbstractArray("EventKind"))
        ->GetComponent(i, 0);
    GT_CHECK(edgeKind == (kind[i] == 0 ? 255 : kind[i]));
  }
  GT_CHECK(tree->GetVertexData()->GetPedigreeIds() == VArray(tree, "GaussianId"));
  GT_CHECK(VArray(tree, "BirthKind")->GetComponent(0, 0) == 255);
  GT_CHECK(VArray(tree, "GaussianId")->GetComponent(0, 0) == -1);
  // Children in creation order.
  GT_CHECK(tree->GetNumberOfChildren(1) == 3);
  GT_CHECK(tree->GetChild(1, 0) == 3 && tree->GetChild(1, 1) == 4 && tree->GetChild(1, 2) == 5);
  GT_CHECK(vtkDataArray::SafeDownCast(tree->GetFieldData()->GetAbstractArray("LastIteration"))
             ->GetComponent(0, 0) == 1000);

  vtkTable* bands = filter->GetFamilyBands();
  GT_CHECK(bands->GetNumberOfRows() == 2);
  GT_CHECK(bands->GetValueByName(0, "MinRow").ToInt() == 0);
  GT_CHECK(bands->GetValueByName(0, "MaxRow").ToInt() == 6);
  GT_CHECK(bands->GetValueByName(0, "MaxIteration").ToInt() == 1000);
  GT_CHECK(bands->GetValueByName(0, "RootVertex").ToInt() == 1);
  GT_CHECK(bands->GetValueByName(1, "MinRow").ToInt() == 7);
  GT_CHECK(bands->GetValueByName(1, "MaxIteration").ToInt() == 500);
  GT_CHECK(bands->GetValueByName(1, "NodeCount").ToInt() == 1);

  // The naive construction gives the same tree.
  vtkNew<vtkGaussianGenealogyTreeFilter> naive;
  naive->SetInputData(table);
  naive->SetNumberOfInitialGaussians(2);
  naive->SetLastIteration(1000);
  naive->NaiveConstructionOn();
  naive->Update();
  vtkTree* other = naive->GetOutput();
  GT_CHECK(other->GetNumberOfVertices() == tree->GetNumberOfVertices());
  for (vtkIdType v = 1; v < tree->GetNumberOfVertices(); ++v)
  {
    GT_CHECK(other->GetParent(v) == tree->GetParent(v));
    GT_CHECK(VArray(other, "LayoutY")->GetComponent(v, 0) == row[v - 1]);
  }

  // Parameters from field data; coarsening.
  auto withFieldData = EventsTable(HandEvents());
  vtkNew<vtkIdTypeArray> n0;
  n0->SetName("NumberOfInitialGaussians");
  n0->InsertNextValue(2);
  withFieldData->GetFieldData()->AddArray(n0);
  vtkNew<vtkIntArray> last;
  last->SetName("LastIteration");
  last->InsertNextValue(2000);
  withFieldData->GetFieldData()->AddArray(last);
  vtkNew<vtkGaussianGenealogyTreeFilter> fromFieldData;
  fromFieldData->SetInputData(withFieldData);
  fromFieldData->SetCoarsenInterval(500);
  fromFieldData->Update();
  GT_CHECK(fromFieldData->GetOutput()->GetNumberOfVertices() == 9);
  GT_CHECK(VArray(fromFieldData->GetOutput(), "Lifespan")->GetComponent(4, 0) == 1500);

  // Bad input: unknown parent -> error, no crash; repair -> orphan root + warning.
  vis4gs::EventTable bad = HandEvents();
  AddEvent(bad, 700, 1, 77, 8);
  auto badTable = EventsTable(bad);
  vtkNew<GenealogyMessageObserver> observer;
  vtkNew<vtkGaussianGenealogyTreeFilter> badFilter;
  badFilter->AddObserver(vtkCommand::ErrorEvent, observer);
  badFilter->AddObserver(vtkCommand::WarningEvent, observer);
  badFilter->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  badFilter->SetInputData(badTable);
  badFilter->SetNumberOfInitialGaussians(2);
  badFilter->Update();
  GT_CHECK(observer->Errors.find("event row 8 (iteration 700, clone): unknown parent "
                                 "GaussianId 77") != std::string::npos);
  GT_CHECK(badFilter->GetOutput()->GetNumberOfVertices() == 0);
  observer->Errors.clear();
  badFilter->RepairUnknownParentsOn();
  badFilter->Update();
  GT_CHECK(observer->Errors.empty());
  GT_CHECK(observer->Warnings.find("orphan root created") != std::string::npos);
  GT_CHECK(badFilter->GetOutput()->GetNumberOfVertices() == 11);
  // Missing columns and initial Gaussians.
  vtkNew<vtkTable> empty;
  badFilter->SetInputData(empty);
  observer->Errors.clear();
  badFilter->Update();
  GT_CHECK(observer->Errors.find("lacks the numeric column(s) Iteration Kind Parent Child") !=
    std::string::npos);
  vtkNew<vtkGaussianGenealogyTreeFilter> noInitial;
  noInitial->AddObserver(vtkCommand::ErrorEvent, observer);
  noInitial->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  noInitial->SetInputData(table);
  observer->Errors.clear();
  noInitial->Update();
  GT_CHECK(observer->Errors.find("no initial Gaussians") != std::string::npos);

  // A chain of 10,000 generations and a family of 100,000 children.
  vis4gs::EventTable chain;
  for (std::int64_t k = 0; k < 10000; ++k)
  {
    AddEvent(chain, static_cast<std::int32_t>(k + 1), 2, k, k + 1);
  }
  for (std::int64_t k = 0; k < 100000; ++k)
  {
    AddEvent(chain, 10001, 1, 10000, 10001 + k);
  }
  vtkNew<vtkGaussianGenealogyTreeFilter> deep;
  deep->SetInputData(EventsTable(chain));
  deep->SetNumberOfInitialGaussians(1);
  deep->Update();
  vtkTree* deepTree = deep->GetOutput();
  GT_CHECK(deepTree->GetNumberOfVertices() == 110002);
  GT_CHECK(deepTree->GetLevel(10001) == 10001);
  GT_CHECK(deepTree->GetNumberOfChildren(10001) == 100000);
  GT_CHECK(VArray(deepTree, "DescendantCount")->GetComponent(1, 0) == 110000);
  GT_CHECK(VArray(deepTree, "LayoutY")->GetComponent(110001, 0) == 110000);

  std::cout << "TestGaussianGenealogyTreeFilter: " << failures << " failure(s); fast tree "
            << filter->GetTreeSeconds() << " s" << std::endl;
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

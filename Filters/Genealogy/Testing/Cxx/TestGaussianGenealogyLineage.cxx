// vtkGaussianGenealogyLineage on the hand-computed log: lineage queries by GaussianId and the
// root-cause trace with per-snapshot values.
#include "vtkGaussianGenealogyLineage.h"
#include "vtkGaussianGenealogyTreeFilter.h"

#include "GenealogyTestHelpers.h"

#include "vtkDoubleArray.h"
#include "vtkTree.h"

#include <cmath>
#include <vector>

namespace
{
std::vector<vtkIdType> Values(vtkIdTypeArray* a)
{
  return std::vector<vtkIdType>(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfTuples());
}
vtkSmartPointer<vtkIdTypeArray> Ids(std::initializer_list<vtkIdType> l)
{
  auto a = vtkSmartPointer<vtkIdTypeArray>::New();
  for (vtkIdType v : l)
  {
    a->InsertNextValue(v);
  }
  return a;
}
} // namespace

int TestGaussianGenealogyLineage(int, char*[])
{
  int failures = 0;
  vtkNew<vtkGaussianGenealogyTreeFilter> filter;
  filter->SetInputData(EventsTable(HandEvents()));
  filter->SetNumberOfInitialGaussians(2);
  filter->SetLastIteration(1000);
  filter->Update();

  vtkNew<vtkGaussianGenealogyLineage> lineage;
  vtkNew<vtkIdTypeArray> result;
  vtkNew<GenealogyMessageObserver> observer;
  lineage->AddObserver(vtkCommand::ErrorEvent, observer);
  GT_CHECK(!lineage->GetAncestors(Ids({ 6 }), result)); // no tree yet
  GT_CHECK(observer->Errors.find("no tree") != std::string::npos);
  lineage->SetTree(filter->GetOutput());
  GT_CHECK(lineage->GetAncestors(Ids({ 6 }), result));
  GT_CHECK((Values(result) == std::vector<vtkIdType>{ 0, 3, 5 }));
  GT_CHECK(lineage->GetDescendants(Ids({ 3 }), result));
  GT_CHECK((Values(result) == std::vector<vtkIdType>{ 5, 6, 7 }));
  GT_CHECK(lineage->GetLineage(Ids({ 5, 99 }), result));
  GT_CHECK((Values(result) == std::vector<vtkIdType>{ 0, 3, 5, 6, 7 }));
  GT_CHECK(lineage->GetNumberOfUnknownIds() == 1);
  GT_CHECK(lineage->GetFamily(Ids({ 4 }), result));
  GT_CHECK((Values(result) == std::vector<vtkIdType>{ 0, 2, 3, 4, 5, 6, 7 }));

  // Trace: snapshots 0, 250, 700 hold a value 10000 * id + iteration for every Gaussian.
  for (int s : { 0, 250, 700 })
  {
    vtkNew<vtkIdTypeArray> ids;
    vtkNew<vtkDoubleArray> values;
    for (vtkIdType id = 7; id >= 0; --id) // unsorted on purpose
    {
      ids->InsertNextValue(id);
      values->InsertNextValue(10000.0 * id + s);
    }
    lineage->AddSnapshotValues(s, ids, values);
  }
  vtkNew<vtkTable> trace;
  GT_CHECK(lineage->TraceToRoot(6, trace));
  GT_CHECK(trace->GetNumberOfRows() == 4);
  if (trace->GetNumberOfRows() == 4)
  {
    const vtkIdType id[4] = { 6, 5, 3, 0 };
    const int snapshot[4] = { 700, -1, 250, 0 };
    for (vtkIdType r = 0; r < 4; ++r)
    {
      GT_CHECK(trace->GetValueByName(r, "GaussianId").ToLongLong() == id[r]);
      GT_CHECK(trace->GetValueByName(r, "Vertex").ToLongLong() == id[r] + 1);
      GT_CHECK(trace->GetValueByName(r, "SnapshotIteration").ToInt() == snapshot[r]);
      const double value = trace->GetValueByName(r, "Value").ToDouble();
      GT_CHECK(snapshot[r] < 0 ? std::isnan(value) : value == 10000.0 * id[r] + snapshot[r]);
    }
  }
  observer->Errors.clear();
  GT_CHECK(!lineage->TraceToRoot(42, trace));
  GT_CHECK(observer->Errors.find("GaussianId 42 is not in the tree") != std::string::npos);

  std::cout << "TestGaussianGenealogyLineage: " << failures << " failure(s)" << std::endl;
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

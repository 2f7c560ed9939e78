// vtkGaussianGenealogyTraceFilter on the hand-computed log: the chain 6 -> 5 -> 3 -> 0 derived
// by hand from HandEvents(), the same rows as vtkGaussianGenealogyLineage::TraceToRoot, no
// rows before a Gaussian is asked for, and an error for an unknown one.
#include "vtkGaussianGenealogyLineage.h"
#include "vtkGaussianGenealogyTraceFilter.h"
#include "vtkGaussianGenealogyTreeFilter.h"

#include "GenealogyTestHelpers.h"

#include "vtkExecutive.h"
#include "vtkTree.h"

#include <cmath>
#include <sstream>

int TestGaussianGenealogyTraceFilter(int, char*[])
{
  int failures = 0;
  vtkNew<vtkGaussianGenealogyTreeFilter> tree;
  tree->SetInputData(EventsTable(HandEvents()));
  tree->SetNumberOfInitialGaussians(2);
  tree->SetLastIteration(1000);

  vtkNew<vtkGaussianGenealogyTraceFilter> trace;
  trace->SetInputConnection(tree->GetOutputPort());
  trace->Update();
  GT_CHECK(trace->GetOutput()->GetNumberOfRows() == 0); // GaussianId -1: nothing asked

  trace->SetGaussianId(6);
  trace->Update();
  vtkTable* rows = trace->GetOutput();
  GT_CHECK(rows->GetNumberOfRows() == 4);
  vtkNew<vtkGaussianGenealogyLineage> lineage;
  lineage->SetTree(tree->GetOutput());
  vtkNew<vtkTable> direct;
  GT_CHECK(lineage->TraceToRoot(6, direct));
  GT_CHECK(direct->GetNumberOfRows() == rows->GetNumberOfRows() &&
    direct->GetNumberOfColumns() == rows->GetNumberOfColumns());
  const vtkIdType id[4] = { 6, 5, 3, 0 };
  for (vtkIdType r = 0; r < rows->GetNumberOfRows() && r < 4; ++r)
  {
    GT_CHECK(rows->GetValueByName(r, "GaussianId").ToLongLong() == id[r]);
    GT_CHECK(rows->GetValueByName(r, "SnapshotIteration").ToInt() == -1);
    GT_CHECK(std::isnan(rows->GetValueByName(r, "Value").ToDouble()));
    for (vtkIdType c = 0; c < rows->GetNumberOfColumns(); ++c)
    {
      const vtkVariant a = rows->GetValue(r, c), b = direct->GetValue(r, c);
      GT_CHECK(a.ToString() == b.ToString());
    }
  }

  vtkNew<GenealogyMessageObserver> observer;
  trace->AddObserver(vtkCommand::ErrorEvent, observer);
  trace->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, observer);
  lineage->AddObserver(vtkCommand::ErrorEvent, observer);
  trace->SetGaussianId(42);
  trace->Update();
  GT_CHECK(observer->Errors.find("no trace of GaussianId 42") != std::string::npos);

  std::ostringstream printed;
  trace->Print(printed);
  GT_CHECK(printed.str().find("GaussianId: 42") != std::string::npos);

  std::cout << "TestGaussianGenealogyTraceFilter: " << failures << " failure(s)" << std::endl;
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

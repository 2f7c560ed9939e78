// vtkGaussianTreeLevelOfDetail against the Core brute-force filter on a synthetic log:
// visible vertices (port 1), the contracted visible subtree (port 0), selections (port 1
// input, pedigree ids and vertex indices), viewport, caching of the index.
#include "vtkGaussianGenealogyTreeFilter.h"
#include "vtkGaussianTreeLevelOfDetail.h"

#include "GenealogyTestHelpers.h"

#include "GenealogyLevelOfDetail.h"
#include "SyntheticEventLog.h"

#include "vtkDataSetAttributes.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTree.h"

#include <algorithm>

int TestGaussianTreeLevelOfDetail(int, char*[])
{
  int failures = 0;
  vis4gs::SyntheticLogParameters prm;
  prm.InitialGaussians = 50;
  prm.FinalGaussians = 5000;
  prm.TotalGaussians = 10000;
  prm.Seed = 3;
  const auto log = vis4gs::GenerateSyntheticEventLog(prm);
  const auto core = vis4gs::Genealogy::Build(log.InitialGaussians, log.Events, log.LastIteration);
  const vis4gs::GenealogyLevelOfDetail reference(core);

  vtkNew<vtkGaussianGenealogyTreeFilter> treeFilter;
  treeFilter->SetInputData(EventsTable(log.Events));
  treeFilter->SetNumberOfInitialGaussians(log.InitialGaussians);
  treeFilter->SetLastIteration(log.LastIteration);

  vtkNew<vtkSelection> selection;
  vtkNew<vtkSelectionNode> selNode;
  selNode->SetContentType(vtkSelectionNode::PEDIGREEIDS);
  selNode->SetFieldType(vtkSelectionNode::VERTEX);
  vtkNew<vtkIdTypeArray> selIds;
  selNode->SetSelectionList(selIds);
  selection->AddNode(selNode);

  vtkNew<vtkGaussianTreeLevelOfDetail> lod;
  lod->SetInputConnection(treeFilter->GetOutputPort());
  lod->SetInputData(1, selection);

  const double zooms[] = { 0.1, 0.6, 1.0, 1.4, 1.8, 2.0 };
  int run = 0;
  for (double z : zooms)
  {
    for (int variant = 0; variant < 3; ++variant, ++run)
    {
      std::vector<std::int64_t> selected;
      selIds->Reset();
      if (variant >= 1)
      {
        for (std::int64_t node : { std::int64_t(17), std::int64_t(4321), std::int64_t(9000) })
        {
          selected.push_back(node);
          selIds->InsertNextValue(core.GetGaussianIds()[node]);
        }
        selIds->Modified();
      }
      vis4gs::GenealogyViewport v;
      if (variant == 2)
      {
        v.MinRow = 1000;
        v.MaxRow = 6000;
        v.MinIteration = 3000;
        v.MaxIteration = 9000;
      }
      lod->SetRowRange(v.MinRow, v.MaxRow);
      lod->SetIterationRange(v.MinIteration, v.MaxIteration);
      lod->SetZoom(z);
      lod->Update();
      const std::vector<std::int64_t> expected =
        reference.QueryBruteForce(vis4gs::ZoomThreshold(z), selected, v);
      vtkSelection* visible = lod->GetVisibleSelection();
      vtkIdTypeArray* vertices =
        vtkIdTypeArray::SafeDownCast(visible->GetNode(0)->GetSelectionList());
      GT_CHECK(
        vertices && vertices->GetNumberOfTuples() == static_cast<vtkIdType>(expected.size()));
      if (!vertices || vertices->GetNumberOfTuples() != static_cast<vtkIdType>(expected.size()))
      {
        continue;
      }
      for (std::size_t k = 0; k < expected.size(); ++k)
      {
        GT_CHECK(vertices->GetValue(static_cast<vtkIdType>(k)) == expected[k] + 1);
      }
      GT_CHECK(lod->GetNumberOfVisibleVertices() == static_cast<vtkIdType>(expected.size()));
      GT_CHECK(run == 0 || lod->GetIndexSeconds() == 0.0); // index cached after the first run

      // Visible subtree: parent = nearest visible ancestor (or the virtual root).
      vtkTree* sub = lod->GetOutput();
      GT_CHECK(sub->GetNumberOfVertices() == static_cast<vtkIdType>(expected.size()) + 1);
      vtkIdTypeArray* inputVertex =
        vtkIdTypeArray::SafeDownCast(sub->GetVertexData()->GetAbstractArray("InputVertexId"));
      vtkDataArray* ids =
        vtkDataArray::SafeDownCast(sub->GetVertexData()->GetAbstractArray("GaussianId"));
      GT_CHECK(inputVertex && ids);
      if (!inputVertex || !ids)
      {
        continue;
      }
      for (vtkIdType w = 1; w < sub->GetNumberOfVertices(); ++w)
      {
        const std::int64_t node = inputVertex->GetValue(w) - 1;
        GT_CHECK(ids->GetComponent(w, 0) == core.GetGaussianIds()[node]);
        std::int64_t u = core.GetParents()[node];
        while (u >= 0 && !std::binary_search(expected.begin(), expected.end(), u))
        {
          u = core.GetParents()[u];
        }
        const vtkIdType p = sub->GetParent(w);
        GT_CHECK(u < 0 ? p == 0 : inputVertex->GetValue(p) == u + 1);
      }
    }
  }

  // Vertex-index selections select the same nodes as pedigree ids.
  selNode->SetContentType(vtkSelectionNode::INDICES);
  selIds->Reset();
  selIds->InsertNextValue(4322); // node 4321
  selIds->Modified();
  lod->SetZoom(0.1);
  lod->SetRowRange(VTK_ID_MIN, VTK_ID_MAX);
  lod->SetIterationRange(VTK_INT_MIN, VTK_INT_MAX);
  lod->Update();
  const auto expected = reference.QueryBruteForce(1.0, { 4321 });
  GT_CHECK(lod->GetNumberOfVisibleVertices() == static_cast<vtkIdType>(expected.size()));

  // Unknown ids are counted and warned about, not an error.
  vtkNew<GenealogyMessageObserver> observer;
  lod->AddObserver(vtkCommand::WarningEvent, observer);
  lod->AddObserver(vtkCommand::ErrorEvent, observer);
  selNode->SetContentType(vtkSelectionNode::PEDIGREEIDS);
  selIds->Reset();
  selIds->InsertNextValue(123456789);
  selIds->Modified();
  lod->Update();
  GT_CHECK(lod->GetNumberOfUnknownSelectedIds() == 1);
  GT_CHECK(observer->Errors.empty());
  GT_CHECK(observer->Warnings.find("not in the tree") != std::string::npos);

  std::cout << "TestGaussianTreeLevelOfDetail: " << failures << " failure(s)" << std::endl;
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

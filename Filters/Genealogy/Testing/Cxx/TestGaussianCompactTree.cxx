// vtkGaussianCompactTree against VTK's own vtkTree holding the same edges (the genealogy
// filter's default output on the SYNTHETIC log): every iterator of vtkGraph and vtkTree
// (out, in, adjacent, edge list, vertex list, depth- and breadth-first), GetChild, GetLevel,
// IsLeaf, GetParentEdge; shallow and deep copies keep the structure, copies from a plain
// tree fall back to vtkTree's lists; the structure takes 40 bytes per vertex (less than
// vtkTree's lists by GetActualMemorySize); inconsistent structures and ReorderChildren are
// refused; the filter switches its output type with CompactTree.
#include "vtkGaussianCompactTree.h"
#include "vtkGaussianGenealogyTreeFilter.h"

#include "GenealogyTestHelpers.h"
#include "SyntheticEventLog.h"

#include "vtkAdjacentVertexIterator.h"
#include "vtkDataSetAttributes.h"
#include "vtkEdgeListIterator.h"
#include "vtkGraphEdge.h"
#include "vtkInEdgeIterator.h"
#include "vtkOutEdgeIterator.h"
#include "vtkSmartPointer.h"
#include "vtkTreeBFSIterator.h"
#include "vtkTreeDFSIterator.h"
#include "vtkVertexListIterator.h"

#include <cmath>
#include <sstream>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <vector>

namespace
{
int failures = 0;

//------------------------------------------------------------------------------
/// Everything the iterators of @p t visit, as one flat list of ids.
std::vector<vtkIdType> Walk(vtkTree* t)
{
  std::vector<vtkIdType> out;
  vtkNew<vtkOutEdgeIterator> oit;
  vtkNew<vtkInEdgeIterator> iit;
  vtkNew<vtkAdjacentVertexIterator> ait;
  vtkNew<vtkGraphEdge> ge;
  for (vtkIdType v = 0; v < t->GetNumberOfVertices(); ++v)
  {
    t->GetOutEdges(v, oit);
    while (oit->HasNext())
    {
      const vtkOutEdgeType e = oit->Next();
      out.insert(out.end(), { e.Target, e.Id });
    }
    t->GetInEdges(v, iit);
    while (iit->HasNext())
    {
      const vtkInEdgeType e = iit->Next();
      out.insert(out.end(), { e.Source, e.Id });
    }
    t->GetChildren(v, ait);
    while (ait->HasNext())
    {
      out.push_back(ait->Next());
    }
    out.insert(out.end(),
      { t->GetLevel(v), t->IsLeaf(v) ? 1 : 0, t->GetNumberOfChildren(v), t->GetDegree(v) });
    if (v != t->GetRoot())
    {
      const vtkEdgeType pe = t->GetParentEdge(v);
      t->GetInEdge(v, 0, ge);
      out.insert(out.end(), { pe.Id, pe.Source, pe.Target, ge->GetId(), ge->GetSource() });
    }
    if (t->GetNumberOfChildren(v) > 0)
    {
      t->GetOutEdge(v, 0, ge);
      out.insert(out.end(), { t->GetChild(v, 0), ge->GetId(), ge->GetTarget() });
    }
  }
  vtkNew<vtkEdgeListIterator> eit;
  t->GetEdges(eit);
  while (eit->HasNext())
  {
    const vtkEdgeType e = eit->Next();
    out.insert(out.end(), { e.Source, e.Target, e.Id });
  }
  vtkNew<vtkVertexListIterator> vit;
  t->GetVertices(vit);
  while (vit->HasNext())
  {
    out.push_back(vit->Next());
  }
  vtkNew<vtkTreeDFSIterator> dfs;
  dfs->SetTree(t);
  dfs->SetMode(vtkTreeDFSIterator::FINISH);
  while (dfs->HasNext())
  {
    out.push_back(dfs->Next());
  }
  vtkNew<vtkTreeBFSIterator> bfs;
  bfs->SetTree(t);
  while (bfs->HasNext())
  {
    out.push_back(bfs->Next());
  }
  return out;
}
} // namespace

//------------------------------------------------------------------------------
int TestGaussianCompactTree(int, char*[])
{
  vis4gs::SyntheticLogParameters prm;
  prm.InitialGaussians = 300;
  prm.TotalGaussians = 12000;
  prm.FinalGaussians = 6000;
  const auto log = vis4gs::GenerateSyntheticEventLog(prm);
  auto events = EventsTable(log.Events);

  vtkNew<vtkGaussianGenealogyTreeFilter> filter;
  filter->SetInputData(events);
  filter->SetNumberOfInitialGaussians(log.InitialGaussians);
  filter->SetLastIteration(log.LastIteration);
  filter->Update();
  auto plain = vtkSmartPointer<vtkTree>::New();
  plain->DeepCopy(filter->GetOutput());
  GT_CHECK(vtkGaussianCompactTree::SafeDownCast(filter->GetOutput()) == nullptr);
  GT_CHECK(std::string(filter->GetOutput()->GetClassName()) == "vtkTree");

  filter->CompactTreeOn();
  filter->Update();
  vtkGaussianCompactTree* compact = vtkGaussianCompactTree::SafeDownCast(filter->GetOutput());
  GT_CHECK(compact != nullptr);
  if (!compact)
  {
    return EXIT_FAILURE;
  }
  const vtkIdType nv = prm.TotalGaussians + 1;
  GT_CHECK(compact->GetNumberOfVertices() == nv && compact->GetNumberOfEdges() == nv - 1);
  GT_CHECK(compact->GetRoot() == 0 && compact->GetInDegree(0) == 0);
  GT_CHECK(compact->GetVertexData()->GetNumberOfTuples() == nv);
  GT_CHECK(compact->GetEdgeData()->GetNumberOfTuples() == nv - 1);
  const std::vector<vtkIdType> expected = Walk(plain);
  GT_CHECK(expected.size() > static_cast<std::size_t>(10 * nv));
  GT_CHECK(Walk(compact) == expected);

  // Copies of the compact tree keep its structure; the filter's next run does not change them.
  vtkNew<vtkGaussianCompactTree> shallow, deep;
  shallow->ShallowCopy(compact);
  deep->DeepCopy(compact);
  GT_CHECK(Walk(shallow) == expected);
  GT_CHECK(Walk(deep) == expected);
  GT_CHECK(shallow->GetVertexData()->GetPedigreeIds() != nullptr);

  // A compact tree given a plain tree answers from vtkTree's own lists.
  vtkNew<vtkGaussianCompactTree> fromPlain;
  fromPlain->ShallowCopy(plain);
  GT_CHECK(Walk(fromPlain) == expected);
  vtkNew<vtkGaussianCompactTree> checkedCopy;
  GT_CHECK(checkedCopy->CheckedShallowCopy(plain));
  GT_CHECK(Walk(checkedCopy) == expected);
  checkedCopy->Initialize();
  GT_CHECK(checkedCopy->GetNumberOfVertices() == 0);

  // 40 bytes per vertex of structure (GetActualMemorySize counts it; vtkGraph counts none of
  // its adjacency lists), and the heap that each form keeps after the filter ran: vtkTree's
  // lists cost more than 40 bytes per vertex beyond the compact arrays.
  const double structureKiB =
    static_cast<double>(compact->GetActualMemorySize()) - plain->GetActualMemorySize();
  std::cout << "structure: " << structureKiB << " KiB for " << nv << " vertices\n";
  GT_CHECK(std::abs(structureKiB - 40.0 * nv / 1024) <= 2);
#ifdef __GLIBC__
  {
    auto kept = [&](bool compactTree)
    {
      vtkNew<vtkGaussianGenealogyTreeFilter> f;
      f->SetInputData(events);
      f->SetNumberOfInitialGaussians(log.InitialGaussians);
      f->SetLastIteration(log.LastIteration);
      f->SetCompactTree(compactTree);
      const struct mallinfo2 before = mallinfo2();
      f->Update();
      const struct mallinfo2 after = mallinfo2();
      return static_cast<double>(after.uordblks + after.hblkhd) -
        static_cast<double>(before.uordblks + before.hblkhd);
    };
    kept(true); // first allocations of the process out of the comparison
    const double heapPlain = kept(false), heapCompact = kept(true);
    std::cout << "heap kept per vertex: vtkTree " << heapPlain / nv << " B, compact "
              << heapCompact / nv << " B\n";
    GT_CHECK(heapPlain - heapCompact > 40.0 * nv);
  }
#endif

  // Refusals.
  vtkNew<GenealogyMessageObserver> messages;
  compact->AddObserver(vtkCommand::ErrorEvent, messages);
  vtkNew<vtkIdTypeArray> order;
  order->InsertNextValue(compact->GetChild(0, 1));
  order->InsertNextValue(compact->GetChild(0, 0));
  compact->ReorderChildren(0, order);
  GT_CHECK(messages->Errors.find("read-only") != std::string::npos);
  GT_CHECK(Walk(compact) == expected);
  vtkNew<vtkGaussianCompactTree> bad;
  bad->AddObserver(vtkCommand::ErrorEvent, messages);
  vtkGaussianCompactTree::Structure s;
  s.InEdges.resize(3);
  s.OutEdges.resize(1); // 3 vertices need 2 edges
  s.OutOffsets = { 0, 1, 1, 1 };
  GT_CHECK(!bad->SetStructure(std::move(s)));
  GT_CHECK(bad->GetNumberOfVertices() == 0);
  GT_CHECK(messages->Errors.find("inconsistent structure") != std::string::npos);
  compact->GetInDegree(nv); // out of range: an error, no crash
  GT_CHECK(messages->Errors.find("out of range") != std::string::npos);

  // Back to a plain vtkTree when the option is turned off again.
  filter->CompactTreeOff();
  filter->Update();
  GT_CHECK(vtkGaussianCompactTree::SafeDownCast(filter->GetOutput()) == nullptr);
  GT_CHECK(Walk(filter->GetOutput()) == expected);

  std::ostringstream print;
  shallow->PrintSelf(print, vtkIndent());
  GT_CHECK(print.str().find("Compact structure: yes") != std::string::npos);
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

// The fast vtkTree construction of vtkGaussianGenealogyTreeFilter (adjacency lists filled in
// parallel, the tree handed over as valid by construction) must give exactly the tree that
// VTK's own validation (ValidateStructure: vtkTree::CheckedShallowCopy's walk) and the naive
// vtkMutableDirectedGraph::AddChild construction give: same vertices, root, in- and out-edges
// with their ids and order, vertex and edge arrays, pedigree ids and field data. Cases: the
// hand log, a 10k-generation chain, a family with 100k children, many small families (the
// SYNTHETIC generator), initial Gaussians without events. Plus the adapter's checks on bad
// parent arrays (a parent after its child, a parent below -1) and the LOD filter's subtree
// (which uses the same builder) against the validated path. The compact output
// (CompactTree, vtkGaussianCompactTree) must answer every one of those queries like the
// plain vtkTree on every case.
#include "vtkGaussianCompactTree.h"
#include "vtkGaussianGenealogyAdapter.h"
#include "vtkGaussianGenealogyTreeFilter.h"
#include "vtkGaussianTreeLevelOfDetail.h"

#include "GenealogyTestHelpers.h"
#include "SyntheticEventLog.h"

#include "vtkAbstractArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkVariant.h"

#include <cstring>
#include <sstream>

namespace
{
int failures = 0;

//------------------------------------------------------------------------------
bool SameArrays(vtkFieldData* a, vtkFieldData* b, const char* what)
{
  if (a->GetNumberOfArrays() != b->GetNumberOfArrays())
  {
    std::cerr << what << ": " << a->GetNumberOfArrays() << " vs " << b->GetNumberOfArrays()
              << " arrays\n";
    return false;
  }
  for (int i = 0; i < a->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* x = a->GetAbstractArray(i);
    vtkAbstractArray* y = b->GetAbstractArray(x->GetName());
    if (!y || std::strcmp(x->GetClassName(), y->GetClassName()) != 0 ||
      x->GetNumberOfTuples() != y->GetNumberOfTuples() ||
      x->GetNumberOfComponents() != y->GetNumberOfComponents())
    {
      std::cerr << what << ": array " << x->GetName() << " differs in type or size\n";
      return false;
    }
    const vtkIdType values = x->GetNumberOfValues();
    if (values > 0 &&
      std::memcmp(x->GetVoidPointer(0),
        y->GetVoidPointer(0),
        static_cast<std::size_t>(values) * static_cast<std::size_t>(x->GetDataTypeSize())) != 0)
    {
      std::cerr << what << ": array " << x->GetName() << " differs in its values\n";
      return false;
    }
  }
  return true;
}

//------------------------------------------------------------------------------
/// Every structural property of two trees, plus their attributes.
bool SameTree(vtkTree* a, vtkTree* b, const std::string& what)
{
  if (a->GetNumberOfVertices() != b->GetNumberOfVertices() ||
    a->GetNumberOfEdges() != b->GetNumberOfEdges() || a->GetRoot() != b->GetRoot())
  {
    std::cerr << what << ": vertices " << a->GetNumberOfVertices() << " vs "
              << b->GetNumberOfVertices() << ", edges " << a->GetNumberOfEdges() << " vs "
              << b->GetNumberOfEdges() << ", root " << a->GetRoot() << " vs " << b->GetRoot()
              << "\n";
    return false;
  }
  for (vtkIdType v = 0; v < a->GetNumberOfVertices(); ++v)
  {
    const vtkIdType nia = a->GetInDegree(v), noa = a->GetOutDegree(v);
    bool same = nia == b->GetInDegree(v) && noa == b->GetOutDegree(v);
    for (vtkIdType e = 0; same && e < nia; ++e)
    {
      const vtkInEdgeType ia = a->GetInEdge(v, e), ib = b->GetInEdge(v, e);
      same = ia.Source == ib.Source && ia.Id == ib.Id;
    }
    for (vtkIdType e = 0; same && e < noa; ++e)
    {
      const vtkOutEdgeType oa = a->GetOutEdge(v, e), ob = b->GetOutEdge(v, e);
      same = oa.Target == ob.Target && oa.Id == ob.Id;
    }
    if (!same)
    {
      std::cerr << what << ": the edges of vertex " << v << " differ\n";
      return false;
    }
  }
  for (vtkIdType e = 0; e < a->GetNumberOfEdges(); ++e)
  {
    if (a->GetSourceVertex(e) != b->GetSourceVertex(e) ||
      a->GetTargetVertex(e) != b->GetTargetVertex(e))
    {
      std::cerr << what << ": edge " << e << " differs\n";
      return false;
    }
  }
  vtkAbstractArray* pa = a->GetVertexData()->GetPedigreeIds();
  vtkAbstractArray* pb = b->GetVertexData()->GetPedigreeIds();
  if (!pa || !pb || std::strcmp(pa->GetName(), pb->GetName()) != 0)
  {
    std::cerr << what << ": pedigree ids differ\n";
    return false;
  }
  return SameArrays(a->GetVertexData(), b->GetVertexData(), (what + " vertex data").c_str()) &&
    SameArrays(a->GetEdgeData(), b->GetEdgeData(), (what + " edge data").c_str()) &&
    SameArrays(a->GetFieldData(), b->GetFieldData(), (what + " field data").c_str());
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkTree> RunFilter(vtkTable* events,
  vtkIdType initial,
  int last,
  bool validate,
  bool naive,
  bool compact = false)
{
  vtkNew<vtkGaussianGenealogyTreeFilter> filter;
  filter->SetInputData(events);
  filter->SetNumberOfInitialGaussians(initial);
  filter->SetLastIteration(last);
  filter->SetValidateStructure(validate);
  filter->SetNaiveConstruction(naive);
  filter->SetCompactTree(compact);
  filter->Update();
  GT_CHECK((vtkGaussianCompactTree::SafeDownCast(filter->GetOutput()) != nullptr) == compact);
  vtkSmartPointer<vtkTree> tree;
  if (compact)
  {
    tree = vtkSmartPointer<vtkGaussianCompactTree>::New();
  }
  else
  {
    tree = vtkSmartPointer<vtkTree>::New();
  }
  tree->ShallowCopy(filter->GetOutput());
  return tree;
}

//------------------------------------------------------------------------------
/// Fast path vs validated vs naive on one log; returns the fast tree.
vtkSmartPointer<vtkTree> CompareAll(const vis4gs::EventTable& e,
  vtkIdType initial,
  int last,
  const std::string& what,
  vtkIdType expectedVertices,
  bool naive = true)
{
  auto table = EventsTable(e);
  auto fast = RunFilter(table, initial, last, false, false);
  auto checked = RunFilter(table, initial, last, true, false);
  GT_CHECK(fast->GetNumberOfVertices() == expectedVertices);
  GT_CHECK(fast->GetRoot() == 0);
  GT_CHECK(SameTree(fast, checked, what + " (fast vs validated)"));
  auto compact = RunFilter(table, initial, last, false, false, true);
  GT_CHECK(SameTree(checked, compact, what + " (validated vs compact)"));
  // The log's column types are read in place; other types through converted copies.
  {
    vis4gs::EventTable storage;
    vis4gs::EventColumns columns;
    std::string error;
    GT_CHECK(vtkGaussianGenealogyAdapter::EventsFromTable(table, storage, columns, error));
    GT_CHECK(columns.Size == e.Size() && storage.Size() == 0);
    GT_CHECK(
      e.Size() == 0 || columns.Parent == table->GetColumnByName("Parent")->GetVoidPointer(0));
    auto converted = vtkSmartPointer<vtkTable>::New();
    const char* names[4] = { "Iteration", "Kind", "Parent", "Child" };
    for (int c = 0; c < 4; ++c)
    {
      vtkNew<vtkDoubleArray> d;
      d->DeepCopy(vtkDataArray::SafeDownCast(table->GetColumnByName(names[c])));
      d->SetName(names[c]);
      converted->AddColumn(d);
    }
    GT_CHECK(vtkGaussianGenealogyAdapter::EventsFromTable(converted, storage, columns, error));
    GT_CHECK(columns.Size == e.Size() && storage.Size() == e.Size());
    GT_CHECK(e.Size() == 0 || columns.Parent == storage.Parent.data());
    auto fromCopies = RunFilter(converted, initial, last, false, false);
    GT_CHECK(SameTree(fast, fromCopies, what + " (columns read in place vs converted)"));
  }
  if (naive)
  {
    auto slow = RunFilter(table, initial, last, false, true);
    GT_CHECK(SameTree(fast, slow, what + " (fast vs naive)"));
  }
  return fast;
}
} // namespace

//------------------------------------------------------------------------------
int TestGaussianGenealogyTreeStructure(int, char*[])
{
  // The hand log: 2 initial Gaussians, 8 events, 8 nodes + the virtual root.
  CompareAll(HandEvents(), 2, 1000, "hand log", 9);

  // A chain 10k generations deep (each split ends its parent and starts one child).
  {
    vis4gs::EventTable e;
    for (int g = 0; g < 10000; ++g)
    {
      AddEvent(e, g + 1, 2, g, g + 1);
    }
    auto tree = CompareAll(e, 1, 20000, "10k-deep chain", 10002);
    GT_CHECK(tree->GetLevel(10001) == 10001);
    GT_CHECK(tree->GetParent(10001) == 10000);
    GT_CHECK(tree->GetNumberOfChildren(0) == 1);
  }

  // One family with 100k children (clones of the single root).
  {
    vis4gs::EventTable e;
    for (int c = 0; c < 100000; ++c)
    {
      AddEvent(e, 1 + c / 100, 1, 0, c + 1);
    }
    auto tree = CompareAll(e, 1, 5000, "100k children", 100002);
    GT_CHECK(tree->GetNumberOfChildren(1) == 100000);
    GT_CHECK(tree->GetChild(1, 0) == 2 && tree->GetChild(1, 99999) == 100001);
  }

  // Many families of realistic shape (SYNTHETIC generator, 20k nodes).
  {
    vis4gs::SyntheticLogParameters prm;
    prm.InitialGaussians = 500;
    prm.TotalGaussians = 20000;
    prm.FinalGaussians = 9800;
    const auto log = vis4gs::GenerateSyntheticEventLog(prm);
    auto tree = CompareAll(
      log.Events, log.InitialGaussians, log.LastIteration, "synthetic 20k", prm.TotalGaussians + 1);
    GT_CHECK(tree->GetNumberOfChildren(0) > 1);

    // The level-of-detail filter's visible subtree goes through the same builder.
    vtkNew<vtkGaussianTreeLevelOfDetail> lod;
    lod->SetInputData(tree);
    lod->SetZoom(0.8);
    lod->Update();
    vtkTree* sub = lod->GetOutput();
    GT_CHECK(sub->GetNumberOfVertices() > 1 && sub->GetNumberOfVertices() < 20001);
    GT_CHECK(sub->GetRoot() == 0);
    // Rebuild the same structure through VTK's validation and compare.
    std::vector<vtkIdType> parents(static_cast<std::size_t>(sub->GetNumberOfVertices() - 1));
    for (vtkIdType v = 1; v < sub->GetNumberOfVertices(); ++v)
    {
      parents[v - 1] = sub->GetParent(v) - 1;
    }
    vtkNew<vtkTree> checked;
    std::string error;
    GT_CHECK(vtkGaussianGenealogyAdapter::BuildStructure(
      parents, checked, sub->GetVertexData(), sub->GetEdgeData(), error, true));
    checked->GetFieldData()->ShallowCopy(sub->GetFieldData());
    GT_CHECK(SameTree(sub, checked, "LOD subtree (fast vs validated)"));
  }

  // Initial Gaussians without events: the virtual root over 3 roots, no other edge.
  {
    auto tree = CompareAll(vis4gs::EventTable(), 3, 10, "no events", 4);
    GT_CHECK(tree->GetNumberOfEdges() == 3 && tree->GetNumberOfChildren(0) == 3);
  }

  // The adapter refuses parent arrays that break "parent < node" on either path (the fast
  // path relies on it), with a message naming the node.
  for (bool validate : { false, true })
  {
    std::string error;
    vtkNew<vtkTree> tree;
    GT_CHECK(!vtkGaussianGenealogyAdapter::BuildStructure(
      { -1, 2, 0 }, tree, nullptr, nullptr, error, validate));
    GT_CHECK(error.find("node 1 has parent 2") != std::string::npos);
    error.clear();
    GT_CHECK(!vtkGaussianGenealogyAdapter::BuildStructure(
      { -1, -2 }, tree, nullptr, nullptr, error, validate));
    GT_CHECK(error.find("node 1 has parent -2") != std::string::npos);
    error.clear();
    GT_CHECK(
      !vtkGaussianGenealogyAdapter::BuildStructure({ 0 }, tree, nullptr, nullptr, error, validate));
    GT_CHECK(error.find("node 0 has parent 0") != std::string::npos);
    // A valid forest: two roots, one child each.
    error.clear();
    GT_CHECK(vtkGaussianGenealogyAdapter::BuildStructure(
      { -1, -1, 1, 0 }, tree, nullptr, nullptr, error, validate));
    GT_CHECK(tree->GetNumberOfVertices() == 5 && tree->GetRoot() == 0);
    GT_CHECK(tree->GetParent(3) == 2 && tree->GetParent(4) == 1);
    GT_CHECK(tree->GetNumberOfChildren(0) == 2 && tree->GetChild(0, 1) == 2);
    GT_CHECK(tree->GetEdgeId(2, 3) == 2);
  }

  // Negative controls: the comparison notices one different parent, two swapped parents and
  // one different vertex value.
  {
    std::string error;
    vtkNew<vtkTree> a, b, c;
    GT_CHECK(
      vtkGaussianGenealogyAdapter::BuildStructure({ -1, -1, 0, 0 }, a, nullptr, nullptr, error));
    GT_CHECK(
      vtkGaussianGenealogyAdapter::BuildStructure({ -1, -1, 0, 1 }, b, nullptr, nullptr, error));
    GT_CHECK(
      vtkGaussianGenealogyAdapter::BuildStructure({ -1, -1, 1, 0 }, c, nullptr, nullptr, error));
    vtkNew<vtkIdTypeArray> ids;
    ids->SetName("GaussianId");
    for (vtkIdType v : { -1, 10, 11, 12, 13 })
    {
      ids->InsertNextValue(v);
    }
    for (vtkTree* t : { a.Get(), b.Get(), c.Get() })
    {
      vtkNew<vtkIdTypeArray> copy;
      copy->DeepCopy(ids);
      t->GetVertexData()->SetPedigreeIds(copy);
    }
    std::cerr << "(negative controls: three differences expected below)\n";
    GT_CHECK(!SameTree(a, b, "control: different parent"));
    GT_CHECK(!SameTree(b, c, "control: two parents swapped"));
    vtkNew<vtkTree> d;
    d->DeepCopy(a);
    vtkIdTypeArray::SafeDownCast(d->GetVertexData()->GetPedigreeIds())->SetValue(3, 99);
    GT_CHECK(!SameTree(a, d, "control: different value"));
    GT_CHECK(SameTree(a, a, "control: same tree"));
  }

  if (failures)
  {
    std::cerr << failures << " check(s) failed\n";
    return 1;
  }
  return 0;
}

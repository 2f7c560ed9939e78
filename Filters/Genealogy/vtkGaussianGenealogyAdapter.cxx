/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyAdapter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianGenealogyAdapter.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkGraphInternals.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkMutableDirectedGraph.h"
#include "vtkNew.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <sstream>
#include <stdexcept>

namespace
{
//------------------------------------------------------------------------------
template <typename Out>
void CopyColumn(vtkDataArray* a, std::vector<Out>& out)
{
  const vtkIdType n = a->GetNumberOfTuples();
  out.resize(static_cast<std::size_t>(n));
  if (a->GetNumberOfComponents() == 1 && a->HasStandardMemoryLayout())
  {
    switch (a->GetDataType())
    {
      vtkTemplateMacro({
        const VTK_TT* p = static_cast<const VTK_TT*>(a->GetVoidPointer(0));
        for (vtkIdType i = 0; i < n; ++i)
        {
          out[i] = static_cast<Out>(p[i]);
        }
        return;
      });
    }
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    out[i] = static_cast<Out>(a->GetComponent(i, 0));
  }
}

//------------------------------------------------------------------------------
vtkDataArray* Column(vtkTable* t, const char* name, const char* lower)
{
  vtkDataArray* a = vtkDataArray::SafeDownCast(t->GetColumnByName(name));
  return a ? a : vtkDataArray::SafeDownCast(t->GetColumnByName(lower));
}

//------------------------------------------------------------------------------
template <typename ArrayT, typename In>
vtkSmartPointer<ArrayT> VertexArray(const char* name,
  const std::vector<In>& values,
  typename ArrayT::ValueType rootValue)
{
  auto a = vtkSmartPointer<ArrayT>::New();
  a->SetName(name);
  a->SetNumberOfTuples(static_cast<vtkIdType>(values.size()) + 1);
  auto* p = a->GetPointer(0);
  p[0] = rootValue;
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    p[i + 1] = static_cast<typename ArrayT::ValueType>(values[i]);
  }
  return a;
}
} // namespace

//------------------------------------------------------------------------------
double vtkGaussianGenealogyAdapter::ThreadCpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyAdapter::EventsFromTable(vtkTable* table,
  vis4gs::EventTable& events,
  std::string& error)
{
  vtkDataArray* it = Column(table, "Iteration", "iteration");
  vtkDataArray* kind = Column(table, "Kind", "kind");
  vtkDataArray* parent = Column(table, "Parent", "parent");
  vtkDataArray* child = Column(table, "Child", "child");
  if (!it || !kind || !parent || !child)
  {
    std::ostringstream s;
    s << "the events table lacks the numeric column(s)" << (it ? "" : " Iteration")
      << (kind ? "" : " Kind") << (parent ? "" : " Parent") << (child ? "" : " Child");
    error = s.str();
    return false;
  }
  CopyColumn(it, events.Iteration);
  CopyColumn(kind, events.Kind);
  CopyColumn(parent, events.Parent);
  CopyColumn(child, events.Child);
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyAdapter::BuildStructure(const std::vector<vtkIdType>& parents,
  vtkTree* tree,
  vtkDataSetAttributes* vertexData,
  vtkDataSetAttributes* edgeData,
  std::string& error)
{
  const std::size_t n = parents.size();
  vtkNew<vtkMutableDirectedGraph> graph;
  vtkGraphInternals* internals = graph->GetGraphInternals(true);
  internals->Adjacency.resize(n + 1);
  // Exact out-edge capacities first (one allocation per parent), then the edges in node
  // order so that children keep their creation order.
  std::vector<vtkIdType> outDegree(n + 1, 0);
  for (std::size_t k = 0; k < n; ++k)
  {
    ++outDegree[static_cast<std::size_t>(parents[k] + 1)];
  }
  for (std::size_t v = 0; v <= n; ++v)
  {
    if (outDegree[v] > 0)
    {
      internals->Adjacency[v].OutEdges.reserve(static_cast<std::size_t>(outDegree[v]));
    }
  }
  outDegree = std::vector<vtkIdType>();
  for (std::size_t k = 0; k < n; ++k)
  {
    const vtkIdType source = parents[k] + 1;
    const vtkIdType target = static_cast<vtkIdType>(k) + 1;
    internals->Adjacency[source].OutEdges.emplace_back(target, static_cast<vtkIdType>(k));
    internals->Adjacency[target].InEdges.emplace_back(source, static_cast<vtkIdType>(k));
  }
  internals->NumberOfEdges = static_cast<vtkIdType>(n);
  if (vertexData)
  {
    graph->GetVertexData()->ShallowCopy(vertexData);
  }
  if (edgeData)
  {
    graph->GetEdgeData()->ShallowCopy(edgeData);
  }
  if (!tree->CheckedShallowCopy(graph))
  {
    error = "the genealogy does not form a valid tree (internal error)";
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyAdapter::FillTree(const vis4gs::Genealogy& g,
  vtkTree* tree,
  vtkTable* bands,
  bool naive,
  std::string& error)
{
  const std::int64_t n = g.GetNumberOfNodes();
  vtkNew<vtkDataSetAttributes> vd;
  auto ids = VertexArray<vtkIdTypeArray>("GaussianId", g.GetGaussianIds(), -1);
  vd->AddArray(ids);
  vd->SetPedigreeIds(ids);
  std::int32_t firstBirth = 0;
  if (n > 0)
  {
    firstBirth = *std::min_element(g.GetBirthIterations().begin(), g.GetBirthIterations().end());
  }
  vd->AddArray(VertexArray<vtkIntArray>("BirthIteration", g.GetBirthIterations(), firstBirth));
  vd->AddArray(VertexArray<vtkIntArray>("DeathIteration", g.GetDeathIterations(), -1));
  {
    std::vector<unsigned char> kinds(g.GetBirthKinds().size());
    std::transform(g.GetBirthKinds().begin(),
      g.GetBirthKinds().end(),
      kinds.begin(),
      [](vis4gs::BirthKind k) { return static_cast<unsigned char>(k); });
    vd->AddArray(VertexArray<vtkUnsignedCharArray>("BirthKind", kinds, VirtualRootKind));
  }
  vd->AddArray(VertexArray<vtkUnsignedCharArray>("Pruned", g.GetPruned(), 0));
  vd->AddArray(VertexArray<vtkIdTypeArray>("FamilyId", g.GetFamilyIds(), -1));
  vd->AddArray(VertexArray<vtkIdTypeArray>("DescendantCount", g.GetDescendantCounts(), n));
  vd->AddArray(VertexArray<vtkIntArray>("Lifespan", g.GetLifespans(), 0));
  vd->AddArray(VertexArray<vtkDoubleArray>("PerceptionValue", g.GetPerceptionValues(), 1.0));
  vd->AddArray(VertexArray<vtkDoubleArray>(
    "LayoutX", g.GetBirthIterations(), static_cast<double>(firstBirth)));
  vd->AddArray(VertexArray<vtkDoubleArray>("LayoutY", g.GetRows(), -1.0));

  vtkNew<vtkDataSetAttributes> ed;
  vtkNew<vtkUnsignedCharArray> edgeKind;
  edgeKind->SetName("EventKind");
  edgeKind->SetNumberOfTuples(n);
  for (std::int64_t i = 0; i < n; ++i)
  {
    edgeKind->SetValue(i,
      g.GetParents()[i] < 0 ? VirtualRootKind : static_cast<unsigned char>(g.GetBirthKinds()[i]));
  }
  ed->AddArray(edgeKind);

  if (naive)
  {
    vtkNew<vtkMutableDirectedGraph> graph;
    graph->AddVertex();
    for (std::int64_t i = 0; i < n; ++i)
    {
      graph->AddChild(g.GetParents()[i] + 1);
    }
    graph->GetVertexData()->ShallowCopy(vd);
    graph->GetEdgeData()->ShallowCopy(ed);
    if (!tree->CheckedShallowCopy(graph))
    {
      error = "the genealogy does not form a valid tree (internal error)";
      return false;
    }
  }
  else
  {
    std::vector<vtkIdType> parents(g.GetParents().begin(), g.GetParents().end());
    if (!BuildStructure(parents, tree, vd, ed, error))
    {
      return false;
    }
  }
  vtkNew<vtkIntArray> last;
  last->SetName("LastIteration");
  last->InsertNextValue(g.GetLastIteration());
  tree->GetFieldData()->AddArray(last);
  vtkNew<vtkDoubleArray> alpha;
  alpha->SetName("PerceptionAlpha");
  alpha->InsertNextValue(g.GetAlpha());
  tree->GetFieldData()->AddArray(alpha);

  if (bands)
  {
    const auto& b = g.GetFamilyBands();
    const vtkIdType f = static_cast<vtkIdType>(b.size());
    auto column = [&](auto array, const char* name)
    {
      array->SetName(name);
      array->SetNumberOfTuples(f);
      bands->AddColumn(array);
      return array;
    };
    vtkNew<vtkIdTypeArray> familyId, rootVertex, rootId, minRow, maxRow, count, maxD;
    vtkNew<vtkIntArray> minIt, maxIt, maxT;
    column(familyId.Get(), "FamilyId");
    column(rootVertex.Get(), "RootVertex");
    column(rootId.Get(), "RootGaussianId");
    column(minIt.Get(), "MinIteration");
    column(maxIt.Get(), "MaxIteration");
    column(minRow.Get(), "MinRow");
    column(maxRow.Get(), "MaxRow");
    column(count.Get(), "NodeCount");
    column(maxD.Get(), "MaxDescendantCount");
    column(maxT.Get(), "MaxLifespan");
    for (vtkIdType k = 0; k < f; ++k)
    {
      familyId->SetValue(k, k);
      rootVertex->SetValue(k, b[k].RootNode + 1);
      rootId->SetValue(k, b[k].RootGaussianId);
      minIt->SetValue(k, b[k].MinIteration);
      maxIt->SetValue(k, b[k].MaxIteration);
      minRow->SetValue(k, b[k].MinRow);
      maxRow->SetValue(k, b[k].MaxRow);
      count->SetValue(k, b[k].NodeCount);
      maxD->SetValue(k, b[k].MaxDescendants);
      maxT->SetValue(k, b[k].MaxLifespan);
    }
  }
  return true;
}

//------------------------------------------------------------------------------
std::shared_ptr<vis4gs::Genealogy> vtkGaussianGenealogyAdapter::FromTree(vtkTree* tree,
  std::string& error)
{
  if (!tree || tree->GetNumberOfVertices() == 0)
  {
    error = "the input tree is empty";
    return nullptr;
  }
  vtkDataSetAttributes* vd = tree->GetVertexData();
  vtkDataArray* ids = vtkDataArray::SafeDownCast(vd->GetAbstractArray("GaussianId"));
  vtkDataArray* birth = vtkDataArray::SafeDownCast(vd->GetAbstractArray("BirthIteration"));
  vtkDataArray* death = vtkDataArray::SafeDownCast(vd->GetAbstractArray("DeathIteration"));
  vtkDataArray* kind = vtkDataArray::SafeDownCast(vd->GetAbstractArray("BirthKind"));
  vtkDataArray* pruned = vtkDataArray::SafeDownCast(vd->GetAbstractArray("Pruned"));
  vtkDataArray* last =
    vtkDataArray::SafeDownCast(tree->GetFieldData()->GetAbstractArray("LastIteration"));
  vtkDataArray* alpha =
    vtkDataArray::SafeDownCast(tree->GetFieldData()->GetAbstractArray("PerceptionAlpha"));
  if (!ids || !birth || !death || !kind || !pruned || !last || last->GetNumberOfTuples() < 1)
  {
    error = "the input tree lacks the genealogy arrays (GaussianId, BirthIteration, "
            "DeathIteration, BirthKind, Pruned, field data LastIteration): use the output of "
            "vtkGaussianGenealogyTreeFilter";
    return nullptr;
  }
  if (tree->GetRoot() != 0)
  {
    error = "the input tree's root is not vertex 0 (not a vtkGaussianGenealogyTreeFilter output)";
    return nullptr;
  }
  const vtkIdType nv = tree->GetNumberOfVertices();
  vis4gs::GenealogyNodes nodes;
  std::vector<std::int64_t> tmp64;
  std::vector<std::int32_t> tmp32;
  std::vector<std::uint8_t> tmp8;
  CopyColumn(ids, tmp64);
  nodes.GaussianIds.assign(tmp64.begin() + 1, tmp64.end());
  CopyColumn(birth, tmp32);
  nodes.Birth.assign(tmp32.begin() + 1, tmp32.end());
  CopyColumn(death, tmp32);
  nodes.Death.assign(tmp32.begin() + 1, tmp32.end());
  CopyColumn(pruned, tmp8);
  nodes.Pruned.assign(tmp8.begin() + 1, tmp8.end());
  CopyColumn(kind, tmp8);
  nodes.Kinds.resize(static_cast<std::size_t>(nv - 1));
  for (vtkIdType v = 1; v < nv; ++v)
  {
    const std::uint8_t k = tmp8[v];
    if (k != 0 && k != 1 && k != 2 && k != 4)
    {
      std::ostringstream s;
      s << "vertex " << v << " has an invalid BirthKind " << static_cast<int>(k);
      error = s.str();
      return nullptr;
    }
    nodes.Kinds[v - 1] = static_cast<vis4gs::BirthKind>(k);
  }
  nodes.Parents.resize(static_cast<std::size_t>(nv - 1));
  for (vtkIdType v = 1; v < nv; ++v)
  {
    nodes.Parents[v - 1] = tree->GetParent(v) - 1;
  }
  try
  {
    return std::make_shared<vis4gs::Genealogy>(vis4gs::Genealogy::Assemble(std::move(nodes),
      static_cast<std::int32_t>(last->GetComponent(0, 0)),
      alpha && alpha->GetNumberOfTuples() > 0 ? alpha->GetComponent(0, 0) : 0.4));
  }
  catch (const std::exception& e)
  {
    error = e.what();
    return nullptr;
  }
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> vtkGaussianGenealogyAdapter::NodesFromSelection(
  const vis4gs::Genealogy& g,
  vtkSelection* selection,
  vtkIdType& unknown,
  std::string& error)
{
  std::vector<std::int64_t> out;
  unknown = 0;
  if (!selection)
  {
    return out;
  }
  for (unsigned int k = 0; k < selection->GetNumberOfNodes(); ++k)
  {
    vtkSelectionNode* node = selection->GetNode(k);
    vtkDataArray* list = vtkDataArray::SafeDownCast(node->GetSelectionList());
    if (!list)
    {
      continue;
    }
    const int content = node->GetContentType();
    if (content != vtkSelectionNode::PEDIGREEIDS && content != vtkSelectionNode::INDICES)
    {
      error = "selections must hold PEDIGREEIDS (GaussianIds) or INDICES (tree vertices)";
      return std::vector<std::int64_t>();
    }
    for (vtkIdType i = 0; i < list->GetNumberOfTuples(); ++i)
    {
      const auto value = static_cast<std::int64_t>(list->GetComponent(i, 0));
      std::int64_t n = -1;
      if (content == vtkSelectionNode::PEDIGREEIDS)
      {
        n = g.FindNode(value);
      }
      else if (value >= 1 && value <= g.GetNumberOfNodes())
      {
        n = value - 1;
      }
      else if (value == 0)
      {
        continue; // the virtual root
      }
      if (n < 0)
      {
        ++unknown;
      }
      else
      {
        out.push_back(n);
      }
    }
  }
  return out;
}

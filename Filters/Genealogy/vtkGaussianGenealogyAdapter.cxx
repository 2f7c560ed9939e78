/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyAdapter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianGenealogyAdapter.h"

#include "Vis4GSDataModel.h"
#include "Vis4GSLineageBreaks.h"

#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkGaussianCompactTree.h"
#include "vtkGraphInternals.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkMutableDirectedGraph.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkTypeInt32Array.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace
{
//------------------------------------------------------------------------------
// o[i] = p[i] converted, in parallel.
template <typename S, typename T>
void ConvertValues(const S* p, T* o, vtkIdType n)
{
#pragma omp parallel for schedule(static) if (n > 65536)
  for (vtkIdType i = 0; i < n; ++i)
  {
    o[i] = static_cast<T>(p[i]);
  }
}

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
      vtkTemplateMacro(
        ConvertValues(static_cast<const VTK_TT*>(a->GetVoidPointer(0)), out.data(), n); return;);
    }
  }
  for (vtkIdType i = 0; i < n; ++i)
  {
    out[i] = static_cast<Out>(a->GetComponent(i, 0));
  }
}

//------------------------------------------------------------------------------
// The values of a one-component array whose values are stored as T (an integer type of that
// size and signedness) in one contiguous block; null otherwise.
template <typename T>
const T* Contiguous(vtkDataArray* a)
{
  bool isSigned = false, isUnsigned = false;
  switch (a->GetDataType())
  {
    case VTK_SIGNED_CHAR:
    case VTK_SHORT:
    case VTK_INT:
    case VTK_LONG:
    case VTK_LONG_LONG:
    case VTK_ID_TYPE:
      isSigned = true;
      break;
    case VTK_UNSIGNED_CHAR:
    case VTK_UNSIGNED_SHORT:
    case VTK_UNSIGNED_INT:
    case VTK_UNSIGNED_LONG:
    case VTK_UNSIGNED_LONG_LONG:
      isUnsigned = true;
      break;
    default:
      break;
  }
  if (a->GetNumberOfComponents() != 1 || !a->HasStandardMemoryLayout() ||
    a->GetDataTypeSize() != static_cast<int>(sizeof(T)) ||
    !(std::is_signed<T>::value ? isSigned : isUnsigned))
  {
    return nullptr;
  }
  return a->GetNumberOfTuples() > 0 ? static_cast<const T*>(a->GetVoidPointer(0)) : nullptr;
}

//------------------------------------------------------------------------------
vtkDataArray* Column(vtkTable* t, const char* name, const char* lower)
{
  vtkDataArray* a = vtkDataArray::SafeDownCast(t->GetColumnByName(name));
  return a ? a : vtkDataArray::SafeDownCast(t->GetColumnByName(lower));
}

//------------------------------------------------------------------------------
// Vertex array of n + 1 values: the virtual root's value, then values[0..n) converted.
// Filled in parallel (each thread writes, and so first touches, its own pages).
template <typename ArrayT, typename In>
vtkSmartPointer<ArrayT> VertexArray(const char* name,
  const std::vector<In>& values,
  typename ArrayT::ValueType rootValue)
{
  using Value = typename ArrayT::ValueType;
  auto a = vtkSmartPointer<ArrayT>::New();
  a->SetName(name);
  const vtkIdType n = static_cast<vtkIdType>(values.size());
  a->SetNumberOfTuples(n + 1);
  Value* p = a->GetPointer(0);
  const In* in = values.data();
  p[0] = rootValue;
#pragma omp parallel for schedule(static)
  for (vtkIdType i = 0; i < n; ++i)
  {
    p[i + 1] = static_cast<Value>(in[i]);
  }
  return a;
}

//------------------------------------------------------------------------------
// A vertex array of node indices or counts (values in [-1, n]): 32-bit while n fits, which
// halves these arrays (at 10M vertices, 40 MB each instead of 80).
template <typename In>
vtkSmartPointer<vtkDataArray> IndexVertexArray(const char* name,
  const std::vector<In>& values,
  std::int64_t rootValue,
  std::int64_t n)
{
  if (n < std::numeric_limits<std::int32_t>::max())
  {
    return VertexArray<vtkTypeInt32Array>(name, values, static_cast<std::int32_t>(rootValue));
  }
  return VertexArray<vtkIdTypeArray>(name, values, static_cast<vtkIdType>(rootValue));
}

//------------------------------------------------------------------------------
/**
 * A vtkTree whose root is set by its builder. Used only as the source of a ShallowCopy:
 * vtkTree::IsStructureValid accepts another vtkTree as it is (it copies the root), so the
 * O(n) connectivity walk is skipped. The builder must guarantee a valid tree (see
 * FillStructure).
 */
class vtkGaussianTrustedTree : public vtkTree
{
public:
  static vtkGaussianTrustedTree* New();
  vtkTypeMacro(vtkGaussianTrustedTree, vtkTree);
  void SetRootVertex(vtkIdType root) { this->Root = root; }

protected:
  vtkGaussianTrustedTree() = default;
  ~vtkGaussianTrustedTree() override = default;

private:
  vtkGaussianTrustedTree(const vtkGaussianTrustedTree&) = delete;
  void operator=(const vtkGaussianTrustedTree&) = delete;
};
vtkStandardNewMacro(vtkGaussianTrustedTree);

//------------------------------------------------------------------------------
/**
 * Children of every node in CSR form: the children of node k are List[Offsets[k] ..
 * Offsets[k + 1]) and the roots (parent -1) are Roots[0 .. NumberOfRoots), all as node
 * indices in increasing order.
 */
struct ChildLists
{
  const std::int64_t* Offsets = nullptr;
  const std::int64_t* List = nullptr;
  vtkIdType ListSize = 0;
  const std::int64_t* Roots = nullptr;
  vtkIdType NumberOfRoots = 0;
};

//------------------------------------------------------------------------------
/**
 * Writes the edges into vtkGraph's own adjacency lists: every std::vector gets its exact size
 * in one allocation (a heap block per in-edge and per non-empty child list: vtkTree's form).
 */
struct AdjacencyListWriter
{
  vtkGraphInternals* Internals;
  vtkVertexAdjacencyList* Adj = nullptr;

  void Start(vtkIdType n, const ChildLists& lists)
  {
    auto& adjacency = this->Internals->Adjacency;
    adjacency.clear();
    adjacency.resize(static_cast<std::size_t>(n + 1));
    this->Adj = adjacency.data();
    this->Adj[0].OutEdges.reserve(static_cast<std::size_t>(lists.NumberOfRoots));
  }
  void Root(vtkIdType, vtkIdType root) { this->Adj[0].OutEdges.emplace_back(root + 1, root); }
  void In(vtkIdType k, vtkIdType p) { this->Adj[k + 1].InEdges.assign(1, vtkInEdgeType(p + 1, k)); }
  void StartChildren(vtkIdType k, vtkIdType count)
  {
    this->Adj[k + 1].OutEdges.reserve(static_cast<std::size_t>(count));
  }
  void Child(vtkIdType k, vtkIdType, vtkIdType child)
  {
    this->Adj[k + 1].OutEdges.emplace_back(child + 1, child);
  }
  void Finish(vtkIdType n) { this->Internals->NumberOfEdges = n; }
  void Fail() { this->Internals->Adjacency.clear(); }
};

//------------------------------------------------------------------------------
/**
 * Writes the same edges into vtkGaussianCompactTree's three flat arrays (40 bytes per
 * vertex, three allocations). The out-edge offsets are a prefix sum of the list lengths, so
 * a malformed list cannot write out of bounds before FillAdjacency reports it.
 */
struct CompactWriter
{
  vtkGaussianCompactTree::Structure S;

  void Start(vtkIdType n, const ChildLists& lists)
  {
    this->S.InEdges.resize(static_cast<std::size_t>(n + 1));
    this->S.InEdges[0] = vtkInEdgeType(-1, -1);
    this->S.OutEdges.resize(static_cast<std::size_t>(n));
    this->S.OutOffsets.resize(static_cast<std::size_t>(n + 2));
    vtkIdType* o = this->S.OutOffsets.data();
    o[0] = 0;
    o[1] = std::min(lists.NumberOfRoots, n);
    for (vtkIdType k = 0; k < n; ++k)
    {
      const vtkIdType count = std::max<vtkIdType>(0, lists.Offsets[k + 1] - lists.Offsets[k]);
      o[k + 2] = std::min(o[k + 1] + count, n);
    }
  }
  void Root(vtkIdType r, vtkIdType root)
  {
    if (r < this->S.OutOffsets[1])
    {
      this->S.OutEdges[r] = vtkOutEdgeType(root + 1, root);
    }
  }
  void In(vtkIdType k, vtkIdType p) { this->S.InEdges[k + 1] = vtkInEdgeType(p + 1, k); }
  void StartChildren(vtkIdType, vtkIdType) {}
  void Child(vtkIdType k, vtkIdType c, vtkIdType child)
  {
    const vtkIdType at = this->S.OutOffsets[k + 1] + c;
    if (at < this->S.OutOffsets[k + 2])
    {
      this->S.OutEdges[at] = vtkOutEdgeType(child + 1, child);
    }
  }
  void Finish(vtkIdType) {}
  void Fail() { this->S = vtkGaussianCompactTree::Structure(); }
};

//------------------------------------------------------------------------------
/**
 * Writes the edges of the tree "vertex 0 is the virtual root over the roots, vertex k + 1 is
 * node k with the in-edge k from parent[k] + 1, out-edges in child order" through @p writer
 * (vtkGraph's adjacency lists or the compact arrays), in parallel over vertices (each
 * vertex's edges are written by one thread only).
 *
 * On the way it checks that @p parent (n values) and @p lists describe the same forest and
 * that every parent precedes its child (-1 <= parent[k] < k); returns false with @p error
 * otherwise (the writer's output is then discarded). When it returns true, the graph "vertex
 * 0 = virtual root, vertex k + 1 = node k, edge k from parent[k] + 1 to k + 1" is a tree
 * rooted at vertex 0: every vertex but 0 has exactly one in-edge and vertex 0 none, there are
 * n edges for n + 1 vertices, the out-edges are exactly the reversed in-edges (each listed
 * child names its list's node as parent, lists are strictly increasing, and they hold n
 * entries in all), and following parents strictly decreases the vertex index, so every
 * vertex reaches vertex 0 (connected) and no cycle exists.
 */
template <typename P, typename Writer>
bool FillAdjacency(Writer& writer,
  vtkIdType n,
  const P* parent,
  const ChildLists& lists,
  std::string& error)
{
  // The roots first (a few thousand, sequential).
  for (vtkIdType r = 0; r < lists.NumberOfRoots; ++r)
  {
    const vtkIdType root = lists.Roots[r];
    if (root < 0 || root >= n || parent[root] != -1 || (r > 0 && root <= lists.Roots[r - 1]))
    {
      std::ostringstream s;
      s << "the list of roots does not match the parents (root " << root << ")";
      error = s.str();
      return false;
    }
  }
  writer.Start(n, lists);
  for (vtkIdType r = 0; r < lists.NumberOfRoots; ++r)
  {
    writer.Root(r, lists.Roots[r]);
  }
  vtkIdType badParent = -1, badList = -1, listed = 0;
#pragma omp parallel for schedule(dynamic, 8192) reduction(max : badParent, badList)             \
  reduction(+ : listed)
  for (vtkIdType k = 0; k < n; ++k)
  {
    const vtkIdType p = static_cast<vtkIdType>(parent[k]);
    if (p < -1 || p >= k)
    {
      badParent = std::max(badParent, k);
      continue;
    }
    writer.In(k, p);
    const vtkIdType b = lists.Offsets[k], e = lists.Offsets[k + 1];
    if (b < 0 || e < b || e > lists.ListSize)
    {
      badList = std::max(badList, k);
      continue;
    }
    if (e > b)
    {
      listed += e - b;
      writer.StartChildren(k, e - b);
      vtkIdType previous = -1;
      for (vtkIdType c = b; c < e; ++c)
      {
        const vtkIdType child = lists.List[c];
        if (child <= previous || child >= n || static_cast<vtkIdType>(parent[child]) != k)
        {
          badList = std::max(badList, k);
          break;
        }
        writer.Child(k, c - b, child);
        previous = child;
      }
    }
  }
  std::ostringstream s;
  if (badParent >= 0)
  {
    s << "node " << badParent << " has parent " << static_cast<vtkIdType>(parent[badParent])
      << ": parents must precede their children (-1 <= parent < node)";
  }
  else if (badList >= 0 || listed + lists.NumberOfRoots != n)
  {
    s << "the child lists do not match the parents (node " << badList << ")";
  }
  else
  {
    writer.Finish(n);
    return true;
  }
  error = s.str();
  writer.Fail();
  return false;
}

//------------------------------------------------------------------------------
/**
 * The tree of @p parent / @p lists (checked by FillAdjacency) into @p tree with the vertex and
 * edge attributes. When @p tree is a vtkGaussianCompactTree it gets the compact arrays.
 * Otherwise, with @p validate the structure goes through a vtkMutableDirectedGraph and
 * vtkTree::CheckedShallowCopy (VTK's own O(n) walk); without, it is built in a vtkTree whose
 * root is set directly (valid by construction, see FillAdjacency) and shallow-copied, which
 * vtkTree accepts without a walk. All give the same tree (TestGaussianGenealogyTreeFilter,
 * TestGaussianCompactTree).
 */
template <typename P>
bool MakeTree(vtkIdType n,
  const P* parent,
  const ChildLists& lists,
  vtkTree* tree,
  vtkDataSetAttributes* vertexData,
  vtkDataSetAttributes* edgeData,
  bool validate,
  std::string& error)
{
  if (auto* compact = vtkGaussianCompactTree::SafeDownCast(tree))
  {
    CompactWriter writer;
    if (!FillAdjacency(writer, n, parent, lists, error))
    {
      return false;
    }
    if (!compact->SetStructure(std::move(writer.S)))
    {
      error = "the genealogy does not form a valid tree (internal error)";
      return false;
    }
    if (vertexData)
    {
      compact->GetVertexData()->ShallowCopy(vertexData);
    }
    if (edgeData)
    {
      compact->GetEdgeData()->ShallowCopy(edgeData);
    }
    return true;
  }
  vtkSmartPointer<vtkGraph> graph;
  if (validate)
  {
    graph = vtkSmartPointer<vtkMutableDirectedGraph>::New();
  }
  else
  {
    auto trusted = vtkSmartPointer<vtkGaussianTrustedTree>::New();
    trusted->SetRootVertex(0);
    graph = trusted;
  }
  AdjacencyListWriter writer{ graph->GetGraphInternals(true) };
  if (!FillAdjacency(writer, n, parent, lists, error))
  {
    return false;
  }
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
} // namespace

//------------------------------------------------------------------------------
double vtkGaussianGenealogyAdapter::ThreadCpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

//------------------------------------------------------------------------------
double vtkGaussianGenealogyAdapter::ProcessCpuSeconds()
{
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
//------------------------------------------------------------------------------
bool vtkGaussianGenealogyAdapter::EventsFromTable(vtkTable* table,
  vis4gs::EventTable& storage,
  vis4gs::EventColumns& events,
  std::string& error)
{
  vtkDataArray* it = Column(table, vis4gs::arrays::EventIteration, "iteration");
  vtkDataArray* kind = Column(table, vis4gs::arrays::EventKind, "kind");
  vtkDataArray* parent = Column(table, vis4gs::arrays::EventParent, "parent");
  vtkDataArray* child = Column(table, vis4gs::arrays::EventChild, "child");
  if (!it || !kind || !parent || !child)
  {
    std::ostringstream s;
    s << "the events table lacks the numeric column(s)" << (it ? "" : " Iteration")
      << (kind ? "" : " Kind") << (parent ? "" : " Parent") << (child ? "" : " Child");
    error = s.str();
    return false;
  }
  storage = vis4gs::EventTable();
  const vtkIdType e = it->GetNumberOfTuples();
  const bool sameLength = kind->GetNumberOfTuples() == e && parent->GetNumberOfTuples() == e &&
    child->GetNumberOfTuples() == e;
  const auto* it32 = Contiguous<std::int32_t>(it);
  const auto* kind8 = Contiguous<std::uint8_t>(kind);
  const auto* parent64 = Contiguous<std::int64_t>(parent);
  const auto* child64 = Contiguous<std::int64_t>(child);
  if (sameLength && it32 && kind8 && parent64 && child64)
  {
    events.Iteration = it32;
    events.Kind = kind8;
    events.Parent = parent64;
    events.Child = child64;
    events.Size = static_cast<std::size_t>(e);
    return true;
  }
  CopyColumn(it, storage.Iteration);
  CopyColumn(kind, storage.Kind);
  CopyColumn(parent, storage.Parent);
  CopyColumn(child, storage.Child);
  try
  {
    events = vis4gs::EventColumns::Of(storage);
  }
  catch (const std::exception& x)
  {
    error = x.what();
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyAdapter::BuildStructure(const std::vector<vtkIdType>& parents,
  vtkTree* tree,
  vtkDataSetAttributes* vertexData,
  vtkDataSetAttributes* edgeData,
  std::string& error,
  bool validate)
{
  const vtkIdType n = static_cast<vtkIdType>(parents.size());
  // Child lists by a counting sort over the parents (node order kept inside each list).
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(n + 2), 0), list, roots;
  for (vtkIdType k = 0; k < n; ++k)
  {
    const vtkIdType p = parents[k];
    if (p < -1 || p >= k)
    {
      std::ostringstream s;
      s << "node " << k << " has parent " << p
        << ": parents must precede their children (-1 <= parent < node)";
      error = s.str();
      return false;
    }
    if (p >= 0)
    {
      ++offsets[p + 2];
    }
  }
  for (vtkIdType k = 0; k <= n; ++k)
  {
    offsets[k + 1] += offsets[k];
  }
  list.resize(static_cast<std::size_t>(offsets[n + 1]));
  roots.reserve(static_cast<std::size_t>(n - offsets[n + 1]));
  for (vtkIdType k = 0; k < n; ++k)
  {
    if (parents[k] < 0)
    {
      roots.push_back(k);
    }
    else
    {
      list[offsets[parents[k] + 1]++] = k; // offsets[p + 1] walks node p's list
    }
  }
  offsets.pop_back(); // offsets[p] is now the start of node p's list, offsets[n] the end
  ChildLists lists;
  lists.Offsets = offsets.data();
  lists.List = list.data();
  lists.ListSize = static_cast<vtkIdType>(list.size());
  lists.Roots = roots.data();
  lists.NumberOfRoots = static_cast<vtkIdType>(roots.size());
  return MakeTree(n, parents.data(), lists, tree, vertexData, edgeData, validate, error);
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyAdapter::BreaksFromFieldData(vtkFieldData* fd,
  vis4gs::LineageBreakTable& breaks,
  std::string& error)
{
  namespace names = vis4gs::arrays;
  vtkDataArray* iteration =
    fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(names::EventBreakIteration)) : nullptr;
  const vtkIdType b = iteration ? iteration->GetNumberOfTuples() : 0;
  breaks = vis4gs::LineageBreakTable();
  breaks.Iteration.resize(static_cast<std::size_t>(b));
  for (vtkIdType i = 0; i < b; ++i)
  {
    breaks.Iteration[i] = static_cast<std::int32_t>(iteration->GetComponent(i, 0));
  }
  for (const auto& c : names::LineageBreakIdColumns(breaks))
  {
    vtkDataArray* a = fd ? vtkDataArray::SafeDownCast(fd->GetAbstractArray(c.first)) : nullptr;
    if (!a || a->GetNumberOfTuples() != b)
    {
      error = std::string("the events' field data has ") + names::EventBreakIteration + " but " +
        (a ? "a " : "no ") + c.first + (a ? " of another length" : "");
      return false;
    }
    c.second->resize(static_cast<std::size_t>(b));
    for (vtkIdType i = 0; i < b; ++i)
    {
      (*c.second)[i] = static_cast<std::int64_t>(a->GetComponent(i, 0));
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyAdapter::FillTree(const vis4gs::Genealogy& g,
  vtkTree* tree,
  vtkTable* bands,
  bool naive,
  std::string& error,
  bool validate)
{
  const std::int64_t n = g.GetNumberOfNodes();
  vtkNew<vtkDataSetAttributes> vd;
  auto ids = VertexArray<vtkIdTypeArray>(vis4gs::arrays::TreeGaussianId, g.GetGaussianIds(), -1);
  vd->AddArray(ids);
  vd->SetPedigreeIds(ids);
  std::int32_t firstBirth = 0;
  if (n > 0)
  {
    firstBirth = *std::min_element(g.GetBirthIterations().begin(), g.GetBirthIterations().end());
  }
  vd->AddArray(VertexArray<vtkIntArray>("BirthIteration", g.GetBirthIterations(), firstBirth));
  vd->AddArray(VertexArray<vtkIntArray>("DeathIteration", g.GetDeathIterations(), -1));
  vd->AddArray(VertexArray<vtkUnsignedCharArray>("BirthKind", g.GetBirthKinds(), VirtualRootKind));
  vd->AddArray(VertexArray<vtkUnsignedCharArray>("Pruned", g.GetPruned(), 0));
  vd->AddArray(IndexVertexArray(vis4gs::arrays::TreeFamilyId, g.GetFamilyIds(), -1, n));
  vd->AddArray(IndexVertexArray("DescendantCount", g.GetDescendantCounts(), n, n));
  vd->AddArray(VertexArray<vtkIntArray>("Lifespan", g.GetLifespans(), 0));
  vd->AddArray(VertexArray<vtkDoubleArray>("PerceptionValue", g.GetPerceptionValues(), 1.0));
  vd->AddArray(
    VertexArray<vtkIntArray>(vis4gs::arrays::TreeLayoutX, g.GetBirthIterations(), firstBirth));
  vd->AddArray(IndexVertexArray(vis4gs::arrays::TreeLayoutY, g.GetRows(), -1, n));
  if (!g.GetBreakRoots().empty())
  {
    vtkNew<vtkUnsignedCharArray> breakRoot;
    breakRoot->SetName(vis4gs::arrays::TreeLineageBreakRoot);
    breakRoot->SetNumberOfTuples(static_cast<vtkIdType>(n + 1));
    breakRoot->FillValue(0);
    for (std::int64_t node : g.GetBreakRoots())
    {
      breakRoot->SetValue(static_cast<vtkIdType>(node + 1), 1);
    }
    vd->AddArray(breakRoot);
  }

  vtkNew<vtkDataSetAttributes> ed;
  vtkNew<vtkUnsignedCharArray> edgeKind;
  edgeKind->SetName("EventKind");
  edgeKind->SetNumberOfTuples(n);
  {
    unsigned char* kind = edgeKind->GetPointer(0);
    const std::int64_t* parent = g.GetParents().data();
    const vis4gs::BirthKind* birthKind = g.GetBirthKinds().data();
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i)
    {
      kind[i] = parent[i] < 0 ? VirtualRootKind : static_cast<unsigned char>(birthKind[i]);
    }
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
    // Core's child lists (CSR, creation order) and the family roots (in node order).
    std::vector<std::int64_t> roots(g.GetFamilyBands().size());
    for (std::size_t f = 0; f < roots.size(); ++f)
    {
      roots[f] = g.GetFamilyBands()[f].RootNode;
    }
    static const std::int64_t noChildren[1] = { 0 };
    ChildLists lists;
    lists.Offsets = n > 0 ? g.GetChildOffsets().data() : noChildren;
    lists.List = g.GetChildren().data();
    lists.ListSize = static_cast<vtkIdType>(g.GetChildren().size());
    lists.Roots = roots.data();
    lists.NumberOfRoots = static_cast<vtkIdType>(roots.size());
    if (n > 0 && static_cast<std::int64_t>(g.GetChildOffsets().size()) != n + 1)
    {
      error = "the genealogy has no child lists (internal error)";
      return false;
    }
    if (!MakeTree(n, g.GetParents().data(), lists, tree, vd, ed, validate, error))
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
  vtkDataArray* ids =
    vtkDataArray::SafeDownCast(vd->GetAbstractArray(vis4gs::arrays::TreeGaussianId));
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

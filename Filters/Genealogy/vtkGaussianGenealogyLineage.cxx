/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianGenealogyLineage.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianGenealogyLineage.h"

#include "Vis4GSDataModel.h" // vis4gs::arrays

#include "vtkGaussianGenealogyAdapter.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkTable.h"
#include "vtkTree.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

vtkStandardNewMacro(vtkGaussianGenealogyLineage);

//------------------------------------------------------------------------------
class vtkGaussianGenealogyLineage::vtkInternals
{
public:
  std::shared_ptr<vis4gs::Genealogy> Genealogy;
  vtkMTimeType TreeTime = 0;
  /// Snapshot iteration -> (sorted ids, values).
  std::map<int, std::pair<std::vector<std::int64_t>, std::vector<double>>> Snapshots;
};

//------------------------------------------------------------------------------
vtkGaussianGenealogyLineage::vtkGaussianGenealogyLineage()
  : Internals(new vtkInternals)
{
}

//------------------------------------------------------------------------------
vtkGaussianGenealogyLineage::~vtkGaussianGenealogyLineage() = default;

//------------------------------------------------------------------------------
void vtkGaussianGenealogyLineage::SetTree(vtkTree* tree)
{
  if (this->Tree != tree)
  {
    this->Tree = tree;
    this->Internals->Genealogy.reset();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkTree* vtkGaussianGenealogyLineage::GetTree()
{
  return this->Tree;
}

//------------------------------------------------------------------------------
void vtkGaussianGenealogyLineage::AddSnapshotValues(int iteration,
  vtkIdTypeArray* ids,
  vtkDataArray* values)
{
  if (!ids || !values || ids->GetNumberOfTuples() != values->GetNumberOfTuples())
  {
    vtkErrorMacro("AddSnapshotValues: ids and values must be given with the same length");
    return;
  }
  const vtkIdType n = ids->GetNumberOfTuples();
  std::vector<std::pair<std::int64_t, double>> pairs(static_cast<std::size_t>(n));
  for (vtkIdType i = 0; i < n; ++i)
  {
    pairs[i] = { ids->GetValue(i), values->GetComponent(i, 0) };
  }
  std::sort(
    pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  auto& entry = this->Internals->Snapshots[iteration];
  entry.first.resize(pairs.size());
  entry.second.resize(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    entry.first[i] = pairs[i].first;
    entry.second[i] = pairs[i].second;
  }
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkGaussianGenealogyLineage::RemoveAllSnapshotValues()
{
  this->Internals->Snapshots.clear();
  this->Modified();
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyLineage::Query(int which,
  vtkIdTypeArray* gaussianIds,
  vtkIdTypeArray* result)
{
  this->NumberOfUnknownIds = 0;
  if (!result || !gaussianIds)
  {
    vtkErrorMacro("ids and result arrays are required");
    return false;
  }
  result->Reset();
  vtkInternals& in = *this->Internals;
  if (!this->Tree)
  {
    vtkErrorMacro("no tree: call SetTree first");
    return false;
  }
  if (!in.Genealogy || in.TreeTime != this->Tree->GetMTime())
  {
    std::string error;
    in.Genealogy = vtkGaussianGenealogyAdapter::FromTree(this->Tree, error);
    if (!in.Genealogy)
    {
      vtkErrorMacro("" << error);
      return false;
    }
    in.TreeTime = this->Tree->GetMTime();
  }
  const vis4gs::Genealogy& g = *in.Genealogy;
  std::vector<std::int64_t> ids(static_cast<std::size_t>(gaussianIds->GetNumberOfTuples()));
  std::copy(gaussianIds->GetPointer(0), gaussianIds->GetPointer(0) + ids.size(), ids.begin());
  std::int64_t unknown = 0;
  const std::vector<std::int64_t> nodes = g.FindNodes(ids, &unknown);
  this->NumberOfUnknownIds = unknown;
  std::vector<std::int64_t> out;
  switch (which)
  {
    case 0:
      out = g.Ancestors(nodes);
      break;
    case 1:
      out = g.Descendants(nodes);
      break;
    case 2:
      out = g.Lineage(nodes);
      break;
    default:
      out = g.Family(nodes);
      break;
  }
  result->SetNumberOfTuples(static_cast<vtkIdType>(out.size()));
  for (std::size_t k = 0; k < out.size(); ++k)
  {
    result->SetValue(static_cast<vtkIdType>(k), g.GetGaussianIds()[out[k]]);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyLineage::GetAncestors(vtkIdTypeArray* ids, vtkIdTypeArray* result)
{
  return this->Query(0, ids, result);
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyLineage::GetDescendants(vtkIdTypeArray* ids, vtkIdTypeArray* result)
{
  return this->Query(1, ids, result);
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyLineage::GetLineage(vtkIdTypeArray* ids, vtkIdTypeArray* result)
{
  return this->Query(2, ids, result);
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyLineage::GetFamily(vtkIdTypeArray* ids, vtkIdTypeArray* result)
{
  return this->Query(3, ids, result);
}

//------------------------------------------------------------------------------
bool vtkGaussianGenealogyLineage::TraceToRoot(vtkIdType gaussianId, vtkTable* result)
{
  if (!result)
  {
    vtkErrorMacro("a result table is required");
    return false;
  }
  result->Initialize();
  vtkNew<vtkIdTypeArray> one;
  one->InsertNextValue(gaussianId);
  vtkNew<vtkIdTypeArray> dummy;
  if (!this->Query(0, one, dummy)) // builds the genealogy
  {
    return false;
  }
  const vis4gs::Genealogy& g = *this->Internals->Genealogy;
  const std::int64_t node = g.FindNode(gaussianId);
  if (node < 0)
  {
    vtkErrorMacro("GaussianId " << gaussianId << " is not in the tree");
    return false;
  }
  const auto& snaps = this->Internals->Snapshots;
  std::vector<std::int32_t> iterations;
  for (const auto& s : snaps)
  {
    iterations.push_back(s.first);
  }
  auto lookup = [&snaps](std::int32_t iteration, std::int64_t id)
  {
    const auto& s = snaps.at(iteration);
    const auto it = std::lower_bound(s.first.begin(), s.first.end(), id);
    return it != s.first.end() && *it == id ? s.second[it - s.first.begin()]
                                            : std::numeric_limits<double>::quiet_NaN();
  };
  const std::vector<vis4gs::TraceStep> trace = g.TraceToRoot(node, iterations, lookup);
  const vtkIdType n = static_cast<vtkIdType>(trace.size());
  vtkNew<vtkIdTypeArray> ids, vertex;
  vtkNew<vtkIntArray> birth, death, snapshot;
  vtkNew<vtkUnsignedCharArray> kind;
  vtkNew<vtkDoubleArray> value;
  ids->SetName(vis4gs::arrays::TreeGaussianId);
  vertex->SetName("Vertex");
  birth->SetName("BirthIteration");
  death->SetName("DeathIteration");
  kind->SetName("BirthKind");
  snapshot->SetName("SnapshotIteration");
  value->SetName("Value");
  for (vtkAbstractArray* a :
    std::initializer_list<vtkAbstractArray*>{ ids, vertex, birth, death, kind, snapshot, value })
  {
    a->SetNumberOfTuples(n);
  }
  for (vtkIdType k = 0; k < n; ++k)
  {
    const vis4gs::TraceStep& s = trace[k];
    ids->SetValue(k, s.GaussianId);
    vertex->SetValue(k, s.Node + 1);
    birth->SetValue(k, s.BirthIteration);
    death->SetValue(k, s.DeathIteration);
    kind->SetValue(k, static_cast<unsigned char>(s.Kind));
    snapshot->SetValue(k, s.SnapshotIteration);
    value->SetValue(k, s.Value);
  }
  for (vtkAbstractArray* a :
    std::initializer_list<vtkAbstractArray*>{ ids, vertex, birth, death, kind, snapshot, value })
  {
    result->AddColumn(a);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkGaussianGenealogyLineage::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Tree: " << this->Tree.Get() << "\n";
  os << indent << "NumberOfUnknownIds: " << this->NumberOfUnknownIds << "\n";
  os << indent << "Snapshots with values: " << this->Internals->Snapshots.size() << "\n";
}

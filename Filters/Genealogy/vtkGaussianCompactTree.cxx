/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCompactTree.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianCompactTree.h"

#include "vtkDataSetAttributes.h"
#include "vtkGraphEdge.h"
#include "vtkObjectFactory.h"

vtkStandardNewMacro(vtkGaussianCompactTree);

//------------------------------------------------------------------------------
vtkGaussianCompactTree::vtkGaussianCompactTree() = default;

//------------------------------------------------------------------------------
vtkGaussianCompactTree::~vtkGaussianCompactTree() = default;

//------------------------------------------------------------------------------
bool vtkGaussianCompactTree::SetStructure(Structure&& structure)
{
  const std::size_t nv = structure.InEdges.size();
  const bool consistent = structure.OutOffsets.size() == nv + 1 &&
    (nv == 0 ||
      (structure.OutOffsets.front() == 0 &&
        structure.OutOffsets.back() == static_cast<vtkIdType>(structure.OutEdges.size()) &&
        structure.OutEdges.size() + 1 == nv));
  this->Initialize();
  if (!consistent)
  {
    vtkErrorMacro("inconsistent structure: " << nv << " vertices, " << structure.OutEdges.size()
                                             << " edges, " << structure.OutOffsets.size()
                                             << " offsets");
    return false;
  }
  this->Edges = std::make_shared<const Structure>(std::move(structure));
  this->Root = nv > 0 ? 0 : -1;
  this->Modified();
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianCompactTree::CheckVertex(vtkIdType v)
{
  if (v < 0 || v >= static_cast<vtkIdType>(this->Edges->InEdges.size()))
  {
    vtkErrorMacro("Vertex index out of range: " << v);
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianCompactTree::GetNumberOfVertices()
{
  return this->Edges ? static_cast<vtkIdType>(this->Edges->InEdges.size())
                     : this->Superclass::GetNumberOfVertices();
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianCompactTree::GetNumberOfEdges()
{
  return this->Edges ? static_cast<vtkIdType>(this->Edges->OutEdges.size())
                     : this->Superclass::GetNumberOfEdges();
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::GetOutEdges(vtkIdType v,
  const vtkOutEdgeType*& edges,
  vtkIdType& nedges)
{
  if (!this->Edges)
  {
    this->Superclass::GetOutEdges(v, edges, nedges);
    return;
  }
  edges = nullptr;
  nedges = 0;
  if (this->CheckVertex(v))
  {
    const vtkIdType b = this->Edges->OutOffsets[v];
    nedges = this->Edges->OutOffsets[v + 1] - b;
    edges = nedges > 0 ? this->Edges->OutEdges.data() + b : nullptr;
  }
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::GetInEdges(vtkIdType v, const vtkInEdgeType*& edges, vtkIdType& nedges)
{
  if (!this->Edges)
  {
    this->Superclass::GetInEdges(v, edges, nedges);
    return;
  }
  edges = nullptr;
  nedges = 0;
  if (this->CheckVertex(v) && v != this->Root)
  {
    edges = this->Edges->InEdges.data() + v;
    nedges = 1;
  }
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianCompactTree::GetOutDegree(vtkIdType v)
{
  if (!this->Edges)
  {
    return this->Superclass::GetOutDegree(v);
  }
  const vtkOutEdgeType* edges;
  vtkIdType n;
  this->GetOutEdges(v, edges, n);
  return n;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianCompactTree::GetInDegree(vtkIdType v)
{
  if (!this->Edges)
  {
    return this->Superclass::GetInDegree(v);
  }
  const vtkInEdgeType* edges;
  vtkIdType n;
  this->GetInEdges(v, edges, n);
  return n;
}

//------------------------------------------------------------------------------
vtkIdType vtkGaussianCompactTree::GetDegree(vtkIdType v)
{
  if (!this->Edges)
  {
    return this->Superclass::GetDegree(v);
  }
  return this->GetInDegree(v) + this->GetOutDegree(v);
}

//------------------------------------------------------------------------------
vtkOutEdgeType vtkGaussianCompactTree::GetOutEdge(vtkIdType v, vtkIdType index)
{
  if (!this->Edges)
  {
    return this->Superclass::GetOutEdge(v, index);
  }
  const vtkOutEdgeType* edges;
  vtkIdType n;
  this->GetOutEdges(v, edges, n);
  if (index < 0 || index >= n)
  {
    vtkErrorMacro("Out edge index out of bounds");
    return vtkOutEdgeType();
  }
  return edges[index];
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::GetOutEdge(vtkIdType v, vtkIdType index, vtkGraphEdge* e)
{
  const vtkOutEdgeType oe = this->GetOutEdge(v, index);
  e->SetId(oe.Id);
  e->SetSource(v);
  e->SetTarget(oe.Target);
}

//------------------------------------------------------------------------------
vtkInEdgeType vtkGaussianCompactTree::GetInEdge(vtkIdType v, vtkIdType index)
{
  if (!this->Edges)
  {
    return this->Superclass::GetInEdge(v, index);
  }
  const vtkInEdgeType* edges;
  vtkIdType n;
  this->GetInEdges(v, edges, n);
  if (index < 0 || index >= n)
  {
    vtkErrorMacro("In edge index out of bounds");
    return vtkInEdgeType();
  }
  return edges[index];
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::GetInEdge(vtkIdType v, vtkIdType index, vtkGraphEdge* e)
{
  const vtkInEdgeType ie = this->GetInEdge(v, index);
  e->SetId(ie.Id);
  e->SetSource(ie.Source);
  e->SetTarget(v);
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::ReorderChildren(vtkIdType parent, vtkIdTypeArray* children)
{
  if (!this->Edges)
  {
    this->Superclass::ReorderChildren(parent, children);
    return;
  }
  vtkErrorMacro("ReorderChildren: a vtkGaussianCompactTree is read-only");
}

//------------------------------------------------------------------------------
std::shared_ptr<const vtkGaussianCompactTree::Structure> vtkGaussianCompactTree::EdgesOf(
  vtkDataObject* src)
{
  vtkGaussianCompactTree* compact = vtkGaussianCompactTree::SafeDownCast(src);
  return compact ? compact->Edges : nullptr;
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::ShallowCopy(vtkDataObject* src)
{
  auto edges = EdgesOf(src);
  this->Superclass::ShallowCopy(src);
  this->Edges = edges;
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::DeepCopy(vtkDataObject* src)
{
  auto edges = EdgesOf(src);
  this->Superclass::DeepCopy(src);
  this->Edges = edges;
}

//------------------------------------------------------------------------------
bool vtkGaussianCompactTree::CheckedShallowCopy(vtkGraph* g)
{
  auto edges = EdgesOf(g);
  const bool ok = this->Superclass::CheckedShallowCopy(g);
  this->Edges = ok ? edges : nullptr;
  return ok;
}

//------------------------------------------------------------------------------
bool vtkGaussianCompactTree::CheckedDeepCopy(vtkGraph* g)
{
  auto edges = EdgesOf(g);
  const bool ok = this->Superclass::CheckedDeepCopy(g);
  this->Edges = ok ? edges : nullptr;
  return ok;
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::CopyStructure(vtkGraph* g)
{
  auto edges = EdgesOf(g);
  this->Superclass::CopyStructure(g);
  this->Edges = edges;
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::Initialize()
{
  this->Edges.reset();
  this->Superclass::Initialize();
}

//------------------------------------------------------------------------------
unsigned long vtkGaussianCompactTree::GetActualMemorySize()
{
  unsigned long size = this->Superclass::GetActualMemorySize();
  if (this->Edges)
  {
    const std::size_t bytes = this->Edges->InEdges.capacity() * sizeof(vtkInEdgeType) +
      this->Edges->OutEdges.capacity() * sizeof(vtkOutEdgeType) +
      this->Edges->OutOffsets.capacity() * sizeof(vtkIdType);
    size += static_cast<unsigned long>(bytes / 1024);
  }
  return size;
}

//------------------------------------------------------------------------------
void vtkGaussianCompactTree::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Compact structure: " << (this->Edges ? "yes" : "no (vtkTree's own)") << "\n";
  if (this->Edges)
  {
    os << indent << "Vertices: " << this->Edges->InEdges.size() << "\n";
    os << indent << "Edges: " << this->Edges->OutEdges.size() << "\n";
  }
}

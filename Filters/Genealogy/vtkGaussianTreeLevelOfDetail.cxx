/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianTreeLevelOfDetail.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianTreeLevelOfDetail.h"

#include "vtkGaussianGenealogyAdapter.h"

#include "GenealogyLevelOfDetail.h"

#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTimerLog.h"
#include "vtkTree.h"

#include <algorithm>

vtkStandardNewMacro(vtkGaussianTreeLevelOfDetail);

//------------------------------------------------------------------------------
class vtkGaussianTreeLevelOfDetail::vtkInternals
{
public:
  std::shared_ptr<vis4gs::Genealogy> Genealogy;
  std::unique_ptr<vis4gs::GenealogyLevelOfDetail> Index;
  vtkTree* Tree = nullptr;
  vtkMTimeType TreeTime = 0;
  std::vector<std::int64_t> Visible;
};

//------------------------------------------------------------------------------
vtkGaussianTreeLevelOfDetail::vtkGaussianTreeLevelOfDetail()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(2);
}

//------------------------------------------------------------------------------
vtkGaussianTreeLevelOfDetail::~vtkGaussianTreeLevelOfDetail() = default;

//------------------------------------------------------------------------------
void vtkGaussianTreeLevelOfDetail::SetSelectedGaussianIds(vtkIdTypeArray* ids)
{
  if (this->SelectedGaussianIds != ids)
  {
    this->SelectedGaussianIds = ids;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
vtkIdTypeArray* vtkGaussianTreeLevelOfDetail::GetSelectedGaussianIds()
{
  return this->SelectedGaussianIds;
}

//------------------------------------------------------------------------------
vtkSelection* vtkGaussianTreeLevelOfDetail::GetVisibleSelection()
{
  return vtkSelection::SafeDownCast(this->GetOutputDataObject(1));
}

//------------------------------------------------------------------------------
int vtkGaussianTreeLevelOfDetail::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTree");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkSelection");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkGaussianTreeLevelOfDetail::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTree");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkSelection");
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkGaussianTreeLevelOfDetail::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTree* input = vtkTree::GetData(inputVector[0]);
  vtkSelection* selectionIn = vtkSelection::GetData(inputVector[1]);
  vtkTree* output = vtkTree::GetData(outputVector, 0);
  vtkSelection* visibleOut = vtkSelection::GetData(outputVector, 1);
  this->IndexSeconds = 0.0;
  this->QuerySeconds = 0.0;
  this->QueryCPUSeconds = 0.0;
  this->NumberOfVisibleVertices = 0;
  this->NumberOfUnknownSelectedIds = 0;
  if (!input || !output || !visibleOut)
  {
    vtkErrorMacro("missing input tree or outputs");
    return 0;
  }
  vtkInternals& in = *this->Internals;
  std::string error;

  // Core genealogy and grid index, once per input tree.
  vtkNew<vtkTimerLog> timer;
  if (!in.Index || in.Tree != input || in.TreeTime != input->GetMTime())
  {
    timer->StartTimer();
    in.Index.reset();
    in.Genealogy = vtkGaussianGenealogyAdapter::FromTree(input, error);
    if (!in.Genealogy)
    {
      vtkErrorMacro("" << error);
      return 0;
    }
    in.Index.reset(new vis4gs::GenealogyLevelOfDetail(*in.Genealogy));
    in.Tree = input;
    in.TreeTime = input->GetMTime();
    timer->StopTimer();
    this->IndexSeconds = timer->GetElapsedTime();
  }
  const vis4gs::Genealogy& g = *in.Genealogy;

  // Selection: input port 1 and SelectedGaussianIds.
  vtkIdType unknown = 0;
  std::vector<std::int64_t> selected =
    vtkGaussianGenealogyAdapter::NodesFromSelection(g, selectionIn, unknown, error);
  if (!error.empty())
  {
    vtkErrorMacro("" << error);
    return 0;
  }
  if (this->SelectedGaussianIds)
  {
    for (vtkIdType i = 0; i < this->SelectedGaussianIds->GetNumberOfTuples(); ++i)
    {
      const std::int64_t node = g.FindNode(this->SelectedGaussianIds->GetValue(i));
      if (node >= 0)
      {
        selected.push_back(node);
      }
      else
      {
        ++unknown;
      }
    }
  }
  this->NumberOfUnknownSelectedIds = unknown;
  if (unknown > 0)
  {
    vtkWarningMacro(<< unknown << " selected id(s) are not in the tree and were ignored");
  }

  vis4gs::ZoomParameters zoom;
  zoom.ZMin = this->ZoomMin;
  zoom.ZMax = this->ZoomMax;
  zoom.K = this->ZoomExponent;
  vis4gs::GenealogyViewport viewport;
  viewport.MinIteration = this->IterationRange[0];
  viewport.MaxIteration = this->IterationRange[1];
  viewport.MinRow = this->RowRange[0];
  viewport.MaxRow = this->RowRange[1];
  timer->StartTimer();
  const double cpu = vtkGaussianGenealogyAdapter::ThreadCpuSeconds();
  try
  {
    this->Threshold = vis4gs::ZoomThreshold(this->Zoom, zoom);
    in.Index->Query(this->Threshold, selected, viewport, in.Visible);
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("" << e.what());
    return 0;
  }
  std::vector<std::int64_t>& visible = in.Visible;
  // Sorted vertex order: a comparison sort for small results, a bitmap pass for large ones.
  const std::int64_t nodes = g.GetNumberOfNodes();
  if (static_cast<std::int64_t>(visible.size()) * 16 < nodes)
  {
    std::sort(visible.begin(), visible.end());
  }
  else
  {
    std::vector<std::uint64_t> bits(static_cast<std::size_t>(nodes / 64 + 1), 0);
    for (std::int64_t v : visible)
    {
      bits[v >> 6] |= std::uint64_t(1) << (v & 63);
    }
    visible.clear();
    for (std::size_t w = 0; w < bits.size(); ++w)
    {
      for (std::uint64_t word = bits[w]; word; word &= word - 1)
      {
        visible.push_back(static_cast<std::int64_t>(w * 64 + __builtin_ctzll(word)));
      }
    }
  }
  timer->StopTimer();
  this->QuerySeconds = timer->GetElapsedTime();
  this->QueryCPUSeconds = vtkGaussianGenealogyAdapter::ThreadCpuSeconds() - cpu;
  const vtkIdType m = static_cast<vtkIdType>(visible.size());
  this->NumberOfVisibleVertices = m;

  // Port 1: visible vertices of the input tree.
  vtkNew<vtkIdTypeArray> vertices;
  vertices->SetNumberOfTuples(m);
  for (vtkIdType k = 0; k < m; ++k)
  {
    vertices->SetValue(k, visible[k] + 1);
  }
  vtkNew<vtkSelectionNode> node;
  node->SetFieldType(vtkSelectionNode::VERTEX);
  node->SetContentType(vtkSelectionNode::INDICES);
  node->SetSelectionList(vertices);
  visibleOut->RemoveAllNodes();
  visibleOut->AddNode(node);

  if (!this->BuildVisibleTree)
  {
    return 1;
  }
  // Port 0: each visible node under its nearest visible ancestor. map[u]: >= 1 new vertex of
  // a visible node; <= -2 hidden node whose nearest visible ancestor is vertex -map[u] - 2;
  // -1 not seen yet. Every hidden node is walked at most once.
  const std::vector<std::int64_t>& parent = g.GetParents();
  std::vector<vtkIdType> map(static_cast<std::size_t>(g.GetNumberOfNodes()), -1);
  std::vector<vtkIdType> newParents(static_cast<std::size_t>(m));
  std::vector<std::int64_t> path;
  for (vtkIdType k = 0; k < m; ++k)
  {
    const std::int64_t v = visible[k];
    std::int64_t u = parent[v];
    path.clear();
    while (u >= 0 && map[u] == -1)
    {
      path.push_back(u);
      u = parent[u];
    }
    const vtkIdType ancestor = u < 0 ? 0 : (map[u] >= 1 ? map[u] : -map[u] - 2);
    for (std::int64_t w : path)
    {
      map[w] = -ancestor - 2;
    }
    newParents[k] = ancestor - 1;
    map[v] = k + 1;
  }
  map = std::vector<vtkIdType>();

  vtkNew<vtkIdList> vertexIds;
  vertexIds->SetNumberOfIds(m + 1);
  vertexIds->SetId(0, 0);
  vtkNew<vtkIdList> edgeIds;
  edgeIds->SetNumberOfIds(m);
  for (vtkIdType k = 0; k < m; ++k)
  {
    vertexIds->SetId(k + 1, visible[k] + 1);
    edgeIds->SetId(k, visible[k]);
  }
  vtkNew<vtkDataSetAttributes> vd;
  vtkDataSetAttributes* inVD = input->GetVertexData();
  for (int a = 0; a < inVD->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* src = inVD->GetAbstractArray(a);
    vtkSmartPointer<vtkAbstractArray> dst = vtk::TakeSmartPointer(src->NewInstance());
    dst->SetName(src->GetName());
    dst->SetNumberOfComponents(src->GetNumberOfComponents());
    dst->SetNumberOfTuples(vertexIds->GetNumberOfIds());
    src->GetTuples(vertexIds, dst);
    vd->AddArray(dst);
    if (src == inVD->GetPedigreeIds())
    {
      vd->SetPedigreeIds(dst);
    }
  }
  vtkNew<vtkIdTypeArray> inputVertex;
  inputVertex->SetName("InputVertexId");
  inputVertex->SetNumberOfTuples(m + 1);
  for (vtkIdType k = 0; k <= m; ++k)
  {
    inputVertex->SetValue(k, vertexIds->GetId(k));
  }
  vd->AddArray(inputVertex);
  vtkNew<vtkDataSetAttributes> ed;
  vtkDataSetAttributes* inED = input->GetEdgeData();
  for (int a = 0; a < inED->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* src = inED->GetAbstractArray(a);
    vtkSmartPointer<vtkAbstractArray> dst = vtk::TakeSmartPointer(src->NewInstance());
    dst->SetName(src->GetName());
    dst->SetNumberOfComponents(src->GetNumberOfComponents());
    dst->SetNumberOfTuples(edgeIds->GetNumberOfIds());
    src->GetTuples(edgeIds, dst);
    ed->AddArray(dst);
  }
  if (!vtkGaussianGenealogyAdapter::BuildStructure(newParents, output, vd, ed, error))
  {
    vtkErrorMacro("" << error);
    return 0;
  }
  output->GetFieldData()->ShallowCopy(input->GetFieldData());
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianTreeLevelOfDetail::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Zoom: " << this->Zoom << "\n";
  os << indent << "ZoomMin: " << this->ZoomMin << "\n";
  os << indent << "ZoomMax: " << this->ZoomMax << "\n";
  os << indent << "ZoomExponent: " << this->ZoomExponent << "\n";
  os << indent << "IterationRange: " << this->IterationRange[0] << " " << this->IterationRange[1]
     << "\n";
  os << indent << "RowRange: " << this->RowRange[0] << " " << this->RowRange[1] << "\n";
  os << indent << "SelectedGaussianIds: " << this->SelectedGaussianIds.Get() << "\n";
  os << indent << "BuildVisibleTree: " << this->BuildVisibleTree << "\n";
  os << indent << "Threshold: " << this->Threshold << "\n";
  os << indent << "NumberOfVisibleVertices: " << this->NumberOfVisibleVertices << "\n";
  os << indent << "NumberOfUnknownSelectedIds: " << this->NumberOfUnknownSelectedIds << "\n";
  os << indent << "IndexSeconds: " << this->IndexSeconds << "\n";
  os << indent << "QuerySeconds: " << this->QuerySeconds << "\n";
  os << indent << "QueryCPUSeconds: " << this->QueryCPUSeconds << "\n";
}

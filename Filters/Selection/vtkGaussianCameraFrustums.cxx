/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCameraFrustums.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianCameraFrustums.h"

#include "ScreenSelection.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSIdColumn.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSelection.h"
#include "vtkSelectionNode.h"
#include "vtkTable.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <memory>
#include <numeric>
#include <vector>

vtkStandardNewMacro(vtkGaussianCameraFrustums);
vtkCxxSetObjectMacro(vtkGaussianCameraFrustums, SelectedIds, vtkIdTypeArray);

//------------------------------------------------------------------------------
vtkGaussianCameraFrustums::vtkGaussianCameraFrustums()
{
  this->SetNumberOfInputPorts(2);
}

//------------------------------------------------------------------------------
vtkGaussianCameraFrustums::~vtkGaussianCameraFrustums()
{
  this->SetSelectedIds(nullptr);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkGaussianCameraFrustums::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->SelectedIds)
  {
    t = std::max(t, this->SelectedIds->GetMTime());
  }
  return t;
}

//------------------------------------------------------------------------------
void vtkGaussianCameraFrustums::SetSelection(vtkSelection* selection)
{
  for (unsigned int n = 0; selection && n < selection->GetNumberOfNodes(); ++n)
  {
    vtkSelectionNode* node = selection->GetNode(n);
    auto* list = vtkIdTypeArray::SafeDownCast(node->GetSelectionList());
    if (list &&
      (node->GetContentType() == vtkSelectionNode::PEDIGREEIDS ||
        node->GetContentType() == vtkSelectionNode::INDICES))
    {
      vtkNew<vtkIdTypeArray> copy;
      copy->DeepCopy(list);
      this->SetSelectedIds(copy);
      return;
    }
  }
  this->SetSelectedIds(nullptr);
}

//------------------------------------------------------------------------------
int vtkGaussianCameraFrustums::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
  }
  else
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianCameraFrustums::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkTable* table = vtkTable::GetData(inputVector[0]);
  vtkPolyData* scene = inputVector[1]->GetNumberOfInformationObjects() > 0
    ? vtkPolyData::GetData(inputVector[1])
    : nullptr;
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  std::vector<vis4gs::Camera> all;
  std::string error;
  if (!table || !vis4gs::TableToCameras(table, all, &error))
  {
    vtkErrorMacro(
      "vtkGaussianCameraFrustums: " << (table ? error : std::string("no camera table")));
    return 0;
  }
  std::vector<vis4gs::Camera> cams;
  std::vector<int> rows;
  for (std::size_t r = 0; r < all.size(); ++r)
  {
    if (!this->TrainingViewsOnly || all[r].Split == vis4gs::CameraSplit::Train)
    {
      cams.push_back(all[r]);
      rows.push_back(static_cast<int>(r));
    }
  }

  // Counts of visible selected Gaussians.
  std::vector<std::uint32_t> counts(cams.size(), 0);
  if (scene && this->SelectedIds && this->SelectedIds->GetNumberOfTuples() > 0 && !cams.empty())
  {
    std::vector<vtkIdType> wanted(this->SelectedIds->GetPointer(0),
      this->SelectedIds->GetPointer(0) + this->SelectedIds->GetNumberOfTuples());
    std::sort(wanted.begin(), wanted.end());
    const vtkIdType n = scene->GetNumberOfPoints();
    vtkDataArray* ids = scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId);
    const bool haveIds = ids && ids->GetNumberOfTuples() == n;
    // The selected rows. A sorted id column (a snapshot's) is searched for the sorted ids in
    // O(selection) (Vis4GSIdColumn.h), instead of looking every row up among the wanted ids.
    std::vector<std::uint32_t> rows;
    std::vector<vtkIdType> found;
    if (haveIds &&
      vis4gs::RowsOfSortedIds(vtkIdTypeArray::SafeDownCast(ids),
        wanted.data(),
        static_cast<vtkIdType>(wanted.size()),
        found))
    {
      rows.assign(found.begin(), found.end());
    }
    else
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        const vtkIdType id = haveIds ? static_cast<vtkIdType>(ids->GetComponent(i, 0)) : i;
        if (std::binary_search(wanted.begin(), wanted.end(), id))
        {
          rows.push_back(static_cast<std::uint32_t>(i));
        }
      }
    }
    // CountVisibleInViews projects only the listed Gaussians: the scene's own Core form when
    // its arrays are one (a reader's cloud, no copy), else a copy of the selected rows only
    // (not of the scene: 1M Gaussians with SH degree 3 are 240 MB per selection change).
    std::shared_ptr<const vis4gs::GaussianCloud> cloud = vis4gs::SharedGaussianCloud(scene);
    if (!cloud)
    {
      vtkNew<vtkPolyData> subset;
      vtkNew<vtkPoints> points;
      subset->GetPointData()->CopyAllocate(scene->GetPointData());
      for (const std::uint32_t i : rows)
      {
        subset->GetPointData()->CopyData(
          scene->GetPointData(), i, points->InsertNextPoint(scene->GetPoint(i)));
      }
      subset->SetPoints(points);
      subset->GetFieldData()->ShallowCopy(scene->GetFieldData());
      auto copy = std::make_shared<vis4gs::GaussianCloud>();
      if (!vis4gs::PolyDataToGaussianCloud(subset, *copy, &error))
      {
        vtkErrorMacro("vtkGaussianCameraFrustums: " << error);
        return 0;
      }
      rows.resize(copy->Count);
      std::iota(rows.begin(), rows.end(), 0U);
      cloud = std::move(copy);
    }
    try
    {
      counts = vis4gs::CountVisibleInViews(*cloud, rows, cams);
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("vtkGaussianCameraFrustums: " << e.what());
      return 0;
    }
  }

  // Depth of the drawn rectangle.
  double depth = this->FrustumDepth;
  if (!(depth > 0))
  {
    std::vector<float> means;
    const vtkIdType n = scene ? scene->GetNumberOfPoints() : 0;
    const vtkIdType stride = std::max<vtkIdType>(1, n / 65536);
    for (vtkIdType i = 0; i < n; i += stride)
    {
      double p[3];
      scene->GetPoint(i, p);
      means.insert(means.end(), { float(p[0]), float(p[1]), float(p[2]) });
    }
    depth = vis4gs::AutoFrustumDepth(cams, means.data(), means.size() / 3);
  }

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIntArray> pointCount, cellCount, pointCamera, cellCamera;
  for (auto* a : { pointCount.Get(), cellCount.Get() })
  {
    a->SetName("VisibleSelectedCount");
  }
  for (auto* a : { pointCamera.Get(), cellCamera.Get() })
  {
    a->SetName("CameraIndex");
  }
  for (std::size_t v = 0; v < cams.size(); ++v)
  {
    std::array<std::array<double, 3>, 5> f;
    try
    {
      f = vis4gs::CameraFrustum(cams[v], depth);
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("vtkGaussianCameraFrustums: " << e.what());
      return 0;
    }
    const vtkIdType base = points->GetNumberOfPoints();
    for (const auto& p : f)
    {
      points->InsertNextPoint(p.data());
      pointCount->InsertNextValue(static_cast<int>(counts[v]));
      pointCamera->InsertNextValue(rows[v]);
    }
    const vtkIdType edges[8][2] = {
      { 0, 1 }, { 0, 2 }, { 0, 3 }, { 0, 4 }, { 1, 2 }, { 2, 3 }, { 3, 4 }, { 4, 1 }
    };
    for (const auto& e : edges)
    {
      const vtkIdType ids[2] = { base + e[0], base + e[1] };
      lines->InsertNextCell(2, ids);
      cellCount->InsertNextValue(static_cast<int>(counts[v]));
      cellCamera->InsertNextValue(rows[v]);
    }
  }
  output->SetPoints(points);
  output->SetLines(lines);
  output->GetPointData()->SetScalars(pointCount);
  output->GetPointData()->AddArray(pointCamera);
  output->GetCellData()->SetScalars(cellCount);
  output->GetCellData()->AddArray(cellCamera);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGaussianCameraFrustums::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SelectedIds: " << this->SelectedIds << "\n";
  os << indent << "FrustumDepth: " << this->FrustumDepth << "\n";
  os << indent << "TrainingViewsOnly: " << this->TrainingViewsOnly << "\n";
}

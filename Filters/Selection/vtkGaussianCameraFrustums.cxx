/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianCameraFrustums.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianCameraFrustums.h"

#include "ScreenSelection.h"
#include "ThreadCount.h"
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
#include "vtkTimeStamp.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <numeric>
#include <string>
#include <thread>
#include <vector>

namespace
{
// What a count is of: the selected ids, the scene and the camera table (identity and MTime of
// each) and the training-views switch.
using Key = std::array<vtkMTimeType, 7>;

vtkMTimeType Stamp(const void* object)
{
  return static_cast<vtkMTimeType>(reinterpret_cast<std::uintptr_t>(object));
}

struct Job
{
  Key JobKey{};
  std::shared_ptr<const vis4gs::GaussianCloud> Cloud;
  std::vector<std::uint32_t> Rows;
  std::vector<vis4gs::Camera> Cameras;
};
}

// The background count: one worker thread, the newest request replacing one not started.
struct vtkGaussianCameraFrustums::vtkInternals
{
  std::mutex Mutex; // guards everything below but Shown, ShownPending (RequestData's thread)
  std::condition_variable Wake, Idle;
  std::unique_ptr<Job> Pending;
  bool Working = false;
  Key WorkingKey{};
  bool Stop = false;
  bool Done = false;
  Key DoneKey{};
  std::vector<std::uint32_t> DoneCounts;
  std::string DoneError;
  std::thread Worker;
  std::mutex CallbackMutex; // held while the callback runs
  std::function<void()> Callback;
  std::vector<std::uint32_t> Shown; // the counts last output
  bool ShownPending = false;
  Key ShownKey{};         // what the counts last output wait for (while ShownPending)
  vtkTimeStamp ShownDone; // GetMTime: when they were found done
  // The automatic depth last computed and what it is of (RequestData's thread only).
  double AutoDepth = 0;
  Key AutoDepthKey{};
  bool AutoDepthValid = false;

  void Run()
  {
    // A background job: the GUI thread runs first (the OpenMP team inherits it).
    vis4gs::LowerThreadPriority(vis4gs::BackgroundThreadNice);
    std::unique_lock<std::mutex> lock(this->Mutex);
    for (;;)
    {
      this->Wake.wait(lock, [this] { return this->Stop || this->Pending; });
      if (this->Stop)
      {
        return;
      }
      const std::unique_ptr<Job> job = std::move(this->Pending);
      this->Working = true;
      this->WorkingKey = job->JobKey;
      lock.unlock();
      std::vector<std::uint32_t> counts;
      std::string error;
      try
      {
        counts = vis4gs::CountVisibleInViews(*job->Cloud, job->Rows, job->Cameras);
      }
      catch (const std::exception& e)
      {
        error = e.what();
      }
      lock.lock();
      this->Done = true;
      this->DoneKey = job->JobKey;
      this->DoneCounts = std::move(counts);
      this->DoneError = std::move(error);
      lock.unlock();
      {
        std::lock_guard<std::mutex> callbackLock(this->CallbackMutex);
        if (this->Callback)
        {
          this->Callback();
        }
      }
      lock.lock();
      this->Working = false;
      this->Idle.notify_all();
    }
  }
};

vtkStandardNewMacro(vtkGaussianCameraFrustums);
vtkCxxSetObjectMacro(vtkGaussianCameraFrustums, SelectedIds, vtkIdTypeArray);

//------------------------------------------------------------------------------
vtkGaussianCameraFrustums::vtkGaussianCameraFrustums()
  : Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(2);
}

//------------------------------------------------------------------------------
vtkGaussianCameraFrustums::~vtkGaussianCameraFrustums()
{
  vtkInternals& in = *this->Internals;
  {
    std::lock_guard<std::mutex> lock(in.Mutex);
    in.Stop = true;
    in.Pending.reset();
  }
  in.Wake.notify_all();
  if (in.Worker.joinable())
  {
    in.Worker.join();
  }
  this->SetSelectedIds(nullptr);
}

//------------------------------------------------------------------------------
void vtkGaussianCameraFrustums::SetCountsReadyCallback(std::function<void()> callback)
{
  std::lock_guard<std::mutex> lock(this->Internals->CallbackMutex);
  this->Internals->Callback = std::move(callback);
}

//------------------------------------------------------------------------------
bool vtkGaussianCameraFrustums::GetCountsPending()
{
  return this->Internals->ShownPending;
}

//------------------------------------------------------------------------------
void vtkGaussianCameraFrustums::WaitForCounts()
{
  vtkInternals& in = *this->Internals;
  std::unique_lock<std::mutex> lock(in.Mutex);
  in.Idle.wait(lock, [&in] { return !in.Working && !in.Pending; });
}

//------------------------------------------------------------------------------
vtkMTimeType vtkGaussianCameraFrustums::GetMTime()
{
  vtkInternals& in = *this->Internals;
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->SelectedIds)
  {
    t = std::max(t, this->SelectedIds->GetMTime());
  }
  if (in.ShownPending)
  {
    // The counts the last output waits for are done: newer than that output, however early the
    // worker finished. (A time stamped by the worker when done was older than the output when
    // the count finished before the update that asked for it ended, which then looked up to
    // date: the frustums kept the counts of the selection before.)
    std::lock_guard<std::mutex> lock(in.Mutex);
    if (in.Done && in.DoneKey == in.ShownKey)
    {
      in.ShownDone.Modified();
      t = std::max(t, in.ShownDone.GetMTime());
    }
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
    // The hub's ids come sorted: used in place, copied and sorted otherwise.
    const vtkIdType* given = this->SelectedIds->GetPointer(0);
    const vtkIdType count = this->SelectedIds->GetNumberOfTuples();
    std::vector<vtkIdType> sorted;
    if (!std::is_sorted(given, given + count))
    {
      sorted.assign(given, given + count);
      std::sort(sorted.begin(), sorted.end());
      given = sorted.data();
    }
    const vtkIdType* wantedBegin = given;
    const vtkIdType* wantedEnd = given + count;
    const vtkIdType n = scene->GetNumberOfPoints();
    vtkDataArray* ids = scene->GetPointData()->GetArray(vis4gs::arrays::GaussianId);
    const bool haveIds = ids && ids->GetNumberOfTuples() == n;
    // The selected rows. A sorted id column (a snapshot's) is searched for the sorted ids in
    // O(selection) (Vis4GSIdColumn.h), instead of looking every row up among the wanted ids.
    std::vector<std::uint32_t> rows;
    rows.reserve(static_cast<std::size_t>(count));
    const bool searched = haveIds &&
      vis4gs::ForEachRowOfIds(vtkIdTypeArray::SafeDownCast(ids),
        given,
        count,
        [&](vtkIdType r) { rows.push_back(static_cast<std::uint32_t>(r)); });
    if (!searched)
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        const vtkIdType id = haveIds ? static_cast<vtkIdType>(ids->GetComponent(i, 0)) : i;
        if (std::binary_search(wantedBegin, wantedEnd, id))
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
    vtkInternals& in = *this->Internals;
    const Key key = { Stamp(this->SelectedIds),
      this->SelectedIds->GetMTime(),
      Stamp(scene),
      scene->GetMTime(),
      Stamp(table),
      table->GetMTime(),
      static_cast<vtkMTimeType>(this->TrainingViewsOnly) };
    bool background = false, counted = false;
    {
      std::lock_guard<std::mutex> lock(in.Mutex);
      background = in.Callback && this->BackgroundCountMinimum > 0 &&
        static_cast<vtkIdType>(rows.size()) > this->BackgroundCountMinimum;
      if (background && in.Done && in.DoneKey == key)
      {
        if (!in.DoneError.empty())
        {
          in.ShownPending = false; // (reported once)
          vtkErrorMacro("vtkGaussianCameraFrustums: " << in.DoneError);
          return 0;
        }
        counts = in.DoneCounts;
        background = false;
        counted = true; // (by the worker: output as if made here)
      }
      else if (background)
      {
        if (!(in.Pending && in.Pending->JobKey == key) && !(in.Working && in.WorkingKey == key))
        {
          auto job = std::make_unique<Job>();
          job->JobKey = key;
          job->Cloud = cloud;
          job->Rows = std::move(rows);
          job->Cameras = cams;
          in.Pending = std::move(job);
          if (!in.Worker.joinable())
          {
            in.Worker = std::thread([&in] { in.Run(); });
          }
          in.Wake.notify_one();
        }
        // Until the worker is done: the counts last output, when they are of these cameras.
        if (in.Shown.size() == cams.size())
        {
          counts = in.Shown;
        }
      }
    }
    in.ShownPending = background;
    in.ShownKey = key;
    if (!background && !counted)
    {
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
  }
  else
  {
    this->Internals->ShownPending = false;
  }
  this->Internals->Shown = counts;

  // Depth of the drawn rectangle: the automatic one depends on the scene and the cameras
  // only, and is kept until they change (a selection change does not sample the scene again).
  double depth = this->FrustumDepth;
  vtkInternals& in = *this->Internals;
  const Key depthKey = { Stamp(scene),
    scene ? scene->GetMTime() : 0,
    Stamp(table),
    table->GetMTime(),
    static_cast<vtkMTimeType>(this->TrainingViewsOnly),
    0,
    0 };
  if (!(depth > 0) && in.AutoDepthValid && in.AutoDepthKey == depthKey)
  {
    depth = in.AutoDepth;
  }
  else if (!(depth > 0))
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
    in.AutoDepth = depth;
    in.AutoDepthKey = depthKey;
    in.AutoDepthValid = true;
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
  os << indent << "BackgroundCountMinimum: " << this->BackgroundCountMinimum << "\n";
  os << indent << "CountsPending: " << this->Internals->ShownPending << "\n";
}

/*=========================================================================

  Program:   Vis4GS
  Module:    vtkGaussianArtifactScoreFilter.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "vtkGaussianArtifactScoreFilter.h"

#include "ArtifactScores.h"
#include "ImageIO.h"
#include "ScoreRegistry.h"
#include "Vis4GSDataModel.h"
#include "Vis4GSNodeSharedMemory.h"
#include "Vis4GSTrainingImages.h"

#include "vtkCommunicator.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

vtkStandardNewMacro(vtkGaussianArtifactScoreFilter);
vtkCxxSetObjectMacro(vtkGaussianArtifactScoreFilter, Controller, vtkMultiProcessController);

namespace
{
// The array takes the vector's memory: a copy would hold the scores twice at the peak.
void AddArray(vtkPolyData* output, const char* name, std::vector<double>&& values)
{
  output->GetPointData()->AddArray(
    vis4gs::AdoptVector<vtkDoubleArray>(name, std::move(values)).GetPointer());
}

// Thrown by the progress callback when StopExecution() was called: not a std::exception, so
// that no handler of the computation's own errors takes it for one.
struct ExecutionStopped
{
};

// The first stage of progressive scores: every 8th of the views, maps at 1/4 of the resolution
// (at most 1/8), about 1/128 of the exact pass's pixels.
void ApplyStage(int stage, int& viewStride, int& lossResolution, int& coverageResolution)
{
  if (stage == 1)
  {
    viewStride *= 8;
    lossResolution = std::min(8, 4 * lossResolution);
    coverageResolution = std::min(8, 4 * coverageResolution);
  }
}

std::string EveryKth(int k)
{
  if (k <= 1)
  {
    return "every training view";
  }
  const int tens = k % 100 / 10, last = k % 10;
  const char* suffix =
    tens == 1 ? "th" : (last == 1 ? "st" : (last == 2 ? "nd" : (last == 3 ? "rd" : "th")));
  return "every " + std::to_string(k) + suffix + " training view";
}

std::string Fraction(int factor)
{
  return factor <= 1 ? "full" : "1/" + std::to_string(factor);
}

char ViewInProgress[256] = "";

void SetViewInProgress(const std::string& text)
{
  // The first byte is written last, so a signal handler reads "" or the whole text.
  ViewInProgress[0] = '\0';
  const std::size_t n = std::min(text.size(), sizeof(ViewInProgress) - 1);
  if (n > 0)
  {
    std::memcpy(ViewInProgress + 1, text.data() + 1, n - 1);
    ViewInProgress[n] = '\0';
    ViewInProgress[0] = text[0];
  }
}

// Fault injection for the tests (Applications/vis4gs/Testing/AnalyzeMPI.sh):
// VIS4GS_TEST_KILL_VIEW=R:V makes process R raise SIGTERM when it starts camera V (V = "any":
// its first view), as if it were killed there.
void MaybeKillForTest(int rank, std::size_t view)
{
  const char* spec = std::getenv("VIS4GS_TEST_KILL_VIEW");
  if (!spec)
  {
    return;
  }
  int r = -1;
  char which[32] = "";
  if (std::sscanf(spec, "%d:%31s", &r, which) == 2 && r == rank &&
    (std::string(which) == "any" || std::string(which) == std::to_string(view)))
  {
    std::raise(SIGTERM);
  }
}

// The MPI path (see SetController): the partials of this process's views, summed over the
// processes, finished on every process.
bool ComputeDistributed(vtkGaussianArtifactScoreFilter* self,
  vtkMultiProcessController* controller,
  const vis4gs::GaussianCloud& cloud,
  const std::vector<vis4gs::Camera>& cameras,
  const vis4gs::ScoreSettings& settings,
  const vis4gs::TrainingImageProvider& images,
  vis4gs::GaussianScores& scores,
  vtkIdType& rendered,
  int& preparationProcesses,
  double seconds[2])
{
  preparationProcesses = 1;
  const auto start = std::chrono::steady_clock::now();
  const int rank = controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  const bool needCameras = settings.Request.NeedsCameras();
  vis4gs::ScorePartials partials;
  std::string error;
  std::size_t current = static_cast<std::size_t>(-1);
  try
  {
    // Every process computes the same split from the same scene, cameras and settings.
    std::vector<std::size_t> views, machineViews;
    std::vector<double> costs;
    std::vector<int> owner;
    if (needCameras)
    {
      views = vis4gs::SelectViews(cameras, settings);
      costs = vis4gs::EstimateViewCosts(cloud, cameras, views, settings);
      owner = vis4gs::SplitViewsByCost(costs, ranks);
    }
    // (collective: every process or none, the same settings on each)
    std::unique_ptr<Vis4GSNodeSharedMemory> queue;
    std::atomic<std::uint64_t>* taken = nullptr;
    if (needCameras && (settings.Request.Blur || settings.Request.Needle) &&
      self->GetDynamicViewBalancing())
    {
      static_assert(std::atomic<std::uint64_t>::is_always_lock_free,
        "the queue's counter is shared between processes");
      queue.reset(new Vis4GSNodeSharedMemory(controller));
      // (zero-filled: the counter starts at 0 on every process of the machine)
      taken = static_cast<std::atomic<std::uint64_t>*>(queue->Map(4096));
      if (taken)
      {
        // This machine's views (its processes' parts of the split), the costliest first: the
        // last views taken are the cheapest, so the processes finish close together.
        for (std::size_t k = 0; k < views.size(); ++k)
        {
          if (queue->LeaderOf(owner[k]) == queue->LeaderOf(rank))
          {
            machineViews.push_back(k);
          }
        }
        std::stable_sort(machineViews.begin(),
          machineViews.end(),
          [&costs](std::size_t a, std::size_t b) { return costs[a] > costs[b]; });
        for (std::size_t& k : machineViews)
        {
          k = views[k];
        }
      }
      else
      {
        vtkWarningWithObjectMacro(self,
          "process " << rank << " of " << ranks
                     << ": the processes of this machine could not share a queue of views ("
                     << (queue->Failure().empty() ? std::string("failed on another process")
                                                  : queue->Failure())
                     << "); each renders the views of the split by estimated cost");
      }
    }
    std::vector<std::size_t> own;
    for (std::size_t k = 0; !taken && k < views.size(); ++k)
    {
      if (owner[k] == rank)
      {
        own.push_back(views[k]);
      }
    }
    auto progress = [self, taken, &machineViews](std::size_t done, std::size_t total)
    {
      if (taken)
      {
        // The machine's share of its views taken so far (this process's count is not known
        // ahead).
        const double all = static_cast<double>(std::max<std::size_t>(1, machineViews.size()));
        self->UpdateProgress(0.95 * std::min(1.0, static_cast<double>(taken->load()) / all));
        return;
      }
      self->UpdateProgress(total > 0 ? 0.95 * static_cast<double>(done) / total : 0.95);
    };
    // (collective: every process or none, the same setting on each)
    std::unique_ptr<Vis4GSNodeSharedMemory> node;
    vis4gs::ScoreSettings local = settings;
    if (needCameras && self->GetSharePreparation())
    {
      node.reset(new Vis4GSNodeSharedMemory(controller));
      local.SharePreparation = node->Share();
    }
    auto viewStarted = [&](std::size_t view)
    {
      current = view;
      SetViewInProgress("view " + std::to_string(view) + " ('" + cameras[view].Name + "')");
      MaybeKillForTest(rank, view);
    };
    if (taken)
    {
      partials = vis4gs::ComputeScorePartials(
        cloud,
        cameras,
        local,
        [&](std::size_t& view)
        {
          const std::uint64_t k = taken->fetch_add(1);
          if (k >= machineViews.size())
          {
            return false;
          }
          view = machineViews[static_cast<std::size_t>(k)];
          return true;
        },
        images,
        progress,
        viewStarted);
    }
    else
    {
      partials =
        vis4gs::ComputeScorePartials(cloud, cameras, local, own, images, progress, viewStarted);
    }
    current = static_cast<std::size_t>(-1);
    SetViewInProgress("");
    rendered = static_cast<vtkIdType>(partials.RenderedViews.size());
    if (node && node->Mapped())
    {
      preparationProcesses = node->Parts();
    }
    else if (node && !node->Failure().empty())
    {
      vtkWarningWithObjectMacro(self,
        "process " << rank << " of " << ranks
                   << ": the processes of this machine could not share the preparation of the "
                      "projection ("
                   << node->Failure() << "); each prepared it alone");
    }
  }
  catch (const std::exception& e)
  {
    SetViewInProgress("");
    std::ostringstream message;
    message << "process " << rank << " of " << ranks;
    if (current != static_cast<std::size_t>(-1) && current < cameras.size())
    {
      message << ", view " << current << " ('" << cameras[current].Name << "')";
    }
    message << ": " << e.what();
    error = message.str();
  }
  seconds[0] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Agree on failure before any reduction, so no process waits for one that gave up.
  int failed = error.empty() ? 0 : 1, anyFailed = 0;
  controller->AllReduce(&failed, &anyFailed, 1, vtkCommunicator::MAX_OP);
  // Timed from here: the wait for the slowest process above is load imbalance, not reduction.
  const auto reduction = std::chrono::steady_clock::now();
  if (anyFailed)
  {
    if (!error.empty())
    {
      vtkErrorWithObjectMacro(self, "Scores failed on " << error);
    }
    else
    {
      vtkErrorWithObjectMacro(self,
        "Scores failed on another process (process " << rank << " of " << ranks
                                                     << " gave up with it)");
    }
    return false;
  }
  // The element-wise sums of the partials (ScorePartials says why that is exact), each slice of
  // the Gaussians summed on the process that finishes it (a reduce-scatter): no process sums or
  // finishes every Gaussian's partials, and the finished scores travel once. Everything happens
  // in the vectors of the cloud's size that the views were summed in: on a virtual machine the
  // first touch of fresh memory costs about 2.3 s of CPU a GiB (Documentation/performance.md,
  // issue 31), so buffers of a slice's or the cloud's size for the exchange would cost a
  // process about a second at 6.1M Gaussians, which one process does not pay.
  const std::size_t n = cloud.Count;
  auto sliceStart = [n, ranks](int r)
  { return static_cast<std::size_t>(static_cast<unsigned long long>(n) * r / ranks); };
  const std::size_t first = sliceStart(rank), count = sliceStart(rank + 1) - first;
  // At most this many values per MPI call: Open MPI's reduction allocates buffers of a call's
  // size, and a scratch of this size receives the sums.
  constexpr std::size_t chunk = std::size_t(1) << 19;
  static_assert(sizeof(unsigned int) == sizeof(std::uint32_t), "32-bit unsigned int");
  auto reduceScatter = [&](auto* values, auto* scratch)
  {
    for (int r = 0; r < ranks; ++r)
    {
      for (std::size_t b = sliceStart(r), e = sliceStart(r + 1); b < e; b += chunk)
      {
        const std::size_t length = std::min(chunk, e - b);
        controller->Reduce(
          values + b, scratch, static_cast<vtkIdType>(length), vtkCommunicator::SUM_OP, r);
        if (r == rank)
        {
          std::copy(scratch, scratch + length, values + b);
        }
      }
    }
  };
  {
    std::vector<double> scratch(std::min(chunk, count));
    // Every process has the same sizes (the same request): empty ones are skipped everywhere.
    for (std::vector<std::uint32_t>* counts : partials.PerGaussianCounts())
    {
      if (!counts->empty())
      {
        reduceScatter(reinterpret_cast<unsigned int*>(counts->data()),
          reinterpret_cast<unsigned int*>(scratch.data()));
      }
    }
    for (std::vector<double>* sums : partials.PerGaussianSums())
    {
      if (!sums->empty())
      {
        reduceScatter(sums->data(), scratch.data());
      }
    }
  }
  // The compensated sums (ScorePartials::BlurCompensation says why): each slice's processes'
  // sums and compensations gathered on the process that finishes it and added there in
  // process order with AddCompensated(), so that the scores do not depend on which process
  // rendered which view.
  {
    const std::size_t gatherChunk =
      std::max<std::size_t>(4096, chunk / static_cast<std::size_t>(ranks));
    std::vector<double> sums(std::min(gatherChunk, count) * ranks);
    std::vector<float> compensations(sums.size());
    for (const auto& [sum, compensation] : partials.CompensatedSums())
    {
      if (sum->empty())
      {
        continue;
      }
      for (int r = 0; r < ranks; ++r)
      {
        for (std::size_t b = sliceStart(r), e = sliceStart(r + 1); b < e; b += gatherChunk)
        {
          const std::size_t length = std::min(gatherChunk, e - b);
          const vtkIdType l = static_cast<vtkIdType>(length);
          controller->Gather(sum->data() + b, sums.data(), l, r);
          controller->Gather(compensation->data() + b, compensations.data(), l, r);
          if (r != rank)
          {
            continue;
          }
          for (std::size_t j = 0; j < length; ++j)
          {
            double s = sums[j];
            float c = compensations[j];
            for (int q = 1; q < ranks; ++q)
            {
              const std::size_t at = static_cast<std::size_t>(q) * length + j;
              vis4gs::AddCompensated(s, c, sums[at], compensations[at]);
            }
            (*sum)[b + j] = s;
            (*compensation)[b + j] = c;
          }
        }
      }
    }
  }
  unsigned long long counts[2] = { partials.ViewsScored, partials.ViewsWithoutImage },
                     totals[2] = { 0, 0 };
  controller->AllReduce(counts, totals, 2, vtkCommunicator::SUM_OP);
  partials.ViewsScored = static_cast<std::size_t>(totals[0]);
  partials.ViewsWithoutImage = static_cast<std::size_t>(totals[1]);
  vis4gs::GaussianScores part;
  std::string finishError;
  const auto finish = std::chrono::steady_clock::now();
  try
  {
    part = vis4gs::FinishGaussianScores(cloud, settings, std::move(partials), first, count);
  }
  catch (const std::exception& e)
  {
    finishError = e.what();
  }
  // (finishing is computation, as in one process's ComputeSeconds, not reduction)
  const double finishSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - finish).count();
  seconds[0] += finishSeconds;
  int finishFailed = finishError.empty() ? 0 : 1, anyFinishFailed = 0;
  controller->AllReduce(&finishFailed, &anyFinishFailed, 1, vtkCommunicator::MAX_OP);
  if (anyFinishFailed)
  {
    vtkErrorWithObjectMacro(self,
      "Scores failed on process " << rank << " of " << ranks << ": "
                                  << (finishError.empty() ? "on another process" : finishError));
    return false;
  }
  // Every process gets every slice's scores (each process's output holds them all): each
  // slice is broadcast, in place, from the process that finished it.
  auto gather = [&](auto& all, bool wanted)
  {
    if (!wanted)
    {
      std::remove_reference_t<decltype(all)>().swap(all);
      return;
    }
    all.resize(n); // (FinishGaussianScores gives the cloud's size)
    for (int r = 0; r < ranks; ++r)
    {
      for (std::size_t b = sliceStart(r), e = sliceStart(r + 1); b < e; b += chunk)
      {
        controller->Broadcast(all.data() + b, static_cast<vtkIdType>(std::min(chunk, e - b)), r);
      }
    }
  };
  const vis4gs::ScoreRequest& req = settings.Request;
  const bool views = needCameras, imageScores = needCameras && (req.Blur || req.Needle);
  gather(part.ViewCoverage, views && req.ViewCoverage);
  gather(part.BlurScore, views && req.Blur);
  gather(part.NeedleScore, views && req.Needle);
  gather(part.NeedleShape, req.NeedleShape);
  gather(part.RenderCost, req.RenderCost);
  gather(part.CostPerContribution, req.CostPerContribution);
  gather(part.Flags, true);
  gather(part.CoverageViews, views && req.ViewCoverage);
  gather(part.ScoredViews, imageScores);
  unsigned long long flagged[4] = { part.NoCoverageViewCount,
    part.NoScoredViewCount,
    part.InvalidCount,
    part.NotEvaluatedCount },
                     flaggedAll[4] = { 0, 0, 0, 0 };
  controller->AllReduce(flagged, flaggedAll, 4, vtkCommunicator::SUM_OP);
  part.NoCoverageViewCount = static_cast<std::size_t>(flaggedAll[0]);
  part.NoScoredViewCount = static_cast<std::size_t>(flaggedAll[1]);
  part.InvalidCount = static_cast<std::size_t>(flaggedAll[2]);
  part.NotEvaluatedCount = static_cast<std::size_t>(flaggedAll[3]);
  part.Warnings = vis4gs::ScoreWarnings(part, settings.Request, n);
  scores = std::move(part);
  seconds[1] = std::chrono::duration<double>(std::chrono::steady_clock::now() - reduction).count() -
    finishSeconds;
  return true;
}
}

//------------------------------------------------------------------------------
vtkGaussianArtifactScoreFilter::vtkGaussianArtifactScoreFilter()
{
  this->SetNumberOfInputPorts(2);
  for (const vis4gs::ScoreDefinition& d : vis4gs::ScoreDefinitions())
  {
    this->EnabledScores.push_back(d.DefaultOn);
  }
}

//------------------------------------------------------------------------------
bool vtkGaussianArtifactScoreFilter::SetScores(const char* list)
{
  std::vector<const vis4gs::ScoreDefinition*> chosen;
  try
  {
    chosen = vis4gs::ParseScoreList(list ? list : "");
  }
  catch (const std::exception& e)
  {
    vtkErrorMacro("SetScores: " << e.what());
    return false;
  }
  std::vector<bool> enabled(this->EnabledScores.size(), false);
  for (const vis4gs::ScoreDefinition* d : chosen)
  {
    enabled[static_cast<std::size_t>(d - vis4gs::ScoreDefinitions().data())] = true;
  }
  if (enabled != this->EnabledScores)
  {
    this->EnabledScores = enabled;
    this->Modified();
  }
  return true;
}

//------------------------------------------------------------------------------
std::string vtkGaussianArtifactScoreFilter::GetScores()
{
  std::string list;
  for (std::size_t k = 0; k < this->EnabledScores.size(); ++k)
  {
    if (this->EnabledScores[k])
    {
      list += (list.empty() ? "" : ",") + std::string(vis4gs::ScoreDefinitions()[k].Name);
    }
  }
  return list;
}

//------------------------------------------------------------------------------
bool vtkGaussianArtifactScoreFilter::EnableScore(const char* name, bool on)
{
  const vis4gs::ScoreDefinition* d = vis4gs::FindScore(name ? name : "");
  if (!d)
  {
    vtkErrorMacro("EnableScore: unknown score '" << (name ? name : "") << "' (expected one of "
                                                 << vis4gs::ScoreNames() << ")");
    return false;
  }
  const std::size_t k = static_cast<std::size_t>(d - vis4gs::ScoreDefinitions().data());
  if (this->EnabledScores[k] != on)
  {
    this->EnabledScores[k] = on;
    this->Modified();
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGaussianArtifactScoreFilter::IsScoreEnabled(const char* name)
{
  const vis4gs::ScoreDefinition* d = vis4gs::FindScore(name ? name : "");
  return d && this->EnabledScores[static_cast<std::size_t>(d - vis4gs::ScoreDefinitions().data())];
}

//------------------------------------------------------------------------------
int vtkGaussianArtifactScoreFilter::GetNumberOfScoreArrays()
{
  return static_cast<int>(vis4gs::ScoreDefinitions().size());
}

//------------------------------------------------------------------------------
const char* vtkGaussianArtifactScoreFilter::GetScoreArrayName(int index)
{
  const auto& all = vis4gs::ScoreDefinitions();
  return index >= 0 && index < static_cast<int>(all.size()) ? all[index].ArrayName : nullptr;
}

//------------------------------------------------------------------------------
int vtkGaussianArtifactScoreFilter::GetScoreArrayStatus(const char* name)
{
  return this->IsScoreEnabled(name) ? 1 : 0;
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::SetScoreArrayStatus(const char* name, int status)
{
  this->EnableScore(name, status != 0);
}

//------------------------------------------------------------------------------
vtkGaussianArtifactScoreFilter::~vtkGaussianArtifactScoreFilter()
{
  this->SetController(nullptr);
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::SetCamerasData(vtkTable* cameras)
{
  this->SetInputData(1, cameras);
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::SetCamerasConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
int vtkGaussianArtifactScoreFilter::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkTable");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianArtifactScoreFilter::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkTable* table = vtkTable::GetData(inputVector[1]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  output->ShallowCopy(input);
  this->NumberOfViewsUsed = 0;
  this->NumberOfViewsWithoutImage = 0;
  this->NumberOfFlaggedGaussians = 0;
  this->NumberOfViewsRendered = 0;
  this->PreparationProcesses = 1;
  this->ComputeSeconds = this->ReductionSeconds = 0;

  vis4gs::ScoreSettings settings;
  const std::vector<vis4gs::ScoreDefinition>& registry = vis4gs::ScoreDefinitions();
  for (std::size_t k = 0; k < registry.size(); ++k)
  {
    settings.Request.*(registry[k].Request) = this->EnabledScores[k];
  }
  settings.LossResolution = this->LossResolution;
  settings.CoverageResolution = this->CoverageResolution;
  settings.ViewStride = this->ViewStride;
  ApplyStage(this->ProgressiveStage,
    settings.ViewStride,
    settings.LossResolution,
    settings.CoverageResolution);
  settings.Footprint = this->FootprintMode == 1 ? vis4gs::FootprintMode::Ellipse3Sigma
                                                : vis4gs::FootprintMode::Rasterizer;
  settings.Accumulation = this->FloatAccumulation ? vis4gs::FootprintAccumulation::Float
                                                  : vis4gs::FootprintAccumulation::Double;
  settings.OcclusionThreshold = this->OcclusionThreshold;
  settings.Lambda = this->Lambda;
  // A recorder of full-resolution renders (the clean-up's "before") takes only the exact stage.
  if (this->ProgressiveStage == 0)
  {
    settings.ViewRendered = this->ViewRendered;
  }
  const unsigned needs = vis4gs::NeedsOf(settings.Request);
  const bool needCameras = (needs & vis4gs::NeedsCameras) != 0;
  const bool needImages = (needs & vis4gs::NeedsImages) != 0;

  std::string error;
  // (no copy of a reader's scene: its arrays are a shared cloud)
  const auto shared = vis4gs::GaussianCloudOf(input, &error);
  if (!shared)
  {
    vtkErrorMacro("The input is not a Gaussian scene: " << error);
    return 0;
  }
  const vis4gs::GaussianCloud& cloud = *shared;
  std::vector<vis4gs::Camera> cameras;
  if (needCameras)
  {
    if (!table)
    {
      std::string wanting;
      for (std::size_t k = 0; k < registry.size(); ++k)
      {
        if (this->EnabledScores[k] && (registry[k].Needs & vis4gs::NeedsCameras))
        {
          wanting += (wanting.empty() ? "" : ", ") + std::string(registry[k].ArrayName);
        }
      }
      vtkErrorMacro(<< wanting
                    << " need the camera table on input port 1 (SetCamerasData / "
                       "SetCamerasConnection).");
      return 0;
    }
    if (!vis4gs::TableToCameras(table, cameras, &error))
    {
      vtkErrorMacro("The camera table is not usable: " << error);
      return 0;
    }
  }
  vis4gs::TrainingImageProvider images;
  struct Unreadable
  {
    std::mutex Mutex;
    std::vector<std::string> Messages;
  };
  auto unreadable = std::make_shared<Unreadable>();
  if (needImages)
  {
    const std::array<float, 3> background = { static_cast<float>(settings.Raster.Background[0]),
      static_cast<float>(settings.Raster.Background[1]),
      static_cast<float>(settings.Raster.Background[2]) };
    if (!Vis4GSTrainingImages(table, this->ImageDirectory, background, cameras, images, error))
    {
      vtkErrorMacro(<< error);
      return 0;
    }
    // One unreadable image must not cost every score: its view is left out of the image
    // scores, as a view without image, and a warning names the file (the reader's message).
    images = [read = std::move(images), unreadable](
               std::size_t view, const vis4gs::Camera& camera, vis4gs::Image& image)
    {
      try
      {
        return read(view, camera, image);
      }
      catch (const std::exception& e)
      {
        std::lock_guard<std::mutex> lock(unreadable->Mutex);
        unreadable->Messages.push_back(e.what());
        return false;
      }
    };
  }
  vtkMultiProcessController* controller =
    this->Controller ? this->Controller : vtkMultiProcessController::GetGlobalController();
  const int ranks = controller ? controller->GetNumberOfProcesses() : 1;
  // The score pass reports progress between views, outside its parallel loops, so a stop
  // thrown from here unwinds it there (in one process: see StopExecution()).
  auto progress = [this, ranks](std::size_t done, std::size_t total)
  {
    this->UpdateProgress(total > 0 ? static_cast<double>(done) / total : 1.0);
    if (ranks <= 1 && this->StopRequested.load())
    {
      throw ExecutionStopped{};
    }
  };
  // A request made before this execution was for an earlier one.
  this->StopRequested = false;
  this->Stopped = false;
  vtkNew<vtkStringArray> stage;
  stage->SetName("ScoreStage");
  output->GetFieldData()->AddArray(stage);
  vis4gs::GaussianScores scores;
  double seconds[2] = { 0, 0 };
  if (ranks <= 1)
  {
    try
    {
      scores = vis4gs::ComputeGaussianScores(cloud, cameras, settings, images, progress);
    }
    catch (const ExecutionStopped&)
    {
      this->Stopped = true;
      stage->InsertNextValue("stopped");
      // No score of an earlier execution that the input carried passes for this one's.
      for (const vis4gs::ScoreDefinition& d : registry)
      {
        output->GetPointData()->RemoveArray(d.ArrayName);
      }
      output->GetPointData()->RemoveArray(vis4gs::arrays::NoVisibleView);
      return 1;
    }
    catch (const std::exception& e)
    {
      vtkErrorMacro("Scores failed: " << e.what());
      return 0;
    }
    this->NumberOfViewsRendered = static_cast<vtkIdType>(scores.ViewIndices.size());
    seconds[0] = scores.Timings.Total;
  }
  else if (!ComputeDistributed(this,
             controller,
             cloud,
             cameras,
             settings,
             images,
             scores,
             this->NumberOfViewsRendered,
             this->PreparationProcesses,
             seconds))
  {
    return 0;
  }
  this->ComputeSeconds = seconds[0];
  this->ReductionSeconds = seconds[1];
  for (const std::string& warning : scores.Warnings)
  {
    vtkWarningMacro(<< warning);
  }
  for (const std::string& message : unreadable->Messages)
  {
    vtkWarningMacro("a training image cannot be read, its view is left out of the Blur and "
                    "Needle scores: "
      << message);
  }
  this->NumberOfViewsUsed = static_cast<vtkIdType>(scores.ViewsUsed);
  this->NumberOfViewsWithoutImage = static_cast<vtkIdType>(scores.ViewsWithoutImage);

  for (std::size_t k = 0; k < registry.size(); ++k)
  {
    if (this->EnabledScores[k])
    {
      AddArray(output, registry[k].ArrayName, std::move(scores.*(registry[k].Values)));
    }
  }
  // The reasons travel with the data (a script sees them without a warning handler): every
  // warning of the computation, and why the blur and needle arrays are NaN when they are.
  vtkNew<vtkStringArray> notes;
  notes->SetName("ScoreWarnings");
  for (const std::string& warning : scores.Warnings)
  {
    notes->InsertNextValue(warning);
  }
  output->GetFieldData()->AddArray(notes);
  stage->InsertNextValue(this->GetStageDescription());
  if (needCameras)
  {
    vtkNew<vtkUnsignedCharArray> flags;
    flags->SetName(vis4gs::arrays::NoVisibleView);
    flags->SetNumberOfTuples(static_cast<vtkIdType>(scores.Flags.size()));
    for (std::size_t i = 0; i < scores.Flags.size(); ++i)
    {
      flags->SetValue(static_cast<vtkIdType>(i), scores.Flags[i]);
      this->NumberOfFlaggedGaussians += scores.Flags[i] != 0 ? 1 : 0;
    }
    output->GetPointData()->AddArray(flags);
  }
  // Pieces other than 0 of a distributed pipeline hold no Gaussian (each is in piece 0).
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) > 1 &&
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()) > 0)
  {
    vtkNew<vtkFieldData> fields;
    fields->ShallowCopy(output->GetFieldData());
    output->Initialize();
    output->SetFieldData(fields);
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGaussianArtifactScoreFilter::RequestUpdateExtent(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector,
  vtkInformationVector* vtkNotUsed(outputVector))
{
  for (int port = 0; port < 2; ++port)
  {
    if (vtkInformation* in = inputVector[port]->GetInformationObject(0))
    {
      in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), 0);
      in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), 1);
      in->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
  }
  return 1;
}

//------------------------------------------------------------------------------
std::string vtkGaussianArtifactScoreFilter::GetStageSettings()
{
  int stride = this->ViewStride, loss = this->LossResolution, coverage = this->CoverageResolution;
  ApplyStage(this->ProgressiveStage, stride, loss, coverage);
  return EveryKth(stride) + ", loss maps at " + Fraction(loss) + ", coverage at " +
    Fraction(coverage) + " resolution";
}

//------------------------------------------------------------------------------
std::string vtkGaussianArtifactScoreFilter::GetStageDescription()
{
  if (this->ProgressiveStage == 1)
  {
    return "stage 1 of 2, approximate: " + this->GetStageSettings();
  }
  const bool exact = this->ViewStride == 1 && this->LossResolution == 1 &&
    this->CoverageResolution == 1 && this->FootprintMode == 0 && !this->FloatAccumulation;
  return exact ? std::string("stage 2 of 2, exact")
               : "stage 2 of 2, approximate as asked: " + this->GetStageSettings() +
      (this->FootprintMode == 1 ? ", 3-sigma ellipse footprints" : "") +
      (this->FloatAccumulation ? ", float accumulation" : "");
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::StopExecution()
{
  this->StopRequested = true;
}

//------------------------------------------------------------------------------
const char* vtkGaussianArtifactScoreFilter::GetViewInProgress()
{
  return ViewInProgress;
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scores: " << this->GetScores() << "\n";
  os << indent << "ImageDirectory: " << this->ImageDirectory << "\n";
  os << indent << "LossResolution: " << this->LossResolution << "\n";
  os << indent << "CoverageResolution: " << this->CoverageResolution << "\n";
  os << indent << "ViewStride: " << this->ViewStride << "\n";
  os << indent << "FootprintMode: " << this->FootprintMode << "\n";
  os << indent << "FloatAccumulation: " << (this->FloatAccumulation ? "On" : "Off") << "\n";
  os << indent << "OcclusionThreshold: " << this->OcclusionThreshold << "\n";
  os << indent << "Lambda: " << this->Lambda << "\n";
  os << indent << "ProgressiveStage: " << this->ProgressiveStage << "\n";
  os << indent << "Stopped: " << (this->Stopped ? "On" : "Off") << "\n";
  os << indent << "NumberOfViewsUsed: " << this->NumberOfViewsUsed << "\n";
  os << indent << "NumberOfViewsWithoutImage: " << this->NumberOfViewsWithoutImage << "\n";
  os << indent << "NumberOfFlaggedGaussians: " << this->NumberOfFlaggedGaussians << "\n";
  os << indent << "NumberOfViewsRendered: " << this->NumberOfViewsRendered << "\n";
  os << indent << "ComputeSeconds: " << this->ComputeSeconds << "\n";
  os << indent << "ReductionSeconds: " << this->ReductionSeconds << "\n";
  os << indent << "Controller: " << this->Controller << "\n";
  os << indent << "SharePreparation: " << (this->SharePreparation ? "On" : "Off") << "\n";
  os << indent << "DynamicViewBalancing: " << (this->DynamicViewBalancing ? "On" : "Off") << "\n";
  os << indent << "PreparationProcesses: " << this->PreparationProcesses << "\n";
  os << indent << "ViewRendered: " << (this->ViewRendered ? "set" : "none") << "\n";
}

//------------------------------------------------------------------------------
void vtkGaussianArtifactScoreFilter::SetViewRendered(ViewRenderedFunction function)
{
  this->ViewRendered = std::move(function);
  this->Modified();
}

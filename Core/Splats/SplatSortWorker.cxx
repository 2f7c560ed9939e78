// SPDX-License-Identifier: BSD-3-Clause
#include "SplatSortWorker.h"

#include "SplatSort.h"

#include <chrono>
#include <exception>
#include <utility>

namespace vis4gs
{

//------------------------------------------------------------------------------
SplatSortWorker::~SplatSortWorker()
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    this->Stop = true;
  }
  this->Wake.notify_all();
  if (this->Thread.joinable())
  {
    this->Thread.join();
  }
}

//------------------------------------------------------------------------------
void SplatSortWorker::Sort(const SplatSortRequest& request,
  std::vector<float>& depths,
  SplatSortResult& result)
{
  const auto t0 = std::chrono::steady_clock::now();
  const GaussianCloud& cloud = *request.Cloud;
  ComputeViewDepths(
    cloud.Positions.data(), cloud.Count, request.WorldToCamera, depths, request.Threads);
  SplatSortOptions options;
  options.Keep = request.Keep ? request.Keep->data() : nullptr;
  options.Threads = request.Threads;
  std::vector<std::uint32_t>& order = result.Order;
  SortBackToFront(depths, order, options);
  const std::size_t budget = request.Budget;
  if (budget > 0 && order.size() > budget)
  {
    const std::size_t k = (order.size() + budget - 1) / budget;
    std::size_t m = 0;
    for (std::size_t i = 0; i < order.size(); i += k)
    {
      order[m++] = order[i];
    }
    order.resize(m);
  }
  result.WorldToCamera = request.WorldToCamera;
  result.SceneKey = request.SceneKey;
  result.CameraKey = request.CameraKey;
  result.Milliseconds =
    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

//------------------------------------------------------------------------------
void SplatSortWorker::Submit(SplatSortRequest request)
{
  {
    std::lock_guard<std::mutex> lock(this->Mutex);
    if (!this->Thread.joinable())
    {
      this->Thread = std::thread(&SplatSortWorker::Run, this);
    }
    this->Next = std::move(request);
    this->Pending = true;
    ++this->Submitted;
  }
  this->Wake.notify_one();
}

//------------------------------------------------------------------------------
bool SplatSortWorker::TakeResult(SplatSortResult& result)
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  if (!this->Fresh)
  {
    return false;
  }
  std::swap(result, this->Ready);
  this->Fresh = false;
  return true;
}

//------------------------------------------------------------------------------
void SplatSortWorker::WaitForLatest()
{
  std::unique_lock<std::mutex> lock(this->Mutex);
  this->Done.wait(lock, [this] { return this->Finished == this->Submitted; });
}

//------------------------------------------------------------------------------
std::uint64_t SplatSortWorker::GetSortCount() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->SortCount;
}

//------------------------------------------------------------------------------
std::string SplatSortWorker::GetLastError() const
{
  std::lock_guard<std::mutex> lock(this->Mutex);
  return this->LastError;
}

//------------------------------------------------------------------------------
void SplatSortWorker::Run()
{
  // The worker's own buffers: the result it fills (swapped with Ready when done) and the
  // depths, both reused from sort to sort.
  SplatSortResult back;
  std::vector<float> depths;
  std::unique_lock<std::mutex> lock(this->Mutex);
  for (;;)
  {
    this->Wake.wait(lock, [this] { return this->Stop || this->Pending; });
    if (this->Stop)
    {
      return;
    }
    SplatSortRequest request = std::move(this->Next);
    this->Next = SplatSortRequest();
    this->Pending = false;
    const std::uint64_t number = this->Submitted;
    lock.unlock();
    std::string error;
    try
    {
      Sort(request, depths, back);
    }
    catch (const std::exception& e)
    {
      error = e.what();
    }
    request = SplatSortRequest(); // the cloud is not held longer than the sort
    lock.lock();
    if (error.empty())
    {
      std::swap(back, this->Ready);
      this->Fresh = true;
    }
    this->LastError = error;
    this->Finished = number;
    ++this->SortCount;
    this->Done.notify_all();
  }
}

} // namespace vis4gs

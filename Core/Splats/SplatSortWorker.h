// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file SplatSortWorker.h
 * @brief The GPU splat renderer's back-to-front order, computed on a thread of its own so that
 * the render thread never sorts: the render thread submits the camera of each frame and draws
 * with the last order that finished (the order lags the camera by the sort's duration).
 *
 * One worker thread (started by the first Submit(), joined by the destructor) sorts for the
 * latest request only: requests submitted while a sort runs replace one another, so the worker
 * never falls behind the camera by more than one sort. Results are double-buffered: the worker
 * fills a buffer of its own and swaps it, under a mutex held only for the swap, into the
 * "ready" slot; TakeResult() swaps the ready slot with the caller's result, so the buffers
 * circulate between the three owners and no sort allocates after the first ones.
 */
#ifndef vis4gs_SplatSortWorker_h
#define vis4gs_SplatSortWorker_h

#include "GaussianCloud.h"

#include <array>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace vis4gs
{

/// What an order is sorted for.
struct SplatSortRequest
{
  /// The Gaussians (their Positions are read); held until the sort is done.
  std::shared_ptr<const GaussianCloud> Cloud;
  /// One byte per Gaussian, 0 leaves it out of the order; nullptr keeps every Gaussian.
  std::shared_ptr<const std::vector<std::uint8_t>> Keep;
  /// Row-major world-to-camera matrix (OpenCV camera: +z forward).
  std::array<double, 16> WorldToCamera{};
  /// When more Gaussians are drawable, only every k-th of the order is kept (k =
  /// ceil(drawable / Budget)), keeping the order; 0 keeps every one.
  std::size_t Budget = 0;
  /// OpenMP threads of the sort; 0 uses OpenMP's default.
  int Threads = 0;
  /// The caller's keys of what the order depends on besides the camera (scene, kept set,
  /// budget) and of the camera: copied to the result, so that the caller can tell whether
  /// an order belongs to the scene it draws and how many camera changes it lags.
  std::uint64_t SceneKey = 0;
  std::uint64_t CameraKey = 0;
};

/// A finished order.
struct SplatSortResult
{
  /// Indices of the drawable Gaussians, back to front (SortBackToFront()), thinned by Budget.
  std::vector<std::uint32_t> Order;
  std::array<double, 16> WorldToCamera{};
  std::uint64_t SceneKey = 0;
  std::uint64_t CameraKey = 0;
  /// Wall-clock milliseconds of the depths and the sort.
  double Milliseconds = 0.0;
};

class SplatSortWorker
{
public:
  SplatSortWorker() = default;
  /// Waits for a running sort to finish and joins the thread.
  ~SplatSortWorker();
  SplatSortWorker(const SplatSortWorker&) = delete;
  SplatSortWorker& operator=(const SplatSortWorker&) = delete;

  /**
   * The order for @p request, on the calling thread: view depths (ComputeViewDepths) and the
   * back-to-front sort (SortBackToFront) of the kept Gaussians, thinned to the budget.
   * @p depths is scratch. The worker thread runs exactly this. Throws what SortBackToFront
   * throws.
   */
  static void Sort(const SplatSortRequest& request,
    std::vector<float>& depths,
    SplatSortResult& result);

  /// Asks for the order of @p request (replacing a request not yet started).
  void Submit(SplatSortRequest request);

  /**
   * When an order finished since the last call, swaps it into @p result (whose old buffer the
   * worker reuses) and returns true; false leaves @p result alone. Never blocks on a sort.
   */
  bool TakeResult(SplatSortResult& result);

  /**
   * Blocks until the order of the last submitted request has finished (then TakeResult()
   * returns it, unless taken already). Returns at once when nothing was submitted.
   */
  void WaitForLatest();

  /// Number of sorts the worker has finished (for tests and figures).
  std::uint64_t GetSortCount() const;

  /// The message of the exception the last sort threw, empty when it succeeded.
  std::string GetLastError() const;

private:
  void Run();

  mutable std::mutex Mutex;
  std::condition_variable Wake; // the worker waits for a request or the end
  std::condition_variable Done; // WaitForLatest waits for a finished sort
  std::thread Thread;
  bool Stop = false;
  bool Pending = false;        // Next holds a request not yet started
  bool Fresh = false;          // Ready holds a result not yet taken
  std::uint64_t Submitted = 0; // requests submitted
  std::uint64_t Finished = 0;  // the number of the last request whose sort finished
  std::uint64_t SortCount = 0;
  std::string LastError;
  SplatSortRequest Next;
  SplatSortResult Ready;
};

} // namespace vis4gs

#endif

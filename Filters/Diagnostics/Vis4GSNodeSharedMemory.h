/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSNodeSharedMemory.h

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
/**
 * @class Vis4GSNodeSharedMemory
 * @brief Memory shared by the processes of a vtkMultiProcessController that run on one machine,
 * for the score pass's view-independent preparation (vis4gs::PreparationShare).
 *
 * The processes of one machine are those with the same host name and boot id (what
 * MPI_Comm_split_type(MPI_COMM_TYPE_SHARED) finds); the lowest of them creates a POSIX shared
 * memory object, the others map it, and it is unlinked as soon as all have mapped it, so none is
 * left behind. Only the controller is used (no MPI call): the filter stays free of MPI (only
 * the vis4gs program links VTK::ParallelMPI), and `vis4gs analyze` and pvbatch take the same
 * path. Map() gives null on every process when any process cannot map (no /dev/shm, less free
 * space there than asked, a failed call): every process then prepares alone, as before.
 * A process alone on its machine gets Parts() 1 and maps memory of its own (Map() is collective).
 *
 * For the tests, VIS4GS_TEST_NO_SHARED_MEMORY=R makes process R's Map() fail (the fallback).
 */
#ifndef Vis4GSNodeSharedMemory_h
#define Vis4GSNodeSharedMemory_h

#include "MultiViewRenderer.h"              // For PreparationShare
#include "vis4gsFiltersDiagnosticsModule.h" // For export macro

#include <cstddef>
#include <string>
#include <vector>

class vtkMultiProcessController;

class VIS4GSFILTERSDIAGNOSTICS_EXPORT Vis4GSNodeSharedMemory
{
public:
  /// Collective over @p controller's processes: finds this process's machine group.
  explicit Vis4GSNodeSharedMemory(vtkMultiProcessController* controller);
  ~Vis4GSNodeSharedMemory();
  Vis4GSNodeSharedMemory(const Vis4GSNodeSharedMemory&) = delete;
  Vis4GSNodeSharedMemory& operator=(const Vis4GSNodeSharedMemory&) = delete;

  /// This process's position among the processes of its machine, and their number.
  int Part() const { return this->NodePart; }
  int Parts() const { return this->NodeParts; }
  /// The lowest process of @p rank's machine (processes with the same run on one machine).
  int LeaderOf(int rank) const { return this->Leaders.at(static_cast<std::size_t>(rank)); }

  /**
   * Collective over every process of the controller: memory of @p bytes mapped by every
   * process of this machine (the same bytes, page-aligned), kept until this object goes or the
   * next Map(); null on every process when one of them could not map it (Failure() says why
   * on that one).
   */
  void* Map(std::size_t bytes);
  /// Collective: returns when every process has reached it.
  void Wait();
  /// Whether the last Map() gave memory (every process of the controller then has some).
  bool Mapped() const { return this->Address != nullptr; }
  /// Why this process's last Map() failed ("" when it did not, or failed elsewhere).
  const std::string& Failure() const { return this->Reason; }

  /// Map() and Wait() for the score pass, with Part() and Parts() (no Map in a single process).
  vis4gs::PreparationShare Share();

private:
  void Unmap();
  vtkMultiProcessController* Controller;
  int NodePart = 0;
  int NodeParts = 1;
  int Leader = 0;           ///< lowest process of this machine
  std::vector<int> Leaders; ///< lowest process of each process's machine
  void* Address = nullptr;
  std::size_t Bytes = 0;
  std::string Reason;
};

#endif

/*=========================================================================

  Program:   Vis4GS
  Module:    Vis4GSNodeSharedMemory.cxx

  Copyright (c) Vis4GS developers
  All rights reserved.
  See LICENSE for details.

=========================================================================*/
#include "Vis4GSNodeSharedMemory.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>
#include <vector>

namespace
{
constexpr int KeySize = 192;
constexpr int NameSize = 64;

// Host name and boot id: processes with the same see the same /dev/shm.
void MachineKey(char key[KeySize])
{
  std::memset(key, 0, KeySize);
  char host[128] = "";
  gethostname(host, sizeof(host) - 1);
  std::string boot;
  std::ifstream in("/proc/sys/kernel/random/boot_id");
  std::getline(in, boot);
  std::snprintf(key, KeySize, "%s|%s", host, boot.c_str());
}

std::string Errno(const char* what)
{
  return std::string(what) + ": " + std::strerror(errno);
}
}

//------------------------------------------------------------------------------
Vis4GSNodeSharedMemory::Vis4GSNodeSharedMemory(vtkMultiProcessController* controller)
  : Controller(controller)
{
  const int ranks = controller->GetNumberOfProcesses();
  const int rank = controller->GetLocalProcessId();
  char key[KeySize];
  MachineKey(key);
  std::vector<char> keys(static_cast<std::size_t>(KeySize) * ranks);
  controller->AllGather(key, keys.data(), KeySize);
  // Each process's machine is named by its lowest process with the same key.
  auto keyOf = [&keys](int r) { return keys.data() + static_cast<std::size_t>(r) * KeySize; };
  this->Leaders.assign(static_cast<std::size_t>(ranks), -1);
  for (int r = 0; r < ranks; ++r)
  {
    for (int q = 0; this->Leaders[r] < 0; ++q) // (q = r matches at the latest)
    {
      if (std::memcmp(keyOf(r), keyOf(q), KeySize) == 0)
      {
        this->Leaders[r] = q;
      }
    }
  }
  this->Leader = this->Leaders[rank];
  this->NodePart =
    static_cast<int>(std::count(this->Leaders.begin(), this->Leaders.begin() + rank, this->Leader));
  this->NodeParts =
    static_cast<int>(std::count(this->Leaders.begin(), this->Leaders.end(), this->Leader));
}

//------------------------------------------------------------------------------
Vis4GSNodeSharedMemory::~Vis4GSNodeSharedMemory()
{
  this->Unmap();
}

//------------------------------------------------------------------------------
void Vis4GSNodeSharedMemory::Unmap()
{
  if (this->Address)
  {
    munmap(this->Address, this->Bytes);
    this->Address = nullptr;
    this->Bytes = 0;
  }
}

//------------------------------------------------------------------------------
void* Vis4GSNodeSharedMemory::Map(std::size_t bytes)
{
  this->Unmap();
  this->Reason.clear();
  const int rank = this->Controller->GetLocalProcessId();
  const int ranks = this->Controller->GetNumberOfProcesses();
  static std::atomic<unsigned> serial{ 0 };
  char name[NameSize] = "";
  int fd = -1;
  bool created = false;
  // Every step below fails into Reason, never out of this function: the other processes wait
  // for this one in the collective calls.
  if (const char* test = std::getenv("VIS4GS_TEST_NO_SHARED_MEMORY"))
  {
    if (std::atoi(test) == rank)
    {
      this->Reason = "VIS4GS_TEST_NO_SHARED_MEMORY";
    }
  }
  if (rank == this->Leader && this->Reason.empty())
  {
    std::snprintf(name, sizeof(name), "/vis4gs-%ld-%u", static_cast<long>(getpid()), serial++);
    fd = shm_open(name, O_CREAT | O_EXCL | O_RDWR, 0600);
    created = fd >= 0;
    struct statvfs fs;
    if (fd < 0)
    {
      this->Reason = Errno("shm_open");
    }
    else if (fstatvfs(fd, &fs) != 0)
    {
      this->Reason = Errno("fstatvfs");
    }
    // A shared memory file system smaller than asked would kill the process with SIGBUS when a
    // page past its size is first written, not fail a call: checked before.
    else if (static_cast<unsigned long long>(fs.f_bavail) * fs.f_frsize < bytes)
    {
      this->Reason = "/dev/shm has " +
        std::to_string(static_cast<unsigned long long>(fs.f_bavail) * fs.f_frsize >> 20) +
        " MiB free, " + std::to_string(bytes >> 20) + " MiB needed";
    }
    else if (ftruncate(fd, static_cast<off_t>(bytes)) != 0)
    {
      this->Reason = Errno("ftruncate");
    }
    if (!this->Reason.empty())
    {
      name[0] = '\0';
    }
  }
  std::vector<char> names(static_cast<std::size_t>(NameSize) * ranks);
  this->Controller->AllGather(name, names.data(), NameSize);
  const char* leaderName = names.data() + static_cast<std::size_t>(this->Leader) * NameSize;
  if (this->Reason.empty() && rank != this->Leader)
  {
    if (leaderName[0] == '\0')
    {
      this->Reason.clear(); // (the leader says why)
    }
    else if ((fd = shm_open(leaderName, O_RDWR, 0600)) < 0)
    {
      this->Reason = Errno("shm_open");
    }
  }
  void* address = nullptr;
  if (this->Reason.empty() && fd >= 0)
  {
    address = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    if (address == MAP_FAILED)
    {
      address = nullptr;
      this->Reason = Errno("mmap");
    }
  }
  if (fd >= 0)
  {
    close(fd);
  }
  // Everyone has opened it (or given up): the name can go, the memory stays while mapped.
  this->Controller->Barrier();
  if (created)
  {
    shm_unlink(name);
  }
  int ok = address ? 1 : 0, allOk = 0;
  this->Controller->AllReduce(&ok, &allOk, 1, vtkCommunicator::MIN_OP);
  if (!allOk)
  {
    if (address)
    {
      munmap(address, bytes);
    }
    return nullptr;
  }
  this->Address = address;
  this->Bytes = bytes;
  return address;
}

//------------------------------------------------------------------------------
void Vis4GSNodeSharedMemory::Wait()
{
  this->Controller->Barrier();
}

//------------------------------------------------------------------------------
vis4gs::PreparationShare Vis4GSNodeSharedMemory::Share()
{
  vis4gs::PreparationShare share;
  share.Part = this->NodePart;
  share.Parts = this->NodeParts;
  // Map() is collective over every process, those alone on their machine too (they map
  // memory of their own).
  if (this->Controller->GetNumberOfProcesses() > 1)
  {
    share.Map = [this](std::size_t bytes) { return this->Map(bytes); };
    share.Wait = [this]() { this->Wait(); };
  }
  return share;
}

// SPDX-License-Identifier: BSD-3-Clause
#include "Vis4GSMPI.h"

#include "vtkGaussianArtifactScoreFilter.h"

#include <csignal>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unistd.h>

#ifdef VIS4GS_USE_MPI
#include "vtkMPIController.h"
#include "vtkMultiProcessController.h"
#endif

namespace
{
#ifdef VIS4GS_USE_MPI
vtkMPIController* TheController = nullptr;
char RankText[64] = "";

void WriteText(const char* text)
{
  const ssize_t ignored = write(2, text, std::strlen(text));
  (void)ignored;
}

// Async-signal-safe: write(2) of buffers prepared beforehand, then the default action.
void SayWhereAndDie(int signal)
{
  char number[4] = {
    static_cast<char>('0' + (signal / 10) % 10), static_cast<char>('0' + signal % 10), '\0', '\0'
  };
  const char* view = vtkGaussianArtifactScoreFilter::GetViewInProgress();
  WriteText("vis4gs: ");
  WriteText(RankText);
  WriteText(" stopped by signal ");
  WriteText(number[0] == '0' ? number + 1 : number);
  if (view[0])
  {
    WriteText(" while on ");
    WriteText(view);
    WriteText("\n");
  }
  else
  {
    WriteText(" with no view in progress\n");
  }
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}
#endif

int EnvInt(const char* name)
{
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : 0;
}
}

//------------------------------------------------------------------------------
int Vis4GSMPISession::LaunchedProcesses()
{
  const int ompi = EnvInt("OMPI_COMM_WORLD_SIZE");
  return ompi > 0 ? ompi : EnvInt("PMI_SIZE");
}

//------------------------------------------------------------------------------
Vis4GSMPISession::Vis4GSMPISession(bool requested)
{
  const int launched = LaunchedProcesses();
  if (!requested && launched == 0)
  {
    return;
  }
#ifdef VIS4GS_USE_MPI
  TheController = vtkMPIController::New();
  TheController->Initialize(nullptr, nullptr);
  vtkMultiProcessController::SetGlobalController(TheController);
  this->Started = true;
  this->LocalRank = TheController->GetLocalProcessId();
  this->Processes = TheController->GetNumberOfProcesses();
  const std::string text =
    "process " + std::to_string(this->LocalRank) + " of " + std::to_string(this->Processes);
  std::strncpy(RankText, text.c_str(), sizeof(RankText) - 1);
  for (int s : { SIGTERM, SIGINT, SIGHUP, SIGSEGV, SIGBUS })
  {
    std::signal(s, SayWhereAndDie);
  }
#else
  if (requested || launched > 1)
  {
    throw std::runtime_error(std::string(requested ? "--mpi was given" : "launched by mpiexec") +
      " but this vis4gs was built without MPI (VIS4GS_USE_MPI=OFF); rebuild with Debian's "
      "libopenmpi-dev installed, or run one process");
  }
#endif
}

//------------------------------------------------------------------------------
Vis4GSMPISession::~Vis4GSMPISession()
{
#ifdef VIS4GS_USE_MPI
  if (this->Started && TheController)
  {
    vtkMultiProcessController::SetGlobalController(nullptr);
    TheController->Finalize();
    TheController->Delete();
    TheController = nullptr;
  }
#endif
}

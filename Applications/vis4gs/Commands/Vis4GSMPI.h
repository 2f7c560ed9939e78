// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Vis4GSMPI.h
 * @brief MPI for the vis4gs program: started only when asked for (--mpi) or when the program
 * was launched by mpiexec (Open MPI's OMPI_COMM_WORLD_SIZE, MPICH/Hydra's PMI_SIZE), so a
 * user who never uses MPI runs exactly as before, with no MPI initialisation at all.
 *
 * When started, a vtkMPIController becomes VTK's global controller (the score filter then
 * spreads the views over the processes) and is finalised when the session ends. Under MPI, a
 * SIGTERM, SIGINT, SIGHUP or SIGSEGV makes the process say which process it is and which view
 * it was on (vtkGaussianArtifactScoreFilter::GetViewInProgress()) before it dies, so the job's
 * error names them (Open MPI then aborts the other processes; SIGKILL cannot be caught and
 * leaves only mpiexec's own message, which names the process).
 */
#ifndef Vis4GSMPI_h
#define Vis4GSMPI_h

class Vis4GSMPISession
{
public:
  /**
   * Starts MPI when @p requested or when the environment shows an MPI launch. Throws
   * std::runtime_error when MPI is wanted but this vis4gs was built without it
   * (VIS4GS_USE_MPI=OFF), rather than letting every process write the same outputs.
   */
  explicit Vis4GSMPISession(bool requested);
  ~Vis4GSMPISession();
  Vis4GSMPISession(const Vis4GSMPISession&) = delete;
  Vis4GSMPISession& operator=(const Vis4GSMPISession&) = delete;

  bool Active() const { return this->Started; }
  int Rank() const { return this->LocalRank; }
  int Size() const { return this->Processes; }

  /// Number of processes the environment announces (0 when not launched by mpiexec).
  static int LaunchedProcesses();

private:
  bool Started = false;
  int LocalRank = 0;
  int Processes = 1;
};

#endif

#pragma once
// The ranks masav was started on: `mpirun -np N masav sph ...` shares one simulation among N
// processes (engine/sph/sph_ranks.h). MPI is optional at build time (CMake finds it, like CUDA);
// a masav built without it refuses to run on several ranks rather than run N copies.
#include <memory>
#include <string>

#include "engine/sph/sph_comm.h"

namespace masav::app {

// The number of ranks the launcher started (OpenMPI and MPICH/PMI set it in the
// environment), without initialising MPI; 1 when started alone.
int launched_ranks();

// This process's rank among the ranks on its machine (OpenMPI, MPICH), -1 when not told.
int local_rank();

// The world communicator when started on more than one rank (MPI is initialised once and
// finalised at exit); null when started alone. Throws masav::Error when started on several
// ranks by a masav built without MPI.
SphComm* world_comm();

// How the ranks' exchanges reach MPI, for the run's report: staged through host memory, and
// whether this MPI could read GPU memory itself (a CUDA-aware build, asked at run time).
std::string exchange_path();

}  // namespace masav::app

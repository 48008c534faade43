#pragma once
// The sea-state library on several processes with MPI (docs/library.md, "On a cluster"): the same
// program under `mpirun -np N` on a workstation or `srun` in a Slurm job. Its own library
// (nearshore_library_mpi, built only where CMake finds MPI), so a build without MPI still has the
// serial library (library_run.hpp).
//
// How the work is split: rank 0 plans (plan_library: cases, costs, largest first) and keeps the
// index; every rank, rank 0 included (a second thread there), asks rank 0 for a state, makes it
// complete (complete_library_state) and asks again, until none is left. A rank that finishes early
// takes the next state: dynamic, so states of different sizes and ranks of different speeds even
// out. Messages are small JSON texts: "give me work", a state id, an outcome. The library folder
// must be on a file system every rank sees (a cluster's shared file system).
#include <filesystem>

#include "nearshore/library/library_run.hpp"

namespace nearshore::library {

/// Whether this process was started by an MPI launcher (mpirun/mpiexec of Open MPI or MPICH, srun
/// with PMI or PMIx): then `nearshore library` runs run_library_mpi, else run_library.
bool started_by_mpi_launcher();

/// run_library on every rank of MPI_COMM_WORLD: call it on every rank with the same arguments.
/// Initialises MPI (thread level FUNNELED: only the main thread of each rank calls MPI) and
/// finalises it before returning. Rank 0 returns the summary; the other ranks return a summary of
/// their own work (states, actions). An error in the plan (a bad library file, a folder in use) is
/// thrown on every rank, so that each exits. With LibraryOptions::threads_per_rank = 0 each bake
/// gets the cores of its machine divided among the ranks that share it.
LibrarySummary run_library_mpi(const std::filesystem::path& library_file, const LibraryOptions& options);

/// This process's MPI rank once run_library_mpi has started (0 before, and when serial).
int library_mpi_rank();

}  // namespace nearshore::library

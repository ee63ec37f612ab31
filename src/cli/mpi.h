#pragma once
// MPI for `cairn plan` and `cairn batch` (docs/batch.md, docs/planning.md):
// when Cairn is built with it (CMake option CAIRN_MPI) and started by
// `mpirun`, every rank runs the same command line; otherwise one process, and
// these functions say so (rank 0 of 1). MPI itself stays in mpi.cpp: the
// planning library sees only its PlanExecutor interface.

#include <functional>
#include <string>
#include <vector>

#include "cairn/planning/planner.h"

namespace cairn::cli {

/// Starts MPI when the process was started by mpirun (and Cairn was built
/// with MPI), and ends it when destroyed. Without mpirun nothing starts: a
/// plain `cairn` run never pays for MPI.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

/// Whether this build has MPI (CAIRN_MPI).
bool MpiBuilt();
/// This process's rank (0 without MPI) and the number of ranks (1).
int MpiRank();
int MpiSize();

/// The executor that spreads the planner's node checks and edges over the
/// ranks (balanced by their estimated cost; every rank gets every result), or
/// null with a single rank.
PlanExecutor* MpiPlanExecutor();

/// `cairn batch` on rank 0 (of several): hands `jobs` (their JSON lines) out
/// one at a time to whichever rank is free, and calls `on_result(k, line)` on
/// this thread with job k's result line as it arrives (in any order). Calls
/// `on_wait()` now and then while it waits (the progress line). Then tells
/// every other rank to stop.
void MpiServeJobs(const std::vector<std::string>& jobs,
                  const std::function<void(size_t, const std::string&)>& on_result,
                  const std::function<void()>& on_wait);
/// Rank 0, on every way out of a batch: tells the other ranks to stop (once;
/// nothing when MpiServeJobs did).
void MpiStopWorkers();
/// `cairn batch` on the other ranks: runs each job rank 0 sends, answering
/// with `run(line)`, until told to stop.
void MpiWorkJobs(const std::function<std::string(const std::string&)>& run);

}  // namespace cairn::cli

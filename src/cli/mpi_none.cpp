// A build without MPI (CAIRN_MPI off, or MPI not found): one process.
#include "cli/mpi.h"

namespace cairn::cli {

MpiSession::MpiSession(int&, char**&) {}
MpiSession::~MpiSession() = default;
bool MpiBuilt() { return false; }
int MpiRank() { return 0; }
int MpiSize() { return 1; }
PlanExecutor* MpiPlanExecutor() { return nullptr; }
void MpiServeJobs(const std::vector<std::string>&,
                  const std::function<void(size_t, const std::string&)>&,
                  const std::function<void()>&) {}
void MpiStopWorkers() {}
void MpiWorkJobs(const std::function<std::string(const std::string&)>&) {}

}  // namespace cairn::cli

#pragma once
// `cairn batch JOBS.jsonl -o RESULTS.jsonl`: many checks, simulations, plans,
// NDBGs and margins in one run, each job's result the document its command prints
// with --json (docs/batch.md).

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "cli/command.h"
#include "cli/margin_command.h"

namespace cairn::cli {

struct BatchArgs {
  std::string jobs;     // JOBS.jsonl
  std::string output;   // -o RESULTS.jsonl
  bool fresh = false;   // --fresh: start over (--resume, the default: skip jobs already there)
  bool resume = false;  // --resume: the default, said explicitly
  bool retry_failed = false;  // --retry-failed: also run again the jobs recorded with exit 2, 4, 5
  double job_timeout = 0;     // --job-timeout S; 0 (or ≥ 1e9 s): none
  int threads = 0;            // --threads; 0: every core (without MPI ranks)
};

/// A job's command, parsed from its command line (without the program name:
/// `check MODEL --without A`) exactly as `cairn` parses it, ready to run
/// in-process. @throws InputError when the command line is not one of
/// check, simulate, plan, blocking, margin with valid options.
using JobCommand = std::function<CommandDocument(const Checkpoint&)>;
using JobParser = std::function<JobCommand(const std::vector<std::string>& args)>;

/// A job's line of RESULTS (without the newline) and its exit code.
struct JobResult {
  std::string line;
  int exit = 0;
};

/// One job (a line of JOBS, already known to be a JSON object with an id),
/// run in-process. Never throws.
JobResult RunJob(const std::string& line, const JobParser& parse, double job_timeout);

/// `cairn batch`: exit 0 once every job has its line in RESULTS (whatever
/// its own exit), 2 when the batch cannot run (JOBS unreadable or a line
/// without an id, RESULTS not writable, not results, or JOBS itself).
int RunBatch(const BatchArgs& args, const JobParser& parse, std::ostream& out, std::ostream& err);

}  // namespace cairn::cli

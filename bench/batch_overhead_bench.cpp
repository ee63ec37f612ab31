// The baseline of `cairn batch`'s overhead (docs/benchmarks.md, "cairn
// batch"): the same check jobs run in one process by the command's own
// document function, with nothing around them (no job parsing, no results
// file, no workers).
//   batch_overhead_bench JOBS.jsonl [repeats]
// prints the seconds per check: CheckDocument alone, and with the document
// written out as text (what `cairn check --json` and a RESULTS line do).
#include <chrono>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cli/check_command.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: batch_overhead_bench JOBS.jsonl [repeats]\n");
    return 2;
  }
  const int repeats = argc > 2 ? std::atoi(argv[2]) : 3;
  std::vector<cairn::cli::CheckArgs> checks;
  std::ifstream in(argv[1]);
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json job = nlohmann::json::parse(line);
    if (job.value("command", "") != "check") continue;
    cairn::cli::CheckArgs args;
    args.scene = job["model"];
    checks.push_back(args);
  }
  using Clock = std::chrono::steady_clock;
  double best_doc = 1e300, best_text = 1e300;
  size_t bytes = 0;
  // On a thread of its own, as `cairn batch` runs its jobs (the main thread's
  // malloc arena grows and trims the heap with brk, a thread's does not: the
  // same checks on the main thread measured up to twice as slow here).
  std::thread([&] {
    for (int r = 0; r < repeats; ++r) {
      auto t0 = Clock::now();
      for (const auto& args : checks) cairn::cli::CheckDocument(args);
      auto t1 = Clock::now();
      for (const auto& args : checks) bytes += cairn::cli::CheckDocument(args).json.dump().size();
      auto t2 = Clock::now();
      best_doc = std::min(best_doc, std::chrono::duration<double>(t1 - t0).count());
      best_text = std::min(best_text, std::chrono::duration<double>(t2 - t1).count());
    }
  }).join();
  const double n = static_cast<double>(checks.size());
  std::printf(
      "%zu checks in one process (best of %d): %.1f us per check (document), %.1f us "
      "(document written as text; %zu bytes in all)\n",
      checks.size(), repeats, 1e6 * best_doc / n, 1e6 * best_text / n, bytes);
  return 0;
}

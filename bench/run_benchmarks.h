#pragma once
// The end of every benchmark main(): hand the arguments the harness did not
// take to Google Benchmark, run, and shut down.
#include <benchmark/benchmark.h>

#include <vector>

namespace cairn::bench {

inline int RunBenchmarks(std::vector<char*>& args) {
  int argc = static_cast<int>(args.size());
  benchmark::Initialize(&argc, args.data());
  if (benchmark::ReportUnrecognizedArguments(argc, args.data())) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

}  // namespace cairn::bench

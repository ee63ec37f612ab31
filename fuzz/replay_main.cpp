// A driver for the fuzz targets without libFuzzer (the GCC build of the test
// suite): replays every file of the given corpus folders through
// LLVMFuzzerTestOneInput, then runs a bounded number of mutations of them
// (byte flips, insertions, deletions, splices and numbers made extreme: the
// kinds of change that found the hostile-input defects), from a fixed seed so that
// a run is the same every time. Usage:
//   TARGET [--runs N | --seconds S] [--seed S] [--timeout S] [--last FILE] DIR...
// --seconds runs mutations until that much time has passed (a fuzz round
// without libFuzzer); --timeout ends the process by SIGALRM when one input
// takes longer (a hang is a finding); --last keeps each input in FILE before
// it runs, so that the one a crash or hang stopped at can be replayed.
// A finding aborts (the target's own rule, or a sanitizer).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

using Bytes = std::vector<uint8_t>;

Bytes Slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return Bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Numbers a mutation may write in place of one in the text.
const char* const kExtremes[] = {"1e308", "-1e308", "1e-320", "5e-324", "0",          "-0",
                                 "1e400", "nan",    "1e12",   "-1",     "2147483648", "1e-9",
                                 "[]",    "{}",     "null",   "\"\"",   "true"};

Bytes Mutate(const std::vector<Bytes>& corpus, std::mt19937_64& rng) {
  Bytes b = corpus[rng() % corpus.size()];
  const int edits = 1 + static_cast<int>(rng() % 4);
  for (int e = 0; e < edits; ++e) {
    const size_t at = b.empty() ? 0 : rng() % b.size();
    switch (rng() % 6) {
      case 0:  // flip a byte
        if (!b.empty()) b[at] ^= static_cast<uint8_t>(1u << (rng() % 8));
        break;
      case 1:  // insert a byte
        b.insert(b.begin() + static_cast<long>(at), static_cast<uint8_t>(rng()));
        break;
      case 2:  // delete a run
        if (!b.empty())
          b.erase(b.begin() + static_cast<long>(at),
                  b.begin() + static_cast<long>(std::min(b.size(), at + 1 + rng() % 8)));
        break;
      case 3: {  // splice in a piece of another input
        const Bytes& o = corpus[rng() % corpus.size()];
        if (o.empty()) break;
        const size_t from = rng() % o.size(),
                     len = 1 + rng() % std::min<size_t>(64, o.size() - from);
        b.insert(b.begin() + static_cast<long>(at), o.begin() + static_cast<long>(from),
                 o.begin() + static_cast<long>(from + len));
        break;
      }
      default: {  // a number made extreme
        size_t s = at;
        while (s < b.size() && !(b[s] >= '0' && b[s] <= '9')) ++s;
        if (s >= b.size()) break;
        size_t t = s;
        while (t < b.size() && ((b[t] >= '0' && b[t] <= '9') || b[t] == '.' || b[t] == 'e' ||
                                b[t] == '-' || b[t] == '+'))
          ++t;
        const std::string x = kExtremes[rng() % (sizeof kExtremes / sizeof *kExtremes)];
        b.erase(b.begin() + static_cast<long>(s), b.begin() + static_cast<long>(t));
        b.insert(b.begin() + static_cast<long>(s), x.begin(), x.end());
      }
    }
  }
  return b;
}

}  // namespace

// Runs one input under the hang watchdog, kept first in `last` if named.
void RunOne(const Bytes& b, unsigned timeout_s, const std::string& last) {
  if (!last.empty())
    std::ofstream(last, std::ios::binary | std::ios::trunc)
        .write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
  ::alarm(timeout_s);  // 0: no watchdog
  LLVMFuzzerTestOneInput(b.data(), b.size());
  ::alarm(0);
}

int main(int argc, char** argv) {
  long runs = 0;
  double seconds = 0;
  unsigned timeout_s = 0;
  std::string last;
  uint64_t seed = 1;
  std::vector<Bytes> corpus;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--runs" && i + 1 < argc) {
      runs = std::atol(argv[++i]);
    } else if (arg == "--seconds" && i + 1 < argc) {
      seconds = std::atof(argv[++i]);
    } else if (arg == "--timeout" && i + 1 < argc) {
      timeout_s = static_cast<unsigned>(std::atoi(argv[++i]));
    } else if (arg == "--last" && i + 1 < argc) {
      last = argv[++i];
    } else if (arg == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (std::filesystem::is_directory(arg)) {
      std::vector<std::filesystem::path> files;
      for (const auto& e : std::filesystem::directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
      std::sort(files.begin(), files.end());
      for (const auto& f : files) corpus.push_back(Slurp(f));
    } else {
      corpus.push_back(Slurp(arg));
    }
  }
  for (const Bytes& b : corpus) RunOne(b, timeout_s, last);
  std::printf("replayed %zu inputs\n", corpus.size());
  if (corpus.empty()) return runs > 0 || seconds > 0 ? 1 : 0;
  std::mt19937_64 rng(seed);
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  long done = 0;
  for (; seconds > 0 ? elapsed() < seconds : done < runs; ++done)
    RunOne(Mutate(corpus, rng), timeout_s, last);
  std::printf("ran %ld mutations in %.0f s (seed %llu): no finding\n", done, elapsed(),
              static_cast<unsigned long long>(seed));
  return 0;
}

// MPI for `cairn plan` and `cairn batch` (mpi.h): the planner's executor
// across ranks and the batch's job server.
#include "cli/mpi.h"

#include <mpi.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <thread>

#include "cairn/mechanics/rest_solution.h"

namespace cairn::cli {
namespace {

bool g_running = false;  // MPI_Init done (and MPI_Finalize not yet)
int g_rank = 0, g_size = 1;
bool g_workers_stopped = false;

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// mpirun (Open MPI's, or a PMI launcher's) says so in the environment.
bool LaunchedByMpirun() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v) != nullptr) return true;
  return false;
}

// ---- Bytes ------------------------------------------------------------------

void PutU64(std::string& out, uint64_t v) { out.append(reinterpret_cast<const char*>(&v), 8); }
uint64_t GetU64(const std::string& in, size_t& at) {
  if (in.size() - at < 8) throw std::runtime_error("MPI: truncated message");
  uint64_t v = 0;
  std::memcpy(&v, in.data() + at, 8);
  at += 8;
  return v;
}
std::string GetBytes(const std::string& in, size_t& at, uint64_t n) {
  if (in.size() - at < n) throw std::runtime_error("MPI: truncated message");
  std::string s = in.substr(at, n);
  at += n;
  return s;
}

// Every rank's `mine`, concatenated in rank order, on every rank.
std::vector<std::string> AllGather(const std::string& mine) {
  int len = static_cast<int>(mine.size());
  std::vector<int> lens(g_size), offsets(g_size, 0);
  MPI_Allgather(&len, 1, MPI_INT, lens.data(), 1, MPI_INT, MPI_COMM_WORLD);
  for (int r = 1; r < g_size; ++r) offsets[r] = offsets[r - 1] + lens[r - 1];
  std::string all(static_cast<size_t>(offsets.back() + lens.back()), '\0');
  MPI_Allgatherv(mine.data(), len, MPI_BYTE, all.data(), lens.data(), offsets.data(), MPI_BYTE,
                 MPI_COMM_WORLD);
  std::vector<std::string> out(g_size);
  for (int r = 0; r < g_size; ++r) out[r] = all.substr(offsets[r], lens[r]);
  return out;
}

// ---- The planner's executor ---------------------------------------------------

// Longest processing time first: the tasks by decreasing cost (ties by
// index), each to the rank with the least cost so far (ties: the lowest
// rank). Deterministic, so every rank computes the same assignment; its
// makespan is within 4/3 of the best (Graham 1969).
std::vector<int> Assign(const std::vector<double>& cost, int ranks) {
  std::vector<int> order(cost.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return cost[a] > cost[b]; });
  std::vector<double> load(ranks, 0);
  std::vector<int> owner(cost.size(), 0);
  for (int i : order) {
    const int r = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    owner[i] = r;
    load[r] += cost[i];
  }
  return owner;
}

class MpiExecutor final : public PlanExecutor {
 public:
  int processes() const override { return g_size; }

  // This rank's tasks (on its threads), then every rank's results to every
  // rank (MPI_Allgatherv): [index][length][bytes] per task, after a status
  // byte that says whether a task threw (then its message follows).
  std::vector<std::string> Map(const std::vector<double>& cost, int threads,
                               const std::function<std::string(int)>& task) override {
    const auto start = Clock::now();
    const std::vector<int> owner = Assign(cost, g_size);
    std::vector<int> mine;
    for (size_t i = 0; i < owner.size(); ++i)
      if (owner[i] == g_rank) mine.push_back(static_cast<int>(i));
    std::vector<std::string> results(mine.size());
    std::exception_ptr error;
    RunOnThreads(
        static_cast<int>(mine.size()), threads, [&](int k) { results[k] = task(mine[k]); }, error);
    std::string packed(1, error ? '\1' : '\0');
    if (error) {
      packed += Describe(error);
    } else {
      for (size_t k = 0; k < mine.size(); ++k) {
        PutU64(packed, static_cast<uint64_t>(mine[k]));
        PutU64(packed, results[k].size());
        packed += results[k];
      }
    }
    const auto exchange = Clock::now();
    work_ += std::chrono::duration<double>(exchange - start).count();
    const std::vector<std::string> all = AllGather(packed);
    communication_ += Since(exchange);
    // A task that threw anywhere stops the search everywhere.
    if (error) std::rethrow_exception(error);
    for (int r = 0; r < g_size; ++r)
      if (!all[r].empty() && all[r][0] != '\0')
        throw std::runtime_error("rank " + std::to_string(r) + ": " + all[r].substr(1));
    std::vector<std::string> out(cost.size());
    for (const std::string& from : all) {
      size_t at = 1;
      while (at < from.size()) {
        const uint64_t i = GetU64(from, at);
        const uint64_t n = GetU64(from, at);
        if (i >= out.size()) throw std::runtime_error("MPI: a task index out of range");
        out[i] = GetBytes(from, at, n);
      }
    }
    return out;
  }

  void Times(std::vector<double>& work, std::vector<double>& communication) override {
    const double mine[2] = {work_, communication_};
    std::vector<double> all(2 * static_cast<size_t>(g_size));
    MPI_Allgather(mine, 2, MPI_DOUBLE, all.data(), 2, MPI_DOUBLE, MPI_COMM_WORLD);
    work.assign(g_size, 0);
    communication.assign(g_size, 0);
    for (int r = 0; r < g_size; ++r) {
      work[r] = all[2 * r];
      communication[r] = all[2 * r + 1];
    }
    work_ = communication_ = 0;
  }

 private:
  static std::string Describe(const std::exception_ptr& error) {
    try {
      std::rethrow_exception(error);
    } catch (const std::exception& e) {
      return e.what();
    } catch (...) {
      return "an unknown exception";
    }
  }
  // task(k) for k in [0, n) on up to `threads` threads; the first exception
  // is kept in `error`.
  static void RunOnThreads(int n, int threads, const std::function<void(int)>& task,
                           std::exception_ptr& error) {
    std::atomic<int> next{0};
    std::mutex error_mutex;
    const auto work = [&] {
      for (int k = next++; k < n; k = next++) {
        try {
          task(k);
        } catch (...) {
          const std::lock_guard<std::mutex> lock(error_mutex);
          if (!error) error = std::current_exception();
        }
      }
    };
    threads = std::max(1, std::min(threads, n));
    if (threads == 1) {
      work();
      return;
    }
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
      pool.emplace_back([&] {
        work();
        ReleaseThreadSolverState();  // the LP solvers' per-thread state
      });
    for (std::thread& t : pool) t.join();
  }

  double work_ = 0, communication_ = 0;
};

MpiExecutor g_executor;

// ---- The batch's job server ---------------------------------------------------

enum Tag : int { kReady = 1, kJob = 2, kStop = 3, kResult = 4 };

std::string Receive(int source, int tag, MPI_Status& status) {
  MPI_Probe(source, tag, MPI_COMM_WORLD, &status);
  int n = 0;
  MPI_Get_count(&status, MPI_BYTE, &n);
  std::string buf(static_cast<size_t>(n), '\0');
  MPI_Recv(buf.data(), n, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return buf;
}

void Send(const std::string& bytes, int dest, int tag) {
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD);
}

}  // namespace

MpiSession::MpiSession(int& argc, char**& argv) {
  if (!LaunchedByMpirun()) return;
  int provided = 0;
  // Only the main thread talks MPI; worker threads compute.
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  g_running = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
}

MpiSession::~MpiSession() {
  if (g_running) MPI_Finalize();
  g_running = false;
}

bool MpiBuilt() { return true; }
int MpiRank() { return g_rank; }
int MpiSize() { return g_size; }
PlanExecutor* MpiPlanExecutor() { return g_size > 1 ? &g_executor : nullptr; }

// Rank 0 answers each message: a worker that is ready gets kInFlight jobs, one
// that returns a result the next job (or, when none is left, nothing until
// every job is back); then every worker is told to stop. With two jobs in
// flight a worker starts its next job as soon as it sends a result, without
// waiting for rank 0 to answer (on a busy machine that answer takes longer
// than a small check); a job waits behind at most one other. Messages are
// polled with a short sleep (at most kPoll), so that rank 0 does not spin a
// core the workers need.
void MpiServeJobs(const std::vector<std::string>& jobs,
                  const std::function<void(size_t, const std::string&)>& on_result,
                  const std::function<void()>& on_wait) {
  constexpr auto kPoll = std::chrono::microseconds(200);
  constexpr int kInFlight = 2;
  size_t next = 0, outstanding = 0;
  // When on_result throws (RESULTS cannot be written), no more jobs go out,
  // but the results of the jobs still running are received (and dropped):
  // a worker must never be left blocked in a send when rank 0 stops.
  std::exception_ptr error;
  const auto hand_out = [&](int worker) {
    if (next < jobs.size() && !error) {
      std::string msg;
      PutU64(msg, next);
      msg += jobs[next++];
      Send(msg, worker, kJob);
      ++outstanding;
    }
  };
  // Every worker says it is ready once at the start.
  int ready = 0;
  auto sleep = std::chrono::microseconds(20);
  while (ready < g_size - 1 || (next < jobs.size() && !error) || outstanding > 0) {
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) {
      on_wait();
      std::this_thread::sleep_for(sleep);
      sleep = std::min(kPoll, sleep * 2);
      continue;
    }
    sleep = std::chrono::microseconds(20);
    const std::string msg = Receive(status.MPI_SOURCE, status.MPI_TAG, status);
    if (status.MPI_TAG == kResult) {
      size_t at = 0;
      const uint64_t k = GetU64(msg, at);
      --outstanding;
      if (k < jobs.size() && !error) {
        try {
          on_result(k, msg.substr(at));
        } catch (...) {
          error = std::current_exception();
        }
      }
      hand_out(status.MPI_SOURCE);
    } else {
      ++ready;
      for (int k = 0; k < kInFlight; ++k) hand_out(status.MPI_SOURCE);
    }
  }
  MpiStopWorkers();
  if (error) std::rethrow_exception(error);
}

void MpiStopWorkers() {
  if (g_workers_stopped || g_size <= 1 || g_rank != 0) return;
  g_workers_stopped = true;
  for (int r = 1; r < g_size; ++r) Send("", r, kStop);
}

void MpiWorkJobs(const std::function<std::string(const std::string&)>& run) {
  Send("", 0, kReady);
  // A result goes out without waiting for rank 0 to take it (MPI_Isend; a
  // large message waits for its receiver): the next job starts at once. It
  // is completed before the next result goes out, and before stopping.
  std::string pending;
  MPI_Request sent = MPI_REQUEST_NULL;
  while (true) {
    MPI_Status status;
    const std::string msg = Receive(0, MPI_ANY_TAG, status);
    if (status.MPI_TAG == kStop) break;
    size_t at = 0;
    const uint64_t k = GetU64(msg, at);
    std::string reply;
    PutU64(reply, k);
    reply += run(msg.substr(at));
    MPI_Wait(&sent, MPI_STATUS_IGNORE);
    pending = std::move(reply);
    MPI_Isend(pending.data(), static_cast<int>(pending.size()), MPI_BYTE, 0, kResult,
              MPI_COMM_WORLD, &sent);
  }
  MPI_Wait(&sent, MPI_STATUS_IGNORE);
}

}  // namespace cairn::cli

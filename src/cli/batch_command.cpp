// `cairn batch`: jobs from a JSON-lines file, each run in-process by its
// command's document function, results appended in the jobs' order
// (docs/batch.md).
#include "cli/batch_command.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <new>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "cairn/core/error.h"
#include "cairn/mechanics/rest_solution.h"
#include "cli/mpi.h"
#include "cli/progress.h"

namespace cairn::cli {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// A job that ran past --job-timeout (thrown from its checkpoint).
struct JobTimeout {};

// The exit code of a job that exceeded --job-timeout (docs/cli.md).
constexpr int kExitTimeout = 5;

std::string Dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// ---- JOBS -------------------------------------------------------------------

struct Job {
  std::string line;  // as in JOBS
  std::string id;    // the id, as JSON text: what RESULTS lines are matched by
};

// Every job of JOBS (blank lines skipped). A line that is not a JSON object
// with an id (a string or an integer), or an id given twice, makes the whole
// file bad input: such a job could not be recorded, nor found again on
// resume. Everything else about a job is its own error, recorded in RESULTS.
std::vector<Job> ReadJobs(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot read the jobs file");
  std::vector<Job> jobs;
  std::set<std::string> ids;
  std::string line;
  for (size_t n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const std::string where = "line " + std::to_string(n);
    const json j = json::parse(line, nullptr, false);
    if (j.is_discarded() || !j.is_object())
      throw InputError(path, where, "not a JSON object (one job per line)");
    const auto id = j.find("id");
    if (id == j.end() || !(id->is_string() || id->is_number_integer()))
      throw InputError(path, where, "a job needs an \"id\" (a string or an integer)");
    Job job{line, Dump(*id)};
    if (!ids.insert(job.id).second)
      throw InputError(path, where, "id " + job.id + " is given twice");
    jobs.push_back(std::move(job));
  }
  if (in.bad()) throw InputError(path, "", "cannot read the jobs file");
  return jobs;
}

// ---- A job's command line -----------------------------------------------------

// Options that write files of their own, or that `batch` sets itself.
bool RefusedOption(const std::string& name) {
  return name == "json" || name == "timeline" || name == "dot" || name == "emit-plans" ||
         name == "html" || name == "help" || name == "version";
}

// An option's value on the command line: numbers as JSON writes them, a list
// comma-separated (as the CLI's list options take them).
std::string OptionValue(const json& v, const std::string& where) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number()) return Dump(v);
  if (v.is_array()) {
    std::string out;
    for (const json& x : v) {
      if (!(x.is_string() || x.is_number()))
        throw InputError("", where, "a list of names or numbers was expected");
      out += (out.empty() ? "" : ",") + OptionValue(x, where);
    }
    return out;
  }
  throw InputError("", where, "a string, a number, a list or true was expected");
}

// The job's command line, as the user would type it after `cairn`.
std::vector<std::string> JobCommandLine(const json& job) {
  for (const auto& [key, value] : job.items())
    if (key != "id" && key != "command" && key != "model" && key != "plan" && key != "options")
      throw InputError("", EscapedName(key),
                       "unknown key of a job (known: id, command, model, plan, options)");
  const auto command = job.find("command");
  if (command == job.end() || !command->is_string())
    throw InputError("", "command", "missing: check, simulate, plan or blocking");
  const std::string name = command->get<std::string>();
  if (name != "check" && name != "simulate" && name != "plan" && name != "blocking")
    throw InputError("", "command",
                     "must be check, simulate, plan or blocking (got " + EscapedName(name) + ")");
  const auto model = job.find("model");
  if (model == job.end() || !model->is_string() || model->get<std::string>().empty())
    throw InputError("", "model", "missing: the model file (a path)");
  const auto plan = job.find("plan");
  if (name == "simulate" && (plan == job.end() || !plan->is_string()))
    throw InputError("", "plan", "missing: simulate needs a plan file (a path)");
  if (name != "simulate" && plan != job.end())
    throw InputError("", "plan", "only simulate takes a plan");

  std::vector<std::string> args{name};
  bool threads = false;
  if (const auto options = job.find("options"); options != job.end()) {
    if (!options->is_object()) throw InputError("", "options", "must be an object");
    for (const auto& [key, value] : options->items()) {
      std::string option = key;
      while (!option.empty() && option.front() == '-') option.erase(0, 1);
      const std::string where = "options." + EscapedName(key);
      if (option.empty()) throw InputError("", where, "not an option");
      if (RefusedOption(option))
        throw InputError("", where, "not in a batch (a job's result is its JSON document)");
      threads = threads || option == "threads";
      if (value.is_null() || (value.is_boolean() && !value.get<bool>())) continue;
      if (value.is_boolean())
        args.push_back("--" + option);
      else
        args.push_back("--" + option + "=" + OptionValue(value, where));
    }
  }
  // A plan job runs on one thread unless it says otherwise: the batch's
  // workers already fill the cores.
  if (name == "plan" && !threads) args.push_back("--threads=1");
  args.push_back("--");
  args.push_back(model->get<std::string>());
  if (name == "simulate") args.push_back(plan->get<std::string>());
  return args;
}

// ---- RESULTS ------------------------------------------------------------------

// RESULTS, opened for appending: with --fresh emptied; otherwise the ids
// already there are collected and a last line cut short (a batch killed while
// it wrote) is cut off, so that the file is whole lines again.
class Results {
 public:
  Results(const std::string& path, bool fresh, std::set<std::string>& done) : path_(path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
      throw InputError("", "-o", "'" + path + "' is not a regular file");
    if (!fresh) ReadDone(done);
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | (fresh ? O_TRUNC : 0),
                 0644);
    if (fd_ < 0) throw InputError("", "-o", "cannot write '" + path + "': " + std::strerror(errno));
    if (keep_ >= 0 && ::ftruncate(fd_, keep_) != 0)
      throw InputError("", "-o", "cannot write '" + path + "': " + std::strerror(errno));
  }
  ~Results() {
    if (fd_ >= 0) ::close(fd_);
  }
  Results(const Results&) = delete;
  Results& operator=(const Results&) = delete;

  // One line, appended and handed to the system at once (a killed batch
  // loses nothing written).
  void Append(std::string line) {
    line += '\n';
    for (size_t at = 0; at < line.size();) {
      const ssize_t n = ::write(fd_, line.data() + at, line.size() - at);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0)
        throw InputError("", "-o", "cannot write '" + path_ + "': " + std::strerror(errno));
      at += static_cast<size_t>(n);
    }
  }

 private:
  // Line by line (RESULTS may be large): the ids, and where a last line cut
  // short starts.
  void ReadDone(std::set<std::string>& done) {
    std::ifstream in(path_, std::ios::binary);
    if (!in) return;  // a new file
    long long at = 0;
    std::string line;
    for (size_t n = 1; std::getline(in, line); ++n) {
      if (in.eof()) {  // no newline after it: cut short, dropped
        keep_ = at;
        break;
      }
      at += static_cast<long long>(line.size()) + 1;
      const json j = json::parse(line, nullptr, false);
      if (j.is_discarded() || !j.is_object() || !j.contains("id") || !j.contains("exit"))
        throw InputError(path_, "line " + std::to_string(n),
                         "not a result of cairn batch (give --fresh to start over)");
      done.insert(Dump(j["id"]));
    }
  }

  std::string path_;
  int fd_ = -1;
  long long keep_ = -1;  // ≥ 0: the length to cut the file to
};

// ---- Progress -------------------------------------------------------------------

// Jobs done, failed, their rate and the time left: on a terminal only.
class BatchProgress {
 public:
  explicit BatchProgress(size_t total) : total_(total) {}
  void Count(int exit) {
    ++done_;
    ++by_exit_[std::clamp(exit, 0, 9)];
  }
  void Show() {
    const double t = std::chrono::duration<double>(Clock::now() - start_).count();
    const double rate = t > 0 ? done_ / t : 0;
    std::ostringstream os;
    os.precision(3);
    os << done_ << "/" << total_ << " jobs, " << Failed() << " failed, " << rate << " jobs/s";
    if (rate > 0) os << ", " << static_cast<long long>((total_ - done_) / rate) << " s left";
    line_.Show(os.str());
  }
  void Done() { line_.Done(); }
  // Failed: bad input, internal error, timed out (3 is simulate's
  // infeasible: a verdict).
  size_t Failed() const { return by_exit_[2] + by_exit_[4] + by_exit_[kExitTimeout]; }
  const std::array<size_t, 10>& by_exit() const { return by_exit_; }

 private:
  size_t total_, done_ = 0;
  std::array<size_t, 10> by_exit_{};
  Progress line_{"cairn batch"};
  Clock::time_point start_ = Clock::now();
};

// ---- Workers --------------------------------------------------------------------

// Results arrive in any order; they are written in the jobs' order.
class InOrder {
 public:
  InOrder(size_t n, Results& results, BatchProgress& progress)
      : slots_(n), results_(results), progress_(progress) {}
  void Put(size_t k, JobResult result) { slots_[k] = std::move(result); }
  void Flush() {
    while (next_ < slots_.size() && slots_[next_]) {
      progress_.Count(slots_[next_]->exit);
      results_.Append(std::move(slots_[next_]->line));
      slots_[next_++].reset();
    }
  }
  bool complete() const { return next_ == slots_.size(); }

 private:
  std::vector<std::optional<JobResult>> slots_;
  size_t next_ = 0;
  Results& results_;
  BatchProgress& progress_;
};

// Without MPI ranks: `threads` threads take the next job as they finish one
// (dynamic: a long job holds up only its thread); this thread writes.
void RunOnThreads(const std::vector<const Job*>& todo, int threads, const JobParser& parse,
                  double timeout, InOrder& order, BatchProgress& progress) {
  std::mutex mutex;
  std::condition_variable ready;
  std::vector<std::pair<size_t, JobResult>> finished;  // under `mutex`
  std::atomic<size_t> next{0};
  std::atomic<bool> stop{false};
  const auto work = [&] {
    for (size_t k = next++; k < todo.size() && !stop; k = next++) {
      JobResult line = RunJob(todo[k]->line, parse, timeout);
      const std::lock_guard<std::mutex> lock(mutex);
      finished.emplace_back(k, std::move(line));
      ready.notify_one();
    }
    ReleaseThreadSolverState();  // the LP solvers' per-thread state
  };
  std::vector<std::thread> pool;
  // Joined on every way out (a write that fails stops the others first).
  struct Join {
    std::atomic<bool>& stop;
    std::vector<std::thread>& pool;
    ~Join() {
      stop = true;
      for (std::thread& t : pool) t.join();
    }
  } join{stop, pool};
  const int n = std::max(1, std::min<int>(threads, static_cast<int>(todo.size())));
  for (int t = 0; t < n; ++t) pool.emplace_back(work);
  size_t taken = 0;
  while (taken < todo.size()) {
    std::unique_lock<std::mutex> lock(mutex);
    ready.wait_for(lock, std::chrono::milliseconds(250), [&] { return !finished.empty(); });
    std::vector<std::pair<size_t, JobResult>> got;
    got.swap(finished);
    lock.unlock();
    for (auto& [k, line] : got) order.Put(k, std::move(line));
    taken += got.size();
    order.Flush();
    progress.Show();
  }
}

std::string Summary(size_t run, size_t skipped, const BatchProgress& progress) {
  std::ostringstream os;
  os << "cairn batch: " << run << " job" << (run == 1 ? "" : "s") << " run";
  if (skipped > 0) os << ", " << skipped << " already in RESULTS";
  const char* what[10] = {"stable",    "not stable", "bad input", "infeasible", "internal error",
                          "timed out", "",           "",          "",           "other exit code"};
  for (int code = 0; code < 10; ++code)
    if (progress.by_exit()[code] > 0)
      os << "; " << progress.by_exit()[code] << " " << what[code] << " (exit " << code << ")";
  os << '\n';
  return os.str();
}

}  // namespace

JobResult RunJob(const std::string& line, const JobParser& parse, double job_timeout) {
  // The line: {"id":…,"exit":…,"result":…} or {"id":…,"exit":…,"error":…},
  // written out directly (the document is dumped once, not copied).
  std::string id = "null";
  int exit = kExitInternalError;
  std::string tail;  // ,"result":… or ,"error":…
  const auto error = [&](int code, const std::string& message) {
    exit = code;
    tail = ",\"error\":" + Dump(json(message));
  };
  try {
    const json job = json::parse(line);
    id = Dump(job.at("id"));
    const auto start = Clock::now();
    const auto deadline =
        start + std::chrono::duration_cast<Clock::duration>(
                    std::chrono::duration<double>(job_timeout > 0 ? job_timeout : 0));
    // The deadline is cooperative: checked before each node check and at
    // every time step; a check (one solve) is not interrupted, but a job that
    // ends past its deadline is recorded as timed out all the same.
    const Checkpoint checkpoint = [&] {
      if (job_timeout > 0 && Clock::now() > deadline) throw JobTimeout{};
    };
    const JobCommand command = parse(JobCommandLine(job));
    const CommandDocument doc = command(checkpoint);
    checkpoint();
    exit = doc.exit;
    tail = ",\"result\":" + Dump(doc.json);
  } catch (const JobTimeout&) {
    std::ostringstream os;
    os << "exceeded --job-timeout " << job_timeout << " s";
    error(kExitTimeout, os.str());
  } catch (const InputError& e) {
    error(kExitBadInput, e.what());
  } catch (const std::bad_alloc&) {
    error(kExitInternalError, "internal error: out of memory");
  } catch (const std::exception& e) {
    error(kExitInternalError, std::string("internal error: ") + e.what());
  } catch (...) {
    error(kExitInternalError, "internal error: an unknown exception");
  }
  return {"{\"id\":" + id + ",\"exit\":" + std::to_string(exit) + tail + "}", exit};
}

int RunBatch(const BatchArgs& args, const JobParser& parse, std::ostream& out, std::ostream& err) {
  // Under mpirun, the ranks but 0 run the jobs rank 0 hands out.
  if (MpiSize() > 1 && MpiRank() != 0) {
    // The exit code travels before the line, to rank 0's counts.
    MpiWorkJobs([&](const std::string& line) {
      const JobResult r = RunJob(line, parse, args.job_timeout);
      return std::to_string(r.exit) + ' ' + r.line;
    });
    return kExitStable;
  }
  const int code = RunGuarded(err, [&]() -> int {
    if (args.fresh && args.resume)
      throw InputError("", "--fresh", "and --resume exclude each other");
    const std::vector<Job> jobs = ReadJobs(args.jobs);
    std::set<std::string> done;
    Results results(args.output, args.fresh, done);
    std::vector<const Job*> todo;
    for (const Job& job : jobs)
      if (!done.count(job.id)) todo.push_back(&job);

    BatchProgress progress(todo.size());
    InOrder order(todo.size(), results, progress);
    if (MpiSize() > 1) {
      std::vector<std::string> lines;
      for (const Job* job : todo) lines.push_back(job->line);
      MpiServeJobs(
          lines,
          [&](size_t k, const std::string& message) {
            // "EXIT LINE": the exit code, a space, the line.
            size_t space = 0;
            while (space < message.size() && message[space] != ' ') ++space;
            JobResult r{message.substr(std::min(space + 1, message.size())),
                        std::atoi(message.c_str())};
            order.Put(k, std::move(r));
            order.Flush();
            progress.Show();
          },
          [&] { progress.Show(); });
    } else {
      const int threads = args.threads > 0
                              ? args.threads
                              : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
      RunOnThreads(todo, threads, parse, args.job_timeout, order, progress);
    }
    progress.Done();
    out << Summary(todo.size(), jobs.size() - todo.size(), progress);
    return kExitStable;
  });
  MpiStopWorkers();  // on every way out: the other ranks must not wait for jobs
  return code;
}

}  // namespace cairn::cli

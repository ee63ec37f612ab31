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
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <new>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <thread>

#include "cairn/core/error.h"
#include "cairn/io/input_file.h"
#include "cairn/io/json_line.h"
#include "cairn/mechanics/rest_solution.h"
#include "cli/mpi.h"
#include "cli/output_files.h"
#include "cli/progress.h"

namespace cairn::cli {
namespace {

using nlohmann::json;
using Clock = std::chrono::steady_clock;

// A job that ran past --job-timeout (thrown from its checkpoint).
struct JobTimeout {};

// The exit code of a job that exceeded --job-timeout (docs/cli.md).
constexpr int kExitTimeout = 5;

// A --job-timeout at or above this many seconds (about 32 years) means no
// deadline: a deadline is a count of nanoseconds (std::chrono's int64), and
// 1e9 s is far inside it wherever the clock starts.
constexpr double kMaxJobTimeoutSeconds = 1e9;

std::string Dump(const json& j) { return j.dump(-1, ' ', false, json::error_handler_t::replace); }

// ---- Lines of JSON --------------------------------------------------------------

// "a string", "a number", ... (for messages).
std::string Article(const json& j) {
  const std::string t = j.type_name();
  return (t == "array" || t == "object" ? "an " : "a ") + t;
}

// The batch reads its own files (JOBS, RESULTS) and a job's files only when
// they are regular files: a FIFO would block the read forever (no deadline
// reaches into a read), a device such as /dev/zero would never end. A folder
// is let through where `folder_ok` (an ASAP model). Nothing is said of a
// path that does not exist: its reader says so.
void RefuseSpecialFile(const std::string& path, bool folder_ok) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return;  // absent: said where it is read
  if (folder_ok && IsDirectory(path)) return;
  CheckInputFile(path, std::numeric_limits<std::uint64_t>::max());
}

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
  RefuseSpecialFile(path, false);
  std::ifstream in(path);
  if (!in) throw InputError(path, "", "cannot read the jobs file");
  std::vector<Job> jobs;
  std::set<std::string> ids;
  std::string line;
  for (size_t n = 1; std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    const std::string where = "line " + std::to_string(n);
    const JsonLine parsed = ParseJsonLine(line);
    if (!parsed.value) throw InputError(path, where, parsed.why + " (one job per line)");
    const json& j = *parsed.value;
    if (!j.is_object())
      throw InputError(path, where, "not a JSON object (one job per line), but " + Article(j));
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

// An option's name as the command line spells it after its dashes: letters,
// digits and inner dashes (so that a key cannot carry a value, `html=x.html`,
// or a second argument).
bool OptionName(const std::string& name) {
  if (name.empty() || !std::isalnum(static_cast<unsigned char>(name.front()))) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-';
  });
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
        throw InputError("", where,
                         "a list of names or numbers was expected, not a list of " +
                             std::string(x.type_name()) + "s");
      out += (out.empty() ? "" : ",") + OptionValue(x, where);
    }
    return out;
  }
  throw InputError("", where,
                   "must be a string, a number, a list or true (a flag), not " + Article(v));
}

// A file name of a job (`model`, `plan`): a non-empty string.
std::string JobFile(const json& job, const char* key, const std::string& what) {
  const auto it = job.find(key);
  if (it == job.end()) throw InputError("", key, "missing: " + what);
  if (!it->is_string())
    throw InputError("", key, "must be a file name (a string), not " + Article(*it));
  if (it->get<std::string>().empty()) throw InputError("", key, "the file name is empty");
  return it->get<std::string>();
}

constexpr const char* kCommands = "check, simulate, plan, blocking, margin or sequence";

// The job's command line, as the user would type it after `cairn`.
std::vector<std::string> JobCommandLine(const json& job) {
  for (const auto& [key, value] : job.items())
    if (key != "id" && key != "command" && key != "model" && key != "plan" && key != "options")
      throw InputError("", key.empty() ? "\"\"" : EscapedName(key),
                       "unknown key of a job (known: id, command, model, plan, options)");
  const auto command = job.find("command");
  if (command == job.end()) throw InputError("", "command", std::string("missing: ") + kCommands);
  if (!command->is_string())
    throw InputError("", "command",
                     std::string("must be ") + kCommands + " (a string), not " + Article(*command));
  const std::string name = command->get<std::string>();
  if (name != "check" && name != "simulate" && name != "plan" && name != "blocking" &&
      name != "margin" && name != "sequence")
    throw InputError("", "command",
                     std::string("must be ") + kCommands + " (got " + EscapedName(name) + ")");
  const std::string model = JobFile(job, "model", "the model file (a path)");
  std::string plan;
  if (name == "simulate") plan = JobFile(job, "plan", "simulate needs a plan file (a path)");
  if (name != "simulate" && job.contains("plan"))
    throw InputError("", "plan", "only simulate takes a plan");

  std::vector<std::string> args{name};
  bool threads = false, asap = false;
  std::vector<std::string> files{plan};  // besides the model, to be read (sidecar, paths)
  if (const auto options = job.find("options"); options != job.end()) {
    if (!options->is_object())
      throw InputError("", "options", "must be an object, not " + Article(*options));
    for (const auto& [key, value] : options->items()) {
      std::string option = key;
      while (!option.empty() && option.front() == '-') option.erase(0, 1);
      const std::string where = "options." + (key.empty() ? "\"\"" : EscapedName(key));
      // The name before any `=`: an output option is refused however it is spelled.
      if (RefusedOption(option.substr(0, option.find('='))))
        throw InputError("", where,
                         "not in a batch: the output options (--json, --html, --timeline, --dot, "
                         "--emit-plans) are not for batch jobs (a job's result is its JSON "
                         "document)");
      if (!OptionName(option))
        throw InputError("", where,
                         option.find('=') != std::string::npos
                             ? "an option's name has no '=': its value is the key's value"
                             : "not an option name");
      threads = threads || option == "threads";
      if (value.is_null() || (value.is_boolean() && !value.get<bool>())) continue;
      if (value.is_boolean()) {
        args.push_back("--" + option);
        continue;
      }
      const std::string text = OptionValue(value, where);
      if (option == "format") asap = text == "asap";
      if (option == "sidecar" || option == "paths") files.push_back(text);
      args.push_back("--" + option + "=" + text);
    }
  }
  // What the job reads must be a regular file (a FIFO would block the batch).
  RefuseSpecialFile(model, asap);
  for (const std::string& f : files)
    if (!f.empty()) RefuseSpecialFile(f, false);
  // A plan or sequence job runs on one thread unless it says otherwise: the
  // batch's workers already fill the cores.
  if ((name == "plan" || name == "sequence") && !threads) args.push_back("--threads=1");
  args.push_back("--");
  args.push_back(model);
  if (name == "simulate") args.push_back(plan);
  return args;
}

// ---- RESULTS ------------------------------------------------------------------

// What a RESULTS line must be: a JSON object with an id (a string or an
// integer, as JOBS gives them) and an exit code. Empty when it is not.
struct RecordedResult {
  std::string id;  // as JSON text
  int exit = 0;
};
std::optional<RecordedResult> AsResult(const JsonLine& parsed) {
  if (!parsed.value || !parsed.value->is_object()) return std::nullopt;
  const json& j = *parsed.value;
  const auto id = j.find("id"), exit = j.find("exit");
  if (id == j.end() || !(id->is_string() || id->is_number_integer())) return std::nullopt;
  if (exit == j.end() || !exit->is_number_integer()) return std::nullopt;
  return RecordedResult{Dump(*id), exit->get<int>()};
}

// Failed: bad input, internal error, timed out (3 is simulate's infeasible,
// a verdict). What --retry-failed runs again, and the progress line counts.
bool Failed(int exit) {
  return exit == kExitBadInput || exit == kExitInternalError || exit == kExitTimeout;
}

// RESULTS, opened for appending: with --fresh emptied; otherwise the ids
// already there are collected and a last line cut short (a batch killed while
// it wrote) is cut off, so that the file is whole lines again. With
// --retry-failed the lines of failed jobs are taken out (their jobs run
// again).
class Results {
 public:
  Results(const std::string& path, bool fresh, bool retry, std::set<std::string>& done)
      : path_(path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
      throw InputError("", "-o", "'" + path + "' is not a regular file");
    if (!fresh) ReadDone(done, retry);
    if (!dropped_.empty()) Rewrite();
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

  // The ids whose failed results were taken out (--retry-failed).
  const std::set<std::string>& retried() const { return retried_; }

 private:
  [[noreturn]] void NotAResult(size_t n, const std::string& why) const {
    throw InputError(path_, "line " + std::to_string(n),
                     "not a result of cairn batch" + (why.empty() ? "" : " (" + why + ")") +
                         "; give --fresh to start over");
  }

  // Line by line (RESULTS may be large): the ids, and where a last line cut
  // short starts.
  void ReadDone(std::set<std::string>& done, bool retry) {
    std::ifstream in(path_, std::ios::binary);
    if (!in) return;  // a new file
    long long at = 0;
    std::string line;
    for (size_t n = 1; std::getline(in, line); ++n) {
      const JsonLine parsed = ParseJsonLine(line);
      const std::optional<RecordedResult> result = AsResult(parsed);
      if (in.eof()) {
        // No newline after it. A batch writes a line and its newline at once,
        // so only a write cut short leaves this: the start of a result (or
        // the whole of one), dropped to be written again. Anything else is
        // not RESULTS, and is refused as a line with its newline is.
        const std::string head = "{\"id\":";  // how every result line starts
        const bool start_of_result = line.size() < head.size()
                                         ? head.rfind(line, 0) == 0
                                         : line.rfind(head, 0) == 0 && parsed.cut_short;
        if (!start_of_result && !result) NotAResult(n, parsed.why);
        keep_ = at;
        break;
      }
      at += static_cast<long long>(line.size()) + 1;
      if (!result) NotAResult(n, parsed.why);
      if (retry && Failed(result->exit)) {
        dropped_.insert(n);
        retried_.insert(result->id);
      } else {
        done.insert(result->id);
      }
    }
    if (in.bad()) throw InputError(path_, "", "cannot read the results file");
  }

  // RESULTS without the dropped lines (and without a last line cut short):
  // written to a temporary file beside it (beside the file a link names),
  // then renamed over it, so that a batch killed meanwhile leaves RESULTS as
  // it was.
  void Rewrite() {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path target = fs::canonical(path_, ec);
    if (ec) throw InputError("", "-o", "cannot write '" + path_ + "': " + ec.message());
    const fs::path temp = target.parent_path() / ("." + target.filename().string() + ".cairn-" +
                                                  std::to_string(::getpid()) + ".tmp");
    bool written = false;
    {
      std::ifstream in(path_, std::ios::binary);
      std::ofstream out(temp, std::ios::binary | std::ios::trunc);
      std::string line;
      for (size_t n = 1; std::getline(in, line) && !in.eof(); ++n)
        if (!dropped_.count(n)) out << line << '\n';
      written = !in.bad() && out.flush();
    }
    if (written) fs::rename(temp, target, ec);
    if (!written || ec) {
      const std::string why = ec ? ec.message() : std::string(std::strerror(errno));
      fs::remove(temp, ec);
      throw InputError("", "-o", "cannot write '" + path_ + "': " + why);
    }
    keep_ = -1;
  }

  std::string path_;
  int fd_ = -1;
  long long keep_ = -1;            // ≥ 0: the length to cut the file to
  std::set<size_t> dropped_;       // lines taken out (--retry-failed)
  std::set<std::string> retried_;  // their ids
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
  size_t Failed() const {
    size_t n = 0;
    for (int code = 0; code < 10; ++code) n += cli::Failed(code) ? by_exit_[code] : 0;
    return n;
  }
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

std::string Summary(size_t run, size_t retried, size_t skipped, const BatchProgress& progress) {
  std::ostringstream os;
  os << "cairn batch: " << run << " job" << (run == 1 ? "" : "s") << " run";
  if (retried > 0) os << " (" << retried << " of them again: --retry-failed)";
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
    // The deadline is cooperative: checked before each node check and at
    // every time step; a check (one solve) is not interrupted, but a job that
    // ends past its deadline is recorded as timed out all the same. A
    // timeout of kMaxJobTimeoutSeconds or more is none.
    const bool limited = job_timeout > 0 && job_timeout < kMaxJobTimeoutSeconds;
    const auto deadline =
        Clock::now() + std::chrono::duration_cast<Clock::duration>(
                           std::chrono::duration<double>(limited ? job_timeout : 0));
    const Checkpoint checkpoint = [&] {
      if (limited && Clock::now() > deadline) throw JobTimeout{};
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
    if (args.fresh && args.retry_failed)
      throw InputError("", "--fresh",
                       "and --retry-failed exclude each other (--fresh runs every job)");
    const std::vector<Job> jobs = ReadJobs(args.jobs);
    // RESULTS is never JOBS (nor a link to it).
    CheckOutputs({{args.output, "-o"}}, {{args.jobs, "the jobs file"}});
    std::set<std::string> done;
    Results results(args.output, args.fresh, args.retry_failed, done);
    std::vector<const Job*> todo;
    size_t retried = 0;
    for (const Job& job : jobs) {
      if (done.count(job.id)) continue;
      todo.push_back(&job);
      retried += results.retried().count(job.id);
    }

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
    out << Summary(todo.size(), retried, jobs.size() - todo.size(), progress);
    return kExitStable;
  });
  MpiStopWorkers();  // on every way out: the other ranks must not wait for jobs
  return code;
}

}  // namespace cairn::cli

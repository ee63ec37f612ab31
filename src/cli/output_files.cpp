#include "cli/output_files.h"

#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>

#include "cairn/core/error.h"

namespace cairn::cli {

namespace {

namespace fs = std::filesystem;

// The temporary files being written, for the signal handler: a fixed table of
// paths (a handler may neither allocate nor lock). Process-wide by nature (a
// signal is); touched only by OutputFiles and the handler.
constexpr int kMaxPending = 64;
constexpr int kMaxLinks = 40;  // as the kernel's own limit on a chain of links
constexpr size_t kMaxPath = 4096;
std::array<std::array<char, kMaxPath>, kMaxPending> g_pending{};
std::array<std::atomic<bool>, kMaxPending> g_used{};

extern "C" void RemovePendingAndReraise(int sig) {
  for (int i = 0; i < kMaxPending; ++i)
    if (g_used[i].load()) ::unlink(g_pending[i].data());
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void InstallHandlers() {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, RemovePendingAndReraise);
    return true;
  }();
  (void)installed;
}

// A slot of the table holding `path`, or -1 when the table is full (the file
// is still written, only not cleaned up by a signal).
int Register(const std::string& path) {
  if (path.size() >= kMaxPath) return -1;
  for (int i = 0; i < kMaxPending; ++i) {
    if (g_used[i].load()) continue;
    std::memcpy(g_pending[i].data(), path.c_str(), path.size() + 1);
    g_used[i].store(true);
    return i;
  }
  return -1;
}

void Unregister(const std::string& path) {
  for (int i = 0; i < kMaxPending; ++i)
    if (g_used[i].load() && path == g_pending[i].data()) g_used[i].store(false);
}

}  // namespace

OutputFiles::~OutputFiles() {
  if (!committed_) Discard();
}

void OutputFiles::Add(const std::string& path, std::string text, const std::string& flag) {
  if (path.empty()) throw InputError("", flag, "the file name is empty");
  std::error_code ec;
  fs::path target(path);
  // Followed on purpose (a chain of links too, even to a file that does not
  // exist yet): the file the link names is replaced, the link kept.
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
    const fs::path to = fs::read_symlink(target, ec);
    if (ec || hops == kMaxLinks)
      throw InputError("", flag,
                       "cannot follow the link '" + path + "'" +
                           (ec ? ": " + ec.message() : ": too many links"));
    target = to.is_absolute() ? to : target.parent_path() / to;
  }

  const fs::file_status st = fs::status(target, ec);
  const bool exists = fs::exists(st);
  if (exists && !fs::is_regular_file(st))
    throw InputError("", flag,
                     "'" + path + "' exists and is not a regular file (" +
                         (fs::is_directory(st) ? "a folder" : "a device, FIFO or socket") +
                         "): Cairn only writes regular files");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string temp =
      (dir / ("." + target.filename().string() + ".cairn-" + std::to_string(::getpid()) + ".tmp"))
          .string();
  files_.push_back({target.string(), path, temp, std::move(text), flag, exists});
}

void OutputFiles::Commit() {
  InstallHandlers();
  for (File& f : files_) {
    Register(f.temp);
    std::ofstream out(f.temp, std::ios::binary | std::ios::trunc);
    if (!(out << f.text) || !out.flush()) {
      const std::string why = std::strerror(errno);
      out.close();
      Discard();
      throw InputError("", f.flag, "cannot write '" + f.shown + "': " + why);
    }
  }
  for (size_t k = 0; k < files_.size(); ++k) {
    std::error_code ec;
    fs::rename(files_[k].temp, files_[k].target, ec);
    if (ec) {
      // The ones renamed already are taken back where they were new.
      for (size_t j = 0; j < k; ++j)
        if (!files_[j].existed) fs::remove(files_[j].target, ec);
      Discard();
      throw InputError("", files_[k].flag,
                       "cannot write '" + files_[k].shown + "': " + ec.message());
    }
    Unregister(files_[k].temp);
  }
  committed_ = true;
}

void OutputFiles::Discard() {
  for (const File& f : files_) {
    std::error_code ec;
    fs::remove(f.temp, ec);
    Unregister(f.temp);
  }
}

}  // namespace cairn::cli

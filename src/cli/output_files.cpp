#include "cli/output_files.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
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

namespace fs = std::filesystem;

// What the signal handler undoes of one commit in progress: its temporary
// files, the targets it is renaming or has renamed that did not exist before,
// and the folders it made. Built before the first file is written; the
// strings it points to (the File records) do not change during the commit.
struct PendingCommit {
  std::vector<const char*> temps, targets;  // (files)
  std::vector<char> existed;                // (files) the target was there before
  // (files) set just before the temporary is renamed over the target.
  std::unique_ptr<std::atomic<bool>[]> renaming;
  std::vector<const char*> folders;     // the missing folders, deepest first
  std::atomic<size_t> folders_made{0};  // made so far, from the top of `folders`
  int slot = -1;                        // in g_commits, or -1
};

namespace {

constexpr int kMaxLinks = 40;  // as the kernel's own limit on a chain of links

// The commits in progress, for the signal handler (a handler may neither
// allocate nor lock: it only reads these records and calls unlink and
// rmdir). Process-wide by nature (a signal is); touched only by OutputFiles
// and the handler. A slot holds one commit, whatever its number of files;
// kMaxCommits bounds only the commits running at once (on several threads).
// A commit that finds every slot taken is still written, only not cleaned up
// by a signal.
constexpr int kMaxCommits = 64;
std::array<std::atomic<PendingCommit*>, kMaxCommits> g_commits{};
// Set by the handler before it reads g_commits: a commit that ends then does
// not free its record (the process is about to end).
std::atomic<bool> g_handling{false};

extern "C" void RemovePendingAndReraise(int sig) {
  g_handling.store(true);
  for (auto& slot : g_commits) {
    const PendingCommit* p = slot.load();
    if (p == nullptr) continue;
    for (size_t k = 0; k < p->temps.size(); ++k) {
      ::unlink(p->temps[k]);
      if (p->renaming[k].load() && !p->existed[k]) ::unlink(p->targets[k]);
    }
    const size_t made = p->folders_made.load();
    for (size_t k = p->folders.size() - made; k < p->folders.size(); ++k) ::rmdir(p->folders[k]);
  }
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

void Register(PendingCommit* p) {
  for (int i = 0; i < kMaxCommits; ++i) {
    PendingCommit* empty = nullptr;
    if (g_commits[i].compare_exchange_strong(empty, p)) {
      p->slot = i;
      return;
    }
  }
}

// Takes the record out of the handler's view. When a handler is already at
// work, its process is about to end: the record stays where it is.
void Unregister(PendingCommit* p) {
  if (p == nullptr || p->slot < 0) return;
  g_commits[p->slot].store(nullptr);
  p->slot = -1;
  while (g_handling.load()) ::pause();
}

// The file a path names, links followed (a chain of links too, even to a file
// that does not exist yet). @throws InputError naming `flag`.
fs::path Resolve(const std::string& path, const std::string& flag) {
  std::error_code ec;
  fs::path target(path);
  for (int hops = 0; fs::is_symlink(fs::symlink_status(target, ec)); ++hops) {
    const fs::path to = fs::read_symlink(target, ec);
    if (ec || hops == kMaxLinks)
      throw InputError("", flag,
                       "cannot follow the link '" + path + "'" +
                           (ec ? ": " + ec.message() : ": too many links"));
    target = to.is_absolute() ? to : target.parent_path() / to;
  }
  return target;
}

// What identifies a file: its device and inode when it exists (a link, a hard
// link, another spelling of the path: the same file), else its absolute path
// with the links of its existing folders resolved.
std::string SameFileKey(const fs::path& p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) == 0)
    return "inode " + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  std::error_code ec;
  const fs::path absolute = fs::absolute(p, ec).lexically_normal();
  fs::path c = fs::weakly_canonical(absolute, ec);
  if (ec) c = absolute;
  return "path " + c.string();
}

// Whether the existing file `file` lies inside the folder `dir` (at any depth).
bool Inside(const fs::path& file, const fs::path& dir) {
  std::error_code ec1, ec2;
  const fs::path f = fs::canonical(file, ec1), d = fs::canonical(dir, ec2);
  if (ec1 || ec2) return false;
  const auto [d_end, f_at] = std::mismatch(d.begin(), d.end(), f.begin(), f.end());
  return d_end == d.end() && f_at != f.end();
}

}  // namespace

std::vector<NamedFile> ModelInputs(const std::string& file, const app::ModelArgs& args,
                                   const std::string& name) {
  std::vector<NamedFile> inputs{{file, name}};
  if (args.format == "asap") {
    std::error_code ec;
    if (!fs::is_directory(file, ec))
      inputs.push_back({fs::absolute(file, ec).parent_path().string(), name + "'s folder"});
  }
  if (!args.sidecar.empty()) inputs.push_back({args.sidecar, "--sidecar"});
  return inputs;
}

void CheckOutputs(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
  OutputFiles files(inputs);
  for (const NamedFile& out : outputs)
    if (!out.path.empty()) files.Add(out.path, "", out.name);
}

OutputFiles::OutputFiles(std::vector<NamedFile> inputs) : inputs_(std::move(inputs)) {
  for (const NamedFile& in : inputs_) {
    std::error_code ec;
    input_keys_.push_back(!in.path.empty() && fs::exists(in.path, ec) ? SameFileKey(in.path) : "");
  }
}

OutputFiles::~OutputFiles() {
  if (!committed_) Discard();
}

void OutputFiles::Add(const std::string& path, std::string text, const std::string& flag) {
  if (path.empty()) throw InputError("", flag, "the file name is empty");
  // Followed on purpose: the file the link names is replaced, the link kept.
  const fs::path target = Resolve(path, flag);

  std::error_code ec;
  const fs::file_status st = fs::status(target, ec);
  const bool exists = fs::exists(st);
  if (exists && !fs::is_regular_file(st))
    throw InputError("", flag,
                     "'" + path + "' exists and is not a regular file (" +
                         (fs::is_directory(st) ? "a folder" : "a device, FIFO or socket") +
                         "): Cairn only writes regular files");
  // An output never replaces an input, nor another output of the same run.
  const std::string key = SameFileKey(target);
  for (size_t i = 0; i < inputs_.size(); ++i) {
    if (key == input_keys_[i])
      throw InputError("", "",
                       flag + " and " + inputs_[i].name + " name the same file '" + path +
                           "': an output never replaces an input");
    if (exists && fs::is_directory(inputs_[i].path, ec) && Inside(target, inputs_[i].path))
      throw InputError("", flag,
                       "'" + path + "' is inside " + inputs_[i].name + " ('" + inputs_[i].path +
                           "'), a folder read as input: an output never replaces an input");
  }
  if (const auto twice = by_key_.find(key); twice != by_key_.end()) {
    const std::string& first = files_[twice->second].flag;
    throw InputError("", "",
                     first == flag ? flag + " names the file '" + path + "' twice"
                                   : first + " and " + flag + " name the same file '" + path + "'");
  }
  by_key_.emplace(key, files_.size());
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string temp =
      (dir / ("." + target.filename().string() + ".cairn-" + std::to_string(::getpid()) + ".tmp"))
          .string();
  files_.push_back({target.string(), path, temp, std::move(text), flag, key, exists});
}

void OutputFiles::AddFolder(const std::string& dir, const std::string& flag) {
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (fs::exists(st) && !fs::is_directory(st))
    throw InputError("", flag, "'" + dir + "' exists and is not a folder");
  folder_ = dir;
  folder_flag_ = flag;
}

void OutputFiles::Commit() {
  InstallHandlers();
  // The missing folders, deepest first (made top first).
  made_folders_.clear();
  if (!folder_.empty()) {
    std::error_code ec;
    for (fs::path p(folder_); !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
      made_folders_.push_back(p.string());
      if (p == p.parent_path()) break;
    }
  }
  // The record for the signal handler, before anything is made.
  pending_ = std::make_unique<PendingCommit>();
  pending_->renaming = std::make_unique<std::atomic<bool>[]>(files_.size());
  for (const File& f : files_) {
    pending_->temps.push_back(f.temp.c_str());
    pending_->targets.push_back(f.target.c_str());
    pending_->existed.push_back(f.existed ? 1 : 0);
  }
  for (const std::string& d : made_folders_) pending_->folders.push_back(d.c_str());
  Register(pending_.get());

  for (size_t k = made_folders_.size(); k-- > 0;) {
    std::error_code ec;
    fs::create_directory(made_folders_[k], ec);
    if (ec) {
      Discard();
      throw InputError("", folder_flag_, "cannot create folder '" + folder_ + "': " + ec.message());
    }
    ++pending_->folders_made;
  }
  for (File& f : files_) {
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
    pending_->renaming[k].store(true);
    fs::rename(files_[k].temp, files_[k].target, ec);
    if (ec) {
      // The ones renamed already are taken back where they were new.
      for (size_t j = 0; j < k; ++j)
        if (!files_[j].existed) fs::remove(files_[j].target, ec);
      Discard();
      throw InputError("", files_[k].flag,
                       "cannot write '" + files_[k].shown + "': " + ec.message());
    }
  }
  Unregister(pending_.get());
  committed_ = true;
}

void OutputFiles::Discard() {
  std::error_code ec;
  for (const File& f : files_) fs::remove(f.temp, ec);
  // The folders this commit made (now empty), deepest first.
  const size_t made = pending_ ? pending_->folders_made.load() : 0;
  for (size_t k = made_folders_.size() - made; k < made_folders_.size(); ++k)
    fs::remove(made_folders_[k], ec);
  Unregister(pending_.get());
}

}  // namespace cairn::cli

#pragma once
// The files a command writes (--timeline, --dot, --emit-plans, --html,
// convert's output), all or none.
//
// Each file is first written whole to a temporary file beside its target
// (the same folder, so that the rename is atomic), and only when every one
// is complete are they renamed over their targets: a reader never sees half a
// file, and a failed run (a full disk, a folder it may not write) leaves the
// targets as they were. Targets are checked before anything is written:
//  - an existing target that is not a regular file (a device such as
//    /dev/full, a folder, a FIFO) is refused: renaming over it would replace
//    a system file with a regular one;
//  - a target that is one of the command's inputs (the model, the plan,
//    --sidecar, --paths, the jobs file; through links and hard links too), or
//    an existing file inside an input folder (an ASAP assembly), is refused:
//    an output never replaces an input;
//  - two outputs that name the same file are refused;
//  - a symbolic link is followed deliberately: the file it points to is
//    replaced and the link is kept.
// A run killed by SIGINT, SIGTERM or SIGHUP while it commits removes what the
// commit made, for any number of files (a handler unlinks the temporary
// files and the targets that did not exist before, removes the folders the
// commit made, then the signal ends the process as before); only SIGKILL can
// leave a temporary file, named `.NAME.cairn-PID.tmp`, never half a target.

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cairn/app/model.h"

namespace cairn::cli {

struct PendingCommit;  // a commit in progress, as the signal handler sees it

/// A file (or folder) on the command line and the name the messages give it:
/// an option (`--sidecar`) or an argument ("the model file").
struct NamedFile {
  std::string path;
  std::string name;
};

/// The files a command reads for its model `file` (named `name`): the file
/// itself, its `--sidecar`, and with `--format asap` the assembly folder
/// (the folder given, or the folder of its config.json).
std::vector<NamedFile> ModelInputs(const std::string& file, const app::ModelArgs& args,
                                   const std::string& name);

/// The outputs a command line names, checked before the command works: none
/// is an input, none is a device or a folder, no two name the same file
/// (empty paths, options not given, are skipped). @throws InputError naming
/// the options.
void CheckOutputs(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs);

class OutputFiles {
 public:
  /// `inputs`: what the command read; no output may replace one of them.
  explicit OutputFiles(std::vector<NamedFile> inputs = {});
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  /// Removes the temporary files (and folders) of an uncommitted set.
  ~OutputFiles();

  /// Adds `text` for `path`, checking the target now. `flag` names the
  /// option the path came from (for the error). @throws InputError.
  void Add(const std::string& path, std::string text, const std::string& flag);
  /// The folder `dir` (and its missing parents) is made at the commit,
  /// before the files, and taken away again when the commit fails or a
  /// signal ends it. @throws InputError naming `flag` when `dir` exists and
  /// is not a folder.
  void AddFolder(const std::string& dir, const std::string& flag);
  /// Writes every file, then renames each over its target. @throws
  /// InputError naming the file's flag; nothing is left then.
  void Commit();

 private:
  struct File {
    std::string target;  // the resolved target (a link followed)
    std::string shown;   // the path as the user gave it
    std::string temp;
    std::string text;
    std::string flag;
    std::string key;  // what identifies the file (SameFileKey)
    bool existed = false;
  };
  void Discard();
  std::vector<NamedFile> inputs_;
  std::vector<std::string> input_keys_;  // SameFileKey of each input (empty: none)
  std::vector<File> files_;
  std::map<std::string, size_t> by_key_;  // SameFileKey -> index in files_
  std::string folder_, folder_flag_;
  std::vector<std::string> made_folders_;   // by this commit, deepest first
  std::unique_ptr<PendingCommit> pending_;  // during Commit
  bool committed_ = false;
};

}  // namespace cairn::cli

#pragma once
// The files a command writes (--timeline, --dot, --emit-plans, convert's
// output), all or none.
//
// Each file is first written whole to a temporary file beside its target
// (the same folder, so that the rename is atomic), and only when every one
// is complete are they renamed over their targets: a reader never sees half a
// file, and a failed run (a full disk, a folder it may not write) leaves the
// targets as they were. Targets are checked before anything is written:
//  - an existing target that is not a regular file (a device such as
//    /dev/full, a folder, a FIFO) is refused: renaming over it would replace
//    a system file with a regular one;
//  - a symbolic link is followed deliberately: the file it points to is
//    replaced and the link is kept.
// A run killed by SIGINT, SIGTERM or SIGHUP removes its temporary files (a
// handler unlinks them, then the signal ends the process as before); only
// SIGKILL can leave one, named `.NAME.cairn-PID.tmp`, never the target.

#include <string>
#include <vector>

namespace cairn::cli {

class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  /// Removes the temporary files of an uncommitted set.
  ~OutputFiles();

  /// Adds `text` for `path`, checking the target now. `flag` names the
  /// option the path came from (for the error). @throws InputError.
  void Add(const std::string& path, std::string text, const std::string& flag);
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
    bool existed = false;
  };
  void Discard();
  std::vector<File> files_;
  bool committed_ = false;
};

}  // namespace cairn::cli

#pragma once
/// @file
/// Opening the files a user names (scenes, plans, COMPAS files, sidecars, ASAP
/// folders and their meshes, STEP files, batch jobs and results): every
/// reader of a user-given path goes through CheckInputFile or ReadInputFile,
/// which refuse what is not a regular file (a folder, a FIFO, a device such
/// as /dev/zero, a socket) without blocking on it, turn every failure of the
/// file system (no such file, a loop of symbolic links, a name too long, no
/// permission) into an InputError naming the file, and read at most a
/// maximum input size (docs/cli.md, "Reading the model").

#include <cstdint>
#include <optional>
#include <string>

namespace cairn {

/// bytes: the largest input file read unless the caller raises the limit
/// (`--max-input-size`): 1 GiB. The largest inputs Cairn is used with (STEP
/// assemblies, meshes of thousands of parts) are tens of megabytes; the
/// limit only stops what is not a model (a device, a runaway file) from
/// exhausting memory.
inline constexpr std::uint64_t kDefaultMaxInputSize = std::uint64_t{1} << 30;

/// Checks, without reading it, that `path` (symbolic links followed) is a
/// regular file of at most `max_size` bytes; returns its size in bytes. A FIFO
/// is opened without waiting for a writer. For readers that hand the path to
/// a library (Assimp, OpenCASCADE). `what` names the file in the message
/// ("file", "mesh file", "STEP file").
/// @throws InputError(path, "", why): "no such file", "is a directory, not a
/// file", "is a FIFO (named pipe), not a regular file", "a loop of symbolic
/// links", "the file name is too long", "permission denied", "is N bytes,
/// more than the maximum input size".
std::uint64_t CheckInputFile(const std::string& path, std::uint64_t max_size = kDefaultMaxInputSize,
                             const std::string& what = "file");

/// The whole content of the regular file `path`, checked as CheckInputFile
/// checks it and read through the same open file, at most `max_size` bytes
/// (a file that grows past the limit while read is refused too).
/// @throws InputError(path, "", why) as CheckInputFile, or a read error.
std::string ReadInputFile(const std::string& path, std::uint64_t max_size = kDefaultMaxInputSize,
                          const std::string& what = "file");

/// Whether `path` (symbolic links followed) is a folder; false when it is not
/// or cannot be examined (reading it then says why). Never throws.
bool IsDirectory(const std::string& path) noexcept;

/// A size in bytes as the `--max-input-size` option takes it: a positive whole
/// number with an optional suffix K, M or G (binary: 1K = 1024 bytes; KiB,
/// MiB, GiB and lower case accepted); none when the text is not one or
/// overflows 64 bits.
std::optional<std::uint64_t> ParseByteSize(const std::string& text);

/// A size for messages: "1073741824 bytes (1 GiB)", "512 bytes".
std::string DescribeByteSize(std::uint64_t bytes);

}  // namespace cairn

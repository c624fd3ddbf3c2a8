#pragma once
// Files a user names, read safely: only a regular file is read (a FIFO would block the run forever, a device
// never end), and no more than a stated size, so every loader refuses them the same way before it allocates.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace s3d {

// Largest text document (profile, display, views, manifest, scene description) any reader accepts.
inline constexpr std::uint64_t kMaxDocumentBytes = std::uint64_t(64) << 20;

// An input file that cannot be read; the message names the file as "<what> '<file>': <reason>".
struct InputFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Why `path` cannot be read as a file, in the user's terms ("does not exist", "is a folder, not a file",
// "is a FIFO (named pipe), not a regular file", ...), or "" when it is a regular file (after links).
std::string inputFileProblem(const std::filesystem::path& path);

// The whole file. Throws InputFileError "<what> '<file>': <reason>" when it is not a regular file, cannot be
// opened or read, or holds more than `maxBytes`. Opened without blocking and checked again once open, so a
// FIFO swapped in after the check is refused too.
std::string readInputFile(const std::filesystem::path& file, const std::string& what,
                          std::uint64_t maxBytes = kMaxDocumentBytes);

}  // namespace s3d

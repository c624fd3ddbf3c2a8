#include "s3d/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace s3d {
namespace {

std::string kindProblem(mode_t mode) {
  if (S_ISREG(mode)) return "";
  if (S_ISDIR(mode)) return "is a folder, not a file";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe), not a regular file";
  if (S_ISSOCK(mode)) return "is a socket, not a regular file";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "is a device, not a regular file";
  return "is not a regular file";
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& what, const std::string& reason) {
  throw InputFileError(what + " '" + file.string() + "': " + reason);
}

// Closes the descriptor on every path out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string inputFileProblem(const std::filesystem::path& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0)
    return errno == ENOENT || errno == ENOTDIR ? "does not exist" : std::strerror(errno);
  return kindProblem(status.st_mode);
}

std::string readInputFile(const std::filesystem::path& file, const std::string& what, std::uint64_t maxBytes) {
  if (const std::string problem = inputFileProblem(file); !problem.empty()) fail(file, what, problem);
  const Descriptor descriptor{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (descriptor.fd < 0) fail(file, what, std::strerror(errno));
  struct stat status {};
  if (::fstat(descriptor.fd, &status) != 0) fail(file, what, std::strerror(errno));
  if (const std::string problem = kindProblem(status.st_mode); !problem.empty()) fail(file, what, problem);
  if (std::uint64_t(status.st_size) > maxBytes)
    fail(file, what, "holds " + std::to_string(status.st_size) + " bytes, more than the " +
                         std::to_string(maxBytes) + " this kind of file may have");
  std::string bytes(std::size_t(status.st_size), '\0');
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ::ssize_t count = ::read(descriptor.fd, bytes.data() + done, bytes.size() - done);
    if (count < 0 && errno == EINTR) continue;
    if (count < 0) fail(file, what, std::string("read failed: ") + std::strerror(errno));
    if (count == 0) break;  // shrank while being read: keep what is there
    done += std::size_t(count);
  }
  bytes.resize(done);
  return bytes;
}

}  // namespace s3d

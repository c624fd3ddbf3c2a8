#pragma once
// Runs a piece of a test in a child process with a time and memory bound, so a hang or a runaway allocation
// fails the test (the child is killed) instead of stalling or swapping the whole suite. Only for code that
// needs no Vulkan device: the child is a fork of the test process.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <exception>
#include <string>
#include <thread>

namespace s3d::test {

#if defined(__SANITIZE_ADDRESS__)
inline constexpr bool kAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
inline constexpr bool kAddressSanitizer = true;
#else
inline constexpr bool kAddressSanitizer = false;
#endif
#else
inline constexpr bool kAddressSanitizer = false;
#endif

struct ChildOutcome {
  bool finished = false;  // false: killed at the time bound
  std::string message;    // what the child's `run` returned (truncated to 4 KiB)
};

// Runs `run` (returns a message, e.g. an error's text) in a child limited to `memoryBytes` of address space;
// waits at most `seconds`. An exception escaping `run` becomes "exception: <what>".
template <typename Run>
ChildOutcome runBounded(Run&& run, double seconds, std::uint64_t memoryBytes) {
  int pipeFds[2];
  if (::pipe(pipeFds) != 0) return {false, "pipe failed"};
  const pid_t child = ::fork();
  if (child == 0) {
    ::close(pipeFds[0]);
    if (!kAddressSanitizer) {  // ASan's shadow alone passes any such bound; its allocator has its own limits
      const rlimit limit{memoryBytes, memoryBytes};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    std::string message;
    try {
      message = run();
    } catch (const std::exception& error) {
      message = std::string("exception: ") + error.what();
    }
    message.resize(std::min<std::size_t>(message.size(), 4096));
    [[maybe_unused]] const auto written = ::write(pipeFds[1], message.data(), message.size());
    ::_exit(0);
  }
  ::close(pipeFds[1]);
  ChildOutcome outcome;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      ::close(pipeFds[0]);
      return outcome;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  outcome.finished = WIFEXITED(status) && WEXITSTATUS(status) == 0;
  char buffer[4096];
  for (::ssize_t count; (count = ::read(pipeFds[0], buffer, sizeof buffer)) > 0;) outcome.message.append(buffer, std::size_t(count));
  ::close(pipeFds[0]);
  if (!outcome.finished) outcome.message = "child died (status " + std::to_string(status) + ")";
  return outcome;
}

}  // namespace s3d::test

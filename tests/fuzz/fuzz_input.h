#pragma once
// Shared by the libFuzzer targets: each hands the fuzzer's bytes to a loader through a real file (the
// loaders' public API takes paths) and accepts only the project's clear errors as a failure mode.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <typeinfo>

namespace s3d::fuzz {

// Writes the input to one file per process (so parallel fuzzers never share it), named with the
// extension the loader dispatches on, and returns its path.
inline std::filesystem::path writeInputFile(const std::uint8_t* data, std::size_t size, const std::string& extension) {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("s3d_fuzz_" + std::to_string(::getpid()) + extension);
  std::ofstream stream(file, std::ios::binary | std::ios::trunc);
  stream.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  stream.close();
  if (!stream) {
    std::fprintf(stderr, "fuzz: cannot write the input file %s\n", file.c_str());
    std::abort();
  }
  return file;
}

// Runs the loader: success and the clear errors the project promises for bad input (std::invalid_argument,
// std::runtime_error, each with a message) are fine; anything else (another exception type such as
// std::bad_alloc or a library's own, an empty message) is a bug and aborts so libFuzzer keeps the input.
template <typename Load>
void loadExpectingOnlyClearErrors(Load&& load) {
  try {
    load();
  } catch (const std::invalid_argument& error) {
    if (*error.what() == '\0') std::abort();
  } catch (const std::runtime_error& error) {
    if (*error.what() == '\0') std::abort();
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fuzz: unclear error %s: %s\n", typeid(error).name(), error.what());
    std::abort();
  }
}

}  // namespace s3d::fuzz

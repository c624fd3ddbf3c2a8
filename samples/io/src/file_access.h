#pragma once
// Internal to s3d_io: image_io.cpp's whole-file reader and atomic writer, for the other format files.
#include <filesystem>
#include <string>
#include <string_view>

#include <stdexcept>

namespace s3d::io::detail {

// The readers' own failures: they already name the file, so the wrappers around a library's errors let
// them pass unchanged.
struct FileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
// Throws FileError "<operation>: cannot read '<file>': <reason>".
[[noreturn]] void failRead(const char* operation, const std::filesystem::path& file, const std::string& reason);

// Throws std::runtime_error "<operation>: cannot read '<file>': <reason>" (missing, not a regular file, I/O).
std::string readWholeFile(const char* operation, const std::filesystem::path& file);
// A PNG's signature and chunk lengths, checked before stb_image sees the bytes: stb grows its IDAT buffer to
// a chunk's declared length before reading it, so a 100-byte file declaring a 2 GB chunk made it allocate
// 2 GB (found by fuzz_png). Throws std::runtime_error "<operation>: cannot read '<file>': ...".
void requirePngStructure(const char* operation, const std::filesystem::path& file, const std::string& bytes);
// Temporary file in the same folder, then rename; the parent folder is created if missing.
void writeWholeFileAtomically(const char* operation, const std::filesystem::path& file, std::string_view bytes);

}  // namespace s3d::io::detail

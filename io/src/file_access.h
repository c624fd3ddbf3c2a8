#pragma once
// Internal to s3d_io: image_io.cpp's whole-file reader and atomic writer, for the other format files.
#include <cstdint>
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
// Throws FileError "cannot read <kind> file '<file>': <reason>"; kind is the format as users call it ("PNG",
// "EXR", "PFM"; "" for just "file"), never a function's name.
[[noreturn]] void failRead(const char* kind, const std::filesystem::path& file, const std::string& reason);

// Throws FileError "cannot read <kind> file '<file>': <reason>" (missing, a folder, not a regular file, I/O).
std::string readWholeFile(const char* kind, const std::filesystem::path& file);
// A PNG's signature and chunk lengths, checked before stb_image sees the bytes: stb grows its IDAT buffer to
// a chunk's declared length before reading it, so a 100-byte file declaring a 2 GB chunk made it allocate
// 2 GB (found by fuzz_png). Throws FileError "cannot read <kind> file '<file>': ...".
void requirePngStructure(const char* kind, const std::filesystem::path& file, const std::string& bytes);
// Throws FileError unless a header's claimed size is within s3d/image_limits.h (every reader's limit), checked
// before any pixel memory is allocated.
void requireReadableSize(const char* kind, const std::filesystem::path& file, std::int64_t width, std::int64_t height);

// A PNG's header as stb_image reads it, after requirePngStructure and requireReadableSize: a decoder asked for
// these sizes cannot be made to allocate more than the readers' limit.
struct PngHeader {
  int width = 0, height = 0, channels = 0;
  bool sixteenBit = false;
};
PngHeader readPngHeader(const char* kind, const std::filesystem::path& file, const std::string& bytes);
// Throws FileError "cannot read <kind> file '<file>': corrupt PNG: <stb_image's reason>".
[[noreturn]] void failPngDecode(const char* kind, const std::filesystem::path& file);

// Temporary file in the same folder, then rename; the parent folder is created if missing.
void writeWholeFileAtomically(const char* kind, const std::filesystem::path& file, std::string_view bytes);

}  // namespace s3d::io::detail

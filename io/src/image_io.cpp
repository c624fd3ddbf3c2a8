#include "s3d/io/image_io.h"

#include "exr_memory_stream.h"
#include "file_access.h"
#include "s3d/io/output_transaction.h"
#include "s3d/png_chunks.h"

// Third-party headers are silenced here because pkg-config exposes them with -I, not -isystem
// (Imath's half.h trips -Wconversion); our own code below keeps the full warning set.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>
#include <half.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>  // implementation lives in Debian's libstb.so: no STB_*_IMPLEMENTATION here
#pragma GCC diagnostic pop

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <random>
#include <utility>
#include <climits>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace s3d::io {
namespace fs = std::filesystem;

namespace {

using detail::FileError;

// Built by appending: `"'" + std::string` trips GCC 12's -Wrestrict false positive at -O3.
std::string quoted(const fs::path& file) {
  std::string text(1, '\'');
  text += file.string();
  text += '\'';
  return text;
}

// "<kind> file" ("PNG file", "EXR file") or just "file": what the user calls it, never a function's name.
std::string fileKind(const char* kind) {
  std::string text(kind);
  if (!text.empty()) text += ' ';
  text += "file ";
  return text;
}

[[noreturn]] void failWrite(const char* kind, const fs::path& file, const std::string& reason) {
  throw FileError("cannot write " + fileKind(kind) + quoted(file) + ": " + reason);
}

}  // namespace

namespace detail {
[[noreturn]] void failRead(const char* kind, const fs::path& file, const std::string& reason) {
  throw FileError("cannot read " + fileKind(kind) + quoted(file) + ": " + reason);
}
}  // namespace detail

namespace {
using detail::failRead;
using detail::requireReadableSize;

// Opens a fresh temporary file beside the target under an unpredictable name, refusing any existing file or
// link there (O_EXCL | O_NOFOLLOW), so a link planted in a shared folder is never written through.
int createTemporaryBeside(const fs::path& file, fs::path& temporary) {
  std::random_device entropy;
  for (int attempt = 0; attempt < 16; ++attempt) {
    char suffix[24];
    std::snprintf(suffix, sizeof suffix, ".%08x.tmp", static_cast<unsigned>(entropy()));
    std::string name(1, '.');  // appended: `"." + std::string` trips GCC 12's -Wrestrict false positive
    name += file.filename().string();
    name += suffix;
    temporary = file.parent_path() / name;
    const int descriptor = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (descriptor >= 0 || errno != EEXIST) return descriptor;
  }
  errno = EEXIST;
  return -1;
}

// Write to a fresh temporary file in the same folder, then rename over the target: rename within one file
// system is atomic, so readers see either the old file or the complete new one, never a partial one; a link
// at the target itself is replaced, not followed.
void writeFileAtomically(const char* kind, const fs::path& file, std::string_view bytes) {
  if (file.empty() || !file.has_filename()) failWrite(kind, file, "path names no file");
  std::error_code error;
  const fs::path target = OutputTransaction::stagedTarget(file);  // messages still name the user's file
  const fs::path folder = target.parent_path();
  if (!folder.empty()) {
    fs::create_directories(folder, error);
    if (error) failWrite(kind, file, "cannot create folder " + quoted(folder) + ": " + error.message());
  }

  fs::path temporary;
  int descriptor = createTemporaryBeside(target, temporary);
  if (descriptor < 0) {
    const int openErrno = errno;  // capture before anything else can overwrite it
    failWrite(kind, file, std::string("cannot create a temporary file beside it: ") + std::strerror(openErrno));
  }
  try {
    std::size_t written = 0;
    while (written < bytes.size()) {
      const ::ssize_t count = ::write(descriptor, bytes.data() + written, bytes.size() - written);
      if (count < 0 && errno == EINTR) continue;
      if (count <= 0) {
        const int writeErrno = errno;
        failWrite(kind, file, std::strerror(count == 0 ? EIO : writeErrno));  // e.g. "File too large"
      }
      written += static_cast<std::size_t>(count);
    }
    if (::close(std::exchange(descriptor, -1)) != 0) {
      const int closeErrno = errno;
      failWrite(kind, file, std::strerror(closeErrno));  // e.g. "No space left on device", reported late
    }
    fs::rename(temporary, target, error);
    if (error) failWrite(kind, file, "cannot move temporary file into place: " + error.message());
  } catch (...) {
    if (descriptor >= 0) ::close(descriptor);
    fs::remove(temporary, error);  // ours: created exclusively above; best effort, the original error matters
    throw;
  }
}

std::string readFileBytes(const char* kind, const fs::path& file) {
  std::error_code error;
  const fs::file_status status = fs::status(file, error);
  if (!fs::exists(status)) failRead(kind, file, "it does not exist");
  if (fs::is_directory(status)) failRead(kind, file, "it is a folder, not a file");
  if (!fs::is_regular_file(status)) failRead(kind, file, "not a regular file");
  std::ifstream stream(file, std::ios::binary);
  if (!stream) {
    const int openErrno = errno;
    failRead(kind, file, std::strerror(openErrno));
  }
  std::string bytes((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
  if (stream.bad()) failRead(kind, file, "I/O error while reading");
  return bytes;
}

// A caller's mistake, not the file system's: std::invalid_argument, still naming the file.
[[noreturn]] void failImage(const char* kind, const fs::path& file, const std::string& reason) {
  throw std::invalid_argument("cannot write " + fileKind(kind) + quoted(file) + ": " + reason);
}

template <typename Image>
void requireWritableImage(const char* kind, const fs::path& file, const Image& image, const char* what) {
  if (image.width == 0 || image.height == 0) failImage(kind, file, std::string("the ") + what + " image is empty");
  if (image.pixels.size() != image.pixelCount() * Image::channels)
    failImage(kind, file, std::string("the ") + what + " pixel buffer holds " + std::to_string(image.pixels.size()) +
                              " values, expected " + std::to_string(image.pixelCount() * Image::channels));
  // Both libraries take int sizes and int row strides.
  if (std::uint64_t(image.width) * Image::channels * sizeof(typename decltype(image.pixels)::value_type) > INT_MAX ||
      image.height > INT_MAX)
    failImage(kind, file, std::string("the ") + what + " image is too large for the file format");
}

void appendToByteVector(void* context, void* data, int size) {
  auto* bytes = static_cast<std::vector<char>*>(context);
  const char* begin = static_cast<const char*>(data);
  bytes->insert(bytes->end(), begin, begin + size);
}

constexpr int kRgbaChannels = 4;

}  // namespace

void writePng(const fs::path& file, const ImageRGBA8& image) {
  requireWritableImage("PNG", file, image, "PNG");
  // Encode into memory first so the file itself goes through the atomic writer.
  std::vector<char> encoded;
  const int rowBytes = static_cast<int>(image.width) * kRgbaChannels;
  if (stbi_write_png_to_func(appendToByteVector, &encoded, static_cast<int>(image.width),
                             static_cast<int>(image.height), kRgbaChannels, image.pixels.data(), rowBytes) == 0)
    failWrite("PNG", file, "PNG encoding failed");
  writeFileAtomically("PNG", file, std::string_view(encoded.data(), encoded.size()));
}

ImageRGBA8 readPng(const fs::path& file) {
  const std::string bytes = readFileBytes("PNG", file);
  (void)detail::readPngHeader("PNG", file, bytes);  // refused before stb sizes its buffers from the header
  int width = 0;
  int height = 0;
  int channelsInFile = 0;
  std::unique_ptr<stbi_uc, void (*)(void*)> decoded(
      stbi_load_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &width,
                            &height, &channelsInFile, kRgbaChannels),
      stbi_image_free);
  if (!decoded) detail::failPngDecode("PNG", file);
  ImageRGBA8 image(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
  std::memcpy(image.pixels.data(), decoded.get(), image.pixels.size());
  return image;
}

void writeExr(const fs::path& file, const ImageRGBA32F& color, const DepthImage* linearDepth) {
  requireWritableImage("EXR", file, color, "color");
  if (linearDepth) {
    if (color.width != linearDepth->width || color.height != linearDepth->height)
      failImage("EXR", file, "the color and the linear depth differ in size");
    requireWritableImage("EXR", file, *linearDepth, "linear depth");
  }
  const int width = static_cast<int>(color.width);
  const int height = static_cast<int>(color.height);

  std::string encoded;
  try {
    Imf::Header header(width, height);
    Imf::FrameBuffer frameBuffer;
    // OpenEXR converts pixel types only when reading, so colour is converted to half here
    // (round to nearest; magnitudes beyond 65504 become infinite).
    std::vector<Imath::half> colorHalf(color.pixels.begin(), color.pixels.end());
    char* colorBase = reinterpret_cast<char*>(colorHalf.data());
    const std::size_t colorXStride = sizeof(Imath::half) * kRgbaChannels;
    const std::size_t colorYStride = colorXStride * color.width;
    const char* const names[kRgbaChannels] = {"R", "G", "B", "A"};
    for (int c = 0; c < kRgbaChannels; ++c) {
      header.channels().insert(names[c], Imf::Channel(Imf::HALF));
      frameBuffer.insert(names[c], Imf::Slice(Imf::HALF, colorBase + sizeof(Imath::half) * std::size_t(c),
                                              colorXStride, colorYStride));
    }
    if (linearDepth) {
      // FLOAT, not HALF: depth needs the precision and half tops out at 65504. The slice is only read.
      header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
      char* depthBase = reinterpret_cast<char*>(const_cast<float*>(linearDepth->pixels.data()));
      frameBuffer.insert("Z", Imf::Slice(Imf::FLOAT, depthBase, sizeof(float), sizeof(float) * linearDepth->width));
    }
    Imf::StdOSStream stream;
    {
      Imf::OutputFile output(stream, header);
      output.setFrameBuffer(frameBuffer);
      output.writePixels(height);
    }  // the destructor writes the line-offset table, so the bytes are complete only after this scope
    encoded = stream.str();
  } catch (const std::exception& error) {
    failWrite("EXR", file, std::string("EXR encoding failed: ") + error.what());
  }
  writeFileAtomically("EXR", file, encoded);
}

ExrFrame readExr(const fs::path& file) {
  const std::string bytes = readFileBytes("EXR", file);
  ExrFrame frame;
  try {
    detail::ExrMemoryStream stream(file, bytes);
    Imf::InputFile input(stream);
    const Imf::Header& header = input.header();
    const Imath::Box2i dataWindow = header.dataWindow();
    const std::int64_t width = std::int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
    const std::int64_t height = std::int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
    if (width <= 0 || height <= 0 || width > INT_MAX / (kRgbaChannels * int(sizeof(float))) || height > INT_MAX)
      failRead("EXR", file, "invalid data window");
    requireReadableSize("EXR", file, width, height);

    const Imf::ChannelList& channels = header.channels();
    for (const char* required : {"R", "G", "B"})
      if (!channels.findChannel(required))
        failRead("EXR", file, std::string("missing colour channel '") + required + "'");
    for (auto channel = channels.begin(); channel != channels.end(); ++channel)
      if (channel.channel().xSampling != 1 || channel.channel().ySampling != 1)
        failRead("EXR", file, std::string("subsampled channel '") + channel.name() + "' is not supported");

    frame.color = ImageRGBA32F(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
    Imf::FrameBuffer frameBuffer;
    const std::size_t colorXStride = sizeof(float) * kRgbaChannels;
    const std::size_t colorYStride = colorXStride * std::size_t(width);
    const char* const names[kRgbaChannels] = {"R", "G", "B", "A"};
    for (int c = 0; c < kRgbaChannels; ++c) {
      const double fill = (c == 3) ? 1.0 : 0.0;  // no alpha channel means fully opaque
      frameBuffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, frame.color.pixels.data() + c, dataWindow,
                                                    colorXStride, colorYStride, 1, 1, fill));
    }
    frame.hasDepth = channels.findChannel("Z") != nullptr;
    if (frame.hasDepth) {
      frame.linearDepth = DepthImage(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
      frameBuffer.insert("Z", Imf::Slice::Make(Imf::FLOAT, frame.linearDepth.pixels.data(), dataWindow,
                                               sizeof(float), sizeof(float) * std::size_t(width)));
    }
    input.setFrameBuffer(frameBuffer);
    input.readPixels(dataWindow.min.y, dataWindow.max.y);
  } catch (const FileError&) {
    throw;
  } catch (const std::exception& error) {
    failRead("EXR", file, "corrupt EXR: " + detail::exrReason(file, error.what()));
  }
  return frame;
}

ImageSize readImageSize(const fs::path& file) {
  std::string extension = file.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (extension == ".exr") {
    try {
      Imf::InputFile input(file.c_str());  // reads the header only
      const Imath::Box2i window = input.header().dataWindow();
      const std::int64_t width = std::int64_t(window.max.x) - window.min.x + 1;
      const std::int64_t height = std::int64_t(window.max.y) - window.min.y + 1;
      if (width <= 0 || height <= 0) failRead("EXR", file, "invalid data window");
      requireReadableSize("EXR", file, width, height);
      return {std::uint32_t(width), std::uint32_t(height)};
    } catch (const FileError&) {
      throw;
    } catch (const std::exception& error) {
      (void)readFileBytes("EXR", file);  // a missing file or a folder is named as such
      failRead("EXR", file, "corrupt EXR: " + detail::exrReason(file, error.what()));
    }
  }
  const char* kind = extension == ".pfm" ? "PFM" : "PNG";
  std::error_code error;
  if (!fs::is_regular_file(file, error)) (void)readFileBytes(kind, file);  // names what it is instead
  std::ifstream stream(file, std::ios::binary);
  std::string head(256, '\0');
  stream.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(stream.gcount()));
  if (extension == ".pfm") {
    std::istringstream tokens(head);
    std::string magic;
    std::int64_t width = 0, height = 0;
    if (!(tokens >> magic >> width >> height) || (magic != "PF" && magic != "Pf") || width <= 0 || height <= 0)
      failRead("PFM", file, "not a PFM header (expected 'PF' or 'Pf', width and height)");
    requireReadableSize("PFM", file, width, height);
    return {std::uint32_t(width), std::uint32_t(height)};
  }
  // PNG: the signature, then IHDR's width and height (big-endian) at bytes 16..23.
  if (head.size() < 24 || !hasPngSignature(head) || head.compare(12, 4, "IHDR") != 0)
    failRead("PNG", file, "not a PNG file (bad signature or header)");
  auto bigEndian = [&](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t i = 0; i < 4; ++i) value = (value << 8) | static_cast<unsigned char>(head[at + i]);
    return value;
  };
  const std::uint32_t width = bigEndian(16), height = bigEndian(20);
  if (width == 0 || height == 0) failRead("PNG", file, "corrupt PNG: zero width or height");
  requireReadableSize("PNG", file, width, height);
  return {width, height};
}

void writeTextFile(const fs::path& file, std::string_view text) { writeFileAtomically("", file, text); }

namespace detail {
std::string readWholeFile(const char* kind, const fs::path& file) { return readFileBytes(kind, file); }

void requireReadableSize(const char* kind, const fs::path& file, std::int64_t width, std::int64_t height) {
  if (width > kMaxImageSide || height > kMaxImageSide || std::uint64_t(width) * std::uint64_t(height) > kMaxImagePixels)
    failRead(kind, file, "image is " + std::to_string(width) + "x" + std::to_string(height) +
                                  ", beyond the readers' limit of " + std::to_string(kMaxImageSide) + " pixels a side and " +
                                  std::to_string(kMaxImagePixels) + " pixels in all");
}

[[noreturn]] void failPngDecode(const char* kind, const fs::path& file) {
  const char* reason = stbi_failure_reason();
  failRead(kind, file, std::string("corrupt PNG: ") + (reason ? reason : "unknown decoder error"));
}

PngHeader readPngHeader(const char* kind, const fs::path& file, const std::string& bytes) {
  requirePngStructure(kind, file, bytes);
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  PngHeader header;
  if (!stbi_info_from_memory(data, static_cast<int>(bytes.size()), &header.width, &header.height, &header.channels))
    failPngDecode(kind, file);
  if (header.width <= 0 || header.height <= 0) failRead(kind, file, "corrupt PNG: zero width or height");
  requireReadableSize(kind, file, header.width, header.height);
  header.sixteenBit = stbi_is_16_bit_from_memory(data, static_cast<int>(bytes.size())) != 0;
  return header;
}

void requirePngStructure(const char* kind, const fs::path& file, const std::string& bytes) {
  if (bytes.size() > INT_MAX) failRead(kind, file, "file is too large");
  // stb_image accepts several formats; the signature check keeps the readers honest about "PNG".
  if (!hasPngSignature(bytes)) failRead(kind, file, "not a PNG file (bad signature)");
  if (const auto overrun = pngChunkOverrun(bytes))
    failRead(kind, file, "corrupt PNG: " + overrun->describe("file"));
}

void writeWholeFileAtomically(const char* kind, const fs::path& file, std::string_view bytes) {
  writeFileAtomically(kind, file, bytes);
}
}  // namespace detail

}  // namespace s3d::io

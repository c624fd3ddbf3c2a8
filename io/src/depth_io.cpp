#include "s3d/io/depth_io.h"

// Third-party headers silenced as in image_io.cpp (pkg-config exposes them with -I, not -isystem).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfStdIO.h>
#include <stb/stb_image.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string_view>

#include "exr_memory_stream.h"
#include "s3d/image_limits.h"
#include "s3d/png_chunks.h"
#include "file_access.h"

namespace s3d::io {
namespace fs = std::filesystem;

namespace {

using detail::failRead;
using detail::FileError;
using detail::requireReadableSize;

std::uint32_t byteSwapped(std::uint32_t value) {
  return (value >> 24) | ((value >> 8) & 0xff00u) | ((value << 8) & 0xff0000u) | (value << 24);
}

// --- PNG writing: CRC-32 of chunks and Adler-32 of the zlib stream (RFC 2083, RFC 1950) ---

std::uint32_t crc32(std::string_view bytes, std::uint32_t crc = 0) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> entries{};
    for (std::uint32_t n = 0; n < 256; ++n) {
      std::uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xedb88320u ^ (c >> 1) : c >> 1;
      entries[n] = c;
    }
    return entries;
  }();
  crc = ~crc;
  for (char byte : bytes) crc = table[(crc ^ std::uint8_t(byte)) & 0xffu] ^ (crc >> 8);
  return ~crc;
}

void appendBigEndian(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((value >> shift) & 0xffu));
}

void appendChunk(std::string& png, const char* type, std::string_view data) {
  appendBigEndian(png, std::uint32_t(data.size()));
  std::string typed(type, 4);
  typed += data;
  png += typed;
  appendBigEndian(png, crc32(typed));
}

}  // namespace

PfmImage readPfm(const fs::path& file) {
  const std::string bytes = detail::readWholeFile("PFM", file);
  // Header: three whitespace-separated tokens after the magic, then exactly one whitespace byte.
  std::size_t position = 0;
  auto nextToken = [&](const char* what) {
    while (position < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[position]))) ++position;
    const std::size_t begin = position;
    while (position < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[position]))) ++position;
    if (begin == position || position >= bytes.size()) failRead("PFM", file, std::string("truncated header: no ") + what);
    return std::string_view(bytes).substr(begin, position - begin);
  };
  const std::string_view magic = nextToken("PF/Pf magic");
  PfmImage image;
  if (magic == "PF")
    image.channels = 3;
  else if (magic == "Pf")
    image.channels = 1;
  else
    failRead("PFM", file, "not a PFM file (expected 'PF' or 'Pf', found '" + std::string(magic.substr(0, 8)) + "')");
  auto parseSide = [&](const char* what) {
    const std::string_view token = nextToken(what);
    std::uint64_t value = 0;
    auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (ec != std::errc() || ptr != token.data() + token.size() || value == 0 || value > kMaxImageSide)
      failRead("PFM", file, std::string("bad ") + what + " '" + std::string(token) + "' (expected 1 to " +
                                    std::to_string(kMaxImageSide) + ")");
    return std::uint32_t(value);
  };
  image.width = parseSide("width");
  image.height = parseSide("height");
  requireReadableSize("PFM", file, image.width, image.height);
  const std::string scaleToken(nextToken("scale"));
  char* scaleEnd = nullptr;
  const double scale = std::strtod(scaleToken.c_str(), &scaleEnd);
  if (scaleEnd != scaleToken.c_str() + scaleToken.size() || !std::isfinite(scale) || scale == 0.0)
    failRead("PFM", file, "bad scale '" + scaleToken + "' (a non-zero number; its sign gives the byte order)");
  ++position;  // the single whitespace byte ending the header
  const bool fileIsLittleEndian = scale < 0.0;

  const std::size_t count = std::size_t(image.width) * image.height * std::size_t(image.channels);
  const std::size_t available = bytes.size() - position;
  if (available < count * sizeof(float))
    failRead("PFM", file, "truncated: " + std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                                  std::to_string(image.channels) + " floats need " + std::to_string(count * sizeof(float)) +
                                  " bytes of pixel data, the file has " + std::to_string(available));
  image.values.resize(count);
  const bool swap = fileIsLittleEndian != (std::endian::native == std::endian::little);
  const std::size_t rowValues = std::size_t(image.width) * std::size_t(image.channels);
  for (std::uint32_t fileRow = 0; fileRow < image.height; ++fileRow) {
    const std::uint32_t y = image.height - 1 - fileRow;  // the file's first row is the bottom one
    const char* source = bytes.data() + position + fileRow * rowValues * sizeof(float);
    float* target = image.values.data() + std::size_t(y) * rowValues;
    for (std::size_t i = 0; i < rowValues; ++i) {
      std::uint32_t word = 0;
      std::memcpy(&word, source + i * sizeof(float), sizeof(word));
      if (swap) word = byteSwapped(word);
      std::memcpy(target + i, &word, sizeof(word));
    }
  }
  return image;
}

void writePfm(const fs::path& file, const PfmImage& image, bool bigEndian) {
  if (image.channels != 1 && image.channels != 3)
    throw std::invalid_argument("PFM image with " + std::to_string(image.channels) + " channels (PFM has 1 or 3)");
  if (image.width == 0 || image.height == 0) throw std::invalid_argument("PFM image is empty");
  const std::size_t rowValues = std::size_t(image.width) * std::size_t(image.channels);
  if (image.values.size() != rowValues * image.height)
    throw std::invalid_argument("PFM image holds " + std::to_string(image.values.size()) + " values for a " +
                                std::to_string(image.width) + "x" + std::to_string(image.height) + "x" +
                                std::to_string(image.channels) + " image");
  std::string bytes = std::string(image.channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(image.width) + " " +
                      std::to_string(image.height) + "\n" + (bigEndian ? "1.0" : "-1.0") + "\n";
  const bool swap = bigEndian == (std::endian::native == std::endian::little);
  for (std::uint32_t fileRow = 0; fileRow < image.height; ++fileRow) {
    const float* source = image.values.data() + std::size_t(image.height - 1 - fileRow) * rowValues;
    for (std::size_t i = 0; i < rowValues; ++i) {
      std::uint32_t word = 0;
      std::memcpy(&word, source + i, sizeof(word));
      if (swap) word = byteSwapped(word);
      char raw[4];
      std::memcpy(raw, &word, sizeof(raw));
      bytes.append(raw, sizeof(raw));
    }
  }
  detail::writeWholeFileAtomically("PFM", file, bytes);
}

Gray16Image readPngGray16(const fs::path& file) {
  const std::string bytes = detail::readWholeFile("PNG", file);
  // The header first: a crafted one can claim a huge image in a tiny file, refused before the decoder sizes
  // its buffers from it.
  const detail::PngHeader header = detail::readPngHeader("PNG", file, bytes);
  if (!header.sixteenBit) failRead("PNG", file, "an 8-bit PNG: depth or disparity needs a 16-bit grey PNG");
  if (header.channels > 2)
    failRead("PNG", file, "a colour PNG: depth or disparity needs a 16-bit grey (single-channel) PNG");
  int width = 0, height = 0, channelsInFile = 0;
  std::unique_ptr<stbi_us, void (*)(void*)> decoded(
      stbi_load_16_from_memory(reinterpret_cast<const stbi_uc*>(bytes.data()), static_cast<int>(bytes.size()), &width,
                               &height, &channelsInFile, 1),
      stbi_image_free);
  if (!decoded) detail::failPngDecode("PNG", file);
  Gray16Image image(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
  std::memcpy(image.pixels.data(), decoded.get(), image.pixels.size() * sizeof(std::uint16_t));
  return image;
}

void writePngGray16(const fs::path& file, const Gray16Image& image) {
  if (image.width == 0 || image.height == 0 || image.pixels.size() != image.pixelCount())
    throw std::invalid_argument("16-bit PNG image is empty or its pixel buffer has the wrong size");
  if (image.width > kMaxImageSide || image.height > kMaxImageSide)  // what the readers accept back
    throw std::invalid_argument("16-bit PNG image is too large");
  // Raw scanlines: filter byte 0, then big-endian samples.
  std::string raw;
  raw.reserve(image.height * (1 + 2 * std::size_t(image.width)));
  for (std::uint32_t y = 0; y < image.height; ++y) {
    raw.push_back('\0');
    for (std::uint32_t x = 0; x < image.width; ++x) {
      const std::uint16_t value = *image.at(x, y);
      raw.push_back(char(value >> 8));
      raw.push_back(char(value & 0xffu));
    }
  }
  // zlib stream of stored deflate blocks (at most 65535 bytes each), then Adler-32.
  std::string zlib("\x78\x01", 2);
  for (std::size_t offset = 0; offset < raw.size() || offset == 0; offset += 65535) {
    const std::size_t length = std::min<std::size_t>(65535, raw.size() - offset);
    const bool last = offset + length >= raw.size();
    zlib.push_back(char(last ? 1 : 0));
    zlib.push_back(char(length & 0xffu));
    zlib.push_back(char(length >> 8));
    zlib.push_back(char(~length & 0xffu));
    zlib.push_back(char((~length >> 8) & 0xffu));
    zlib.append(raw, offset, length);
    if (last) break;
  }
  std::uint32_t a = 1, b = 0;
  for (char byte : raw) {
    a = (a + std::uint8_t(byte)) % 65521u;
    b = (b + a) % 65521u;
  }
  appendBigEndian(zlib, (b << 16) | a);

  std::string header;
  appendBigEndian(header, image.width);
  appendBigEndian(header, image.height);
  header += std::string("\x10\x00\x00\x00\x00", 5);  // bit depth 16, grey, deflate, adaptive filters, no interlace
  std::string png(kPngSignature);
  appendChunk(png, "IHDR", header);
  appendChunk(png, "IDAT", zlib);
  appendChunk(png, "IEND", {});
  detail::writeWholeFileAtomically("PNG", file, png);
}

DepthImage readExrChannel(const fs::path& file, const std::string& channel) {
  const std::string bytes = detail::readWholeFile("EXR", file);
  DepthImage image;
  try {
    detail::ExrMemoryStream stream(file, bytes);
    Imf::InputFile input(stream);
    const Imf::Header& header = input.header();
    const Imath::Box2i dataWindow = header.dataWindow();
    const std::int64_t width = std::int64_t(dataWindow.max.x) - dataWindow.min.x + 1;
    const std::int64_t height = std::int64_t(dataWindow.max.y) - dataWindow.min.y + 1;
    if (width <= 0 || height <= 0) failRead("EXR", file, "invalid data window");
    // A crafted header can claim a huge window in a tiny file: refused before it is allocated.
    requireReadableSize("EXR", file, width, height);
    const Imf::ChannelList& channels = header.channels();
    const Imf::Channel* found = channels.findChannel(channel);
    if (!found) {
      std::string names;
      for (auto entry = channels.begin(); entry != channels.end(); ++entry)
        names += (names.empty() ? "" : ", ") + std::string(entry.name());
      failRead("EXR", file, "no channel '" + channel + "' (channels: " + names + ")");
    }
    if (found->xSampling != 1 || found->ySampling != 1)
      failRead("EXR", file, "subsampled channel '" + channel + "' is not supported");
    image = DepthImage(static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height));
    Imf::FrameBuffer frameBuffer;
    frameBuffer.insert(channel, Imf::Slice::Make(Imf::FLOAT, image.pixels.data(), dataWindow, sizeof(float),
                                                 sizeof(float) * std::size_t(width)));
    input.setFrameBuffer(frameBuffer);
    input.readPixels(dataWindow.min.y, dataWindow.max.y);
  } catch (const FileError&) {
    throw;
  } catch (const std::exception& error) {
    failRead("EXR", file, "corrupt EXR: " + detail::exrReason(file, error.what()));
  }
  return image;
}

}  // namespace s3d::io

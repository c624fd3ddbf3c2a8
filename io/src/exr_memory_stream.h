#pragma once
// Internal to s3d_io: an OpenEXR input stream over a file's bytes already in memory, named by the file, so
// OpenEXR's own messages name the user's file (its StdISStream calls every stream "(string)").
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#include <ImfIO.h>
#pragma GCC diagnostic pop

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace s3d::io::detail {

class ExrMemoryStream final : public Imf::IStream {
 public:
  ExrMemoryStream(const std::filesystem::path& file, std::string_view bytes)
      : Imf::IStream(file.c_str()), bytes_(bytes) {}

  // OpenEXR's contract: throw when fewer than n bytes remain; return false once the last byte was read.
  bool read(char c[], int n) override {
    // seekg may have moved past the end (a corrupt offset table): the remaining count must not wrap around.
    if (n < 0 || position_ > bytes_.size() || std::uint64_t(n) > bytes_.size() - position_)
      throw std::runtime_error("early end of file: " + std::to_string(n) + " bytes wanted at offset " +
                               std::to_string(position_) + " of " + std::to_string(bytes_.size()));
    std::memcpy(c, bytes_.data() + position_, std::size_t(n));
    position_ += std::uint64_t(n);
    return position_ < bytes_.size();
  }
  std::uint64_t tellg() override { return position_; }
  void seekg(std::uint64_t position) override { position_ = position; }

 private:
  std::string_view bytes_;
  std::uint64_t position_ = 0;
};

// OpenEXR prefixes its reasons with `Cannot read image file "<name>". `; the caller names the file already.
inline std::string exrReason(const std::filesystem::path& file, const std::string& message) {
  const std::string prefix = "Cannot read image file \"" + file.string() + "\". ";
  return message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
}

}  // namespace s3d::io::detail

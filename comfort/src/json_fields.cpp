#include "json_fields.h"

#include "s3d/json_document.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <stdexcept>

namespace s3d::comfort::detail {

nlohmann::json readJsonFile(const std::filesystem::path& file, const char* what) {
  return s3d::readJsonDocument(file, what);
}

void writeTextAtomically(const std::filesystem::path& file, const std::string& text, const char* what) {
  const std::string name = std::string(what) + " '" + file.string() + "'";
  if (file.empty() || !file.has_filename()) throw std::runtime_error(name + ": the path names no file");
  // A fresh temporary beside the target under an unpredictable name, refusing any existing file or link there
  // (O_EXCL | O_NOFOLLOW): a link planted in a shared folder is never written through.
  std::random_device entropy;
  std::filesystem::path temporary;
  int descriptor = -1;
  for (int attempt = 0; attempt < 16 && descriptor < 0; ++attempt) {
    char suffix[24];
    std::snprintf(suffix, sizeof suffix, ".%08x.tmp", static_cast<unsigned>(entropy()));
    temporary = file;
    temporary += suffix;
    descriptor = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (descriptor < 0 && errno != EEXIST) break;
  }
  if (descriptor < 0)
    throw std::runtime_error(name + ": cannot create a temporary file beside it: " + std::strerror(errno));
  std::size_t written = 0;
  int writeErrno = 0;
  while (written < text.size()) {
    const ::ssize_t count = ::write(descriptor, text.data() + written, text.size() - written);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) {
      writeErrno = count == 0 ? EIO : errno;
      break;
    }
    written += std::size_t(count);
  }
  if (::close(descriptor) != 0 && writeErrno == 0) writeErrno = errno;  // e.g. "No space left on device", late
  std::error_code error;
  if (writeErrno != 0) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error("cannot write " + name + ": " + std::strerror(writeErrno));  // e.g. "File too large"
  }
  std::filesystem::rename(temporary, file, error);  // a link at the target itself is replaced, not followed
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw std::runtime_error(name + ": cannot move the file into place: " + error.message());
  }
}

double shortest(float value) {
  if (!std::isfinite(value)) return double(value);
  char text[32];
  const std::to_chars_result end = std::to_chars(text, text + sizeof(text) - 1, value);
  *end.ptr = '\0';
  return std::strtod(text, nullptr);
}

std::string describe(Range range) {
  std::ostringstream text;
  text << (range.lowOpen ? "(" : "[") << range.low << ", " << range.high << (range.highOpen ? ")" : "]");
  return text.str();
}

ObjectReader::ObjectReader(const nlohmann::json& object, std::string path) : object_(object), path_(std::move(path)) {
  if (!object_.is_object())
    throw std::invalid_argument((path_.empty() ? std::string("the document") : "'" + path_ + "'") +
                                " must be a JSON object (got " + object_.type_name() + ")");
}

std::string ObjectReader::pathOf(const char* key) const { return path_.empty() ? key : path_ + "." + key; }

const nlohmann::json* ObjectReader::find(const char* key) {
  known_.emplace_back(key);
  const auto it = object_.find(key);
  return it == object_.end() ? nullptr : &*it;
}

void ObjectReader::number(const char* key, float& value, Range range) {
  const nlohmann::json* entry = find(key);
  if (!entry) return;
  if (!entry->is_number())
    throw std::invalid_argument("'" + pathOf(key) + "' must be a number (got " + entry->type_name() + ")");
  const double number = entry->get<double>();
  const bool below = range.lowOpen ? !(number > range.low) : !(number >= range.low);
  const bool above = range.highOpen ? !(number < range.high) : !(number <= range.high);
  if (!std::isfinite(number) || below || above) {
    std::ostringstream message;
    message << "'" << pathOf(key) << "' = " << entry->dump() << " is outside " << describe(range);
    throw std::invalid_argument(message.str());
  }
  value = float(number);
}

void ObjectReader::integer(const char* key, int& value, int low, int high) {
  const nlohmann::json* entry = find(key);
  if (!entry) return;
  if (!entry->is_number_integer())
    throw std::invalid_argument("'" + pathOf(key) + "' must be an integer (got " + entry->dump() + ")");
  const long long number = entry->get<long long>();
  if (number < low || number > high)
    throw std::invalid_argument("'" + pathOf(key) + "' = " + std::to_string(number) + " is outside [" +
                                std::to_string(low) + ", " + std::to_string(high) + "]");
  value = int(number);
}

void ObjectReader::boolean(const char* key, bool& value) {
  const nlohmann::json* entry = find(key);
  if (!entry) return;
  if (!entry->is_boolean())
    throw std::invalid_argument("'" + pathOf(key) + "' must be true or false (got " + entry->dump() + ")");
  value = entry->get<bool>();
}

void ObjectReader::choice(const char* key, std::string& value, const std::vector<std::string>& choices) {
  const nlohmann::json* entry = find(key);
  if (!entry) return;
  std::string list;
  for (const std::string& name : choices) list += (list.empty() ? "" : ", ") + name;
  if (!entry->is_string() || std::find(choices.begin(), choices.end(), entry->get<std::string>()) == choices.end())
    throw std::invalid_argument("'" + pathOf(key) + "' = " + entry->dump() + " is not one of: " + list);
  value = entry->get<std::string>();
}

void ObjectReader::finish() const {
  for (const auto& [key, entry] : object_.items()) {
    (void)entry;
    if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
    std::string list;
    for (const std::string& name : known_) list += (list.empty() ? "" : ", ") + name;
    throw std::invalid_argument("unknown key '" + pathOf(key.c_str()) + "' (known keys" +
                                (path_.empty() ? std::string() : " of '" + path_ + "'") + ": " + list + ")");
  }
}

}  // namespace s3d::comfort::detail

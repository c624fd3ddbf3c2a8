#include "gltf_webp.h"

#include <webp/decode.h>

namespace s3d::renderer::gltf {

bool webpInfo(const unsigned char* bytes, int size, int& width, int& height) {
  return size > 0 && WebPGetInfo(bytes, std::size_t(size), &width, &height) != 0;
}

bool decodeWebp(tinygltf::Image& image, const unsigned char* bytes, int size) {
  int width = 0, height = 0;
  if (!webpInfo(bytes, size, width, height)) return false;
  const std::size_t stride = std::size_t(width) * 4;
  image.image.resize(stride * std::size_t(height));
  if (!WebPDecodeRGBAInto(bytes, std::size_t(size), image.image.data(), image.image.size(), int(stride))) {
    image.image.clear();
    return false;
  }
  image.width = width;
  image.height = height;
  image.component = 4;
  image.bits = 8;
  image.pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  return true;
}

int textureImage(const tinygltf::Texture& texture) {
  const auto webp = texture.extensions.find("EXT_texture_webp");
  if (webp != texture.extensions.end() && webp->second.IsObject() && webp->second.Get("source").IsInt())
    return webp->second.Get("source").GetNumberAsInt();
  return texture.source;
}

}  // namespace s3d::renderer::gltf

#pragma once
// EXT_texture_webp: WebP textures decoded with Debian's libwebp, and the image a texture shows.
#include <cstdint>

#include <tiny_gltf.h>

namespace s3d::renderer::gltf {

// Whether `bytes` hold a WebP file; if so, its size (from the header, before anything is decoded).
bool webpInfo(const unsigned char* bytes, int size, int& width, int& height);

// Decodes a WebP file into `image` as 8-bit RGBA; false when the data does not decode.
bool decodeWebp(tinygltf::Image& image, const unsigned char* bytes, int size);

// The image a texture shows: EXT_texture_webp's source when the texture has one, else its own source (-1: none).
int textureImage(const tinygltf::Texture& texture);

}  // namespace s3d::renderer::gltf

#pragma once
// Scenes and CPU references shared by the material tests (test_cutout_materials.cpp,
// test_material_shading.cpp): a textured unit quad in front of a camera, the pixel rays that reach it, and
// the bilinear, repeating texture lookup the renderer's sampler performs.
#include <cmath>
#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "s3d/renderer/deferred_renderer.h"
#include "s3d/renderer/scene.h"

namespace s3d::renderer::test {

// The quad z = 0, x and y in [-1, 1], facing +z, counter-clockwise from +z; uv (0, 0) at its top-left corner
// (-1, 1), u along +x, v along -y.
inline Mesh makeTexturedQuad() {
  Mesh mesh;
  const glm::vec3 normal(0.0f, 0.0f, 1.0f);
  mesh.vertices = {{{-1.0f, 1.0f, 0.0f}, normal}, {{1.0f, 1.0f, 0.0f}, normal},
                   {{1.0f, -1.0f, 0.0f}, normal}, {{-1.0f, -1.0f, 0.0f}, normal}};
  mesh.texCoords = {{0.0f, 0.0f}, {1.0f, 0.0f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  mesh.tangents.assign(4, glm::vec4(1.0f, 0.0f, 0.0f, 1.0f));
  mesh.indices = {0, 3, 2, 0, 2, 1};
  return mesh;
}

// The quad's texture coordinate at a point of its plane (quad space).
inline glm::vec2 quadTexCoord(glm::vec2 point) { return {(point.x + 1.0f) * 0.5f, (1.0f - point.y) * 0.5f}; }

// The world ray through pixel (x, y)'s centre of a width x height image of `camera` (no roll).
inline glm::vec3 pixelRay(const Camera& camera, std::uint32_t x, std::uint32_t y, std::uint32_t width, std::uint32_t height) {
  const float tanHalf = std::tan(camera.verticalFovRadians * 0.5f);
  const float aspect = float(width) / float(height);
  const float ndcX = (float(x) + 0.5f) / float(width) * 2.0f - 1.0f;
  const float ndcY = (float(y) + 0.5f) / float(height) * 2.0f - 1.0f;  // Vulkan: +y down the image
  const glm::vec3 view(ndcX * tanHalf * aspect, -ndcY * tanHalf, -1.0f);
  return glm::mat3(glm::inverse(cameraView(camera))) * view;
}

inline float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// What the renderer's texture sampler returns at uv: bilinear between texel centres, repeating; colour
// decoded from sRGB first for sRGB textures (Vulkan filters after the conversion), alpha linear.
inline glm::vec4 sampleBilinear(const Texture& texture, glm::vec2 uv) {
  const int w = int(texture.width), h = int(texture.height);
  auto texel = [&](int x, int y) {
    x = ((x % w) + w) % w;
    y = ((y % h) + h) % h;
    const std::uint8_t* p = &texture.rgba[4 * (std::size_t(y) * std::size_t(w) + std::size_t(x))];
    glm::vec4 value(p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f, p[3] / 255.0f);
    if (texture.encoding == Texture::Encoding::Srgb)
      for (int c = 0; c < 3; ++c) value[c] = srgbToLinear(value[c]);
    return value;
  };
  const float fx = uv.x * float(w) - 0.5f, fy = uv.y * float(h) - 0.5f;
  const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
  const float ax = fx - float(x0), ay = fy - float(y0);
  return glm::mix(glm::mix(texel(x0, y0), texel(x0 + 1, y0), ax), glm::mix(texel(x0, y0 + 1), texel(x0 + 1, y0 + 1), ax), ay);
}

}  // namespace s3d::renderer::test

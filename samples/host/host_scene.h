#pragma once
// The host's scene and renderer: a lit room with boxes (the world) and a first-person object drawn with its own
// projection into its own slice of the depth range (the seed's Listing 4.2 layout: device depth [0, split] for the
// first-person layer, [split, 1] for the world), by the host's own pipeline and shaders into its own D32 depth.
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "host_vulkan.h"

namespace host {

struct Camera {
  glm::vec3 position{0.0f, 1.6f, 0.0f};
  glm::vec3 forward{0.0f, 0.0f, -1.0f};
  float verticalFov = glm::radians(60.0f);
  float nearPlane = 0.1f, farPlane = 100.0f;           // the world's projection
  float weaponNear = 0.05f, weaponFar = 5.0f;          // the first-person layer's projection
  float firstPersonDepthRange = 0.1f;                  // its slice of the device depth range
};

struct Box {
  glm::vec3 center, halfSize, color;
};

class Scene {
 public:
  Scene(const Device& device, std::uint32_t width, std::uint32_t height);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // Clears and draws the world, then the first-person layer, into `color` (R8G8B8A8_SRGB) and `depth` (D32);
  // both must be in their attachment layouts.
  void record(VkCommandBuffer cmd, const Image& color, const Image& depth) const;

  // The host's physics: distance along the ray to the first world box within maxDistance (the seed's crosshair ray
  // cast; the first-person layer is not part of the world).
  std::optional<float> rayCast(glm::vec3 origin, glm::vec3 direction, float maxDistance) const;
  // The first-person object's linear view depth range (what the host knows of its weapon).
  glm::vec2 weaponDepthRange() const;

  const Camera& camera() const { return camera_; }

 private:
  const Device& device_;
  std::uint32_t width_, height_;
  Camera camera_;
  std::vector<Box> world_;
  Box weapon_;  // in view space
  VkPipelineLayout layout_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  std::optional<Buffer> vertices_, indices_;
};

}  // namespace host

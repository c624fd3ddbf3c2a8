#pragma once
// Buffers and images with their memory, plus upload, readback and layout transitions.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <vulkan/vulkan.h>

#include "s3d/vk/context.h"
#include "s3d/vk/unique.h"

namespace s3d::vk {

struct Buffer {
  Unique<VkBuffer> buffer;
  Unique<VkDeviceMemory> memory;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // persistently mapped when host-visible
};

enum class MemoryLocation { Device, HostVisible };

Buffer createBuffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryLocation location);

struct Image {
  Unique<VkImage> image;
  Unique<VkDeviceMemory> memory;
  Unique<VkImageView> view;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::uint32_t layer = 0;  // the array layer `view` shows (a borrowed layer of a host's array image)
};

// `layers` > 1: an array image; its view shows layer 0 (make other layers' views where they are needed).
Image createImage(const Context& context, VkFormat format, std::uint32_t width, std::uint32_t height,
                  VkImageUsageFlags usage, std::uint32_t layers = 1);

// A host's image and view (of `layer`) seen as an Image, for passes that take one: s3d never destroys them.
Image borrowImage(VkImage image, VkImageView view, VkFormat format, std::uint32_t width, std::uint32_t height,
                  std::uint32_t layer = 0);

// Bytes per texel of the uncompressed formats s3d uses; throws for others.
std::uint32_t texelSize(VkFormat format);

// One image layout transition with explicit stages and accesses (synchronization2).
struct ImageState {
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
};
void transition(VkCommandBuffer cmd, const Image& image, const ImageState& from, const ImageState& to);
// One global memory barrier (synchronization2): the source stage's accesses before the destination stage's.
void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);
// Earlier compute shaders' storage reads and writes before later ones'.
void computeStorageBarrier(VkCommandBuffer cmd);

// The sampler compute passes read images through with texelFetch: no filtering, clamped at the edges (a texel is
// fetched as written; a sampled descriptor needs one).
Unique<VkSampler> createNearestClampSampler(const Context& context);

// Common states.
inline constexpr ImageState kUndefined{};
inline constexpr ImageState kComputeRead{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                         VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
inline constexpr ImageState kComputeWrite{VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                          VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
inline constexpr ImageState kFragmentRead{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                                          VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};
inline constexpr ImageState kColorAttachment{VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                                             VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                             VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT |
                                                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
inline constexpr ImageState kDepthAttachment{VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
                                             VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT |
                                                 VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
                                             VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT |
                                                 VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT};
inline constexpr ImageState kTransferSource{VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                            VK_ACCESS_2_TRANSFER_READ_BIT};
inline constexpr ImageState kTransferDestination{VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
                                                 VK_ACCESS_2_TRANSFER_WRITE_BIT};

// Copies tightly packed texels into the image and leaves it in `finalState`.
void uploadImage(Context& context, const Image& image, std::span<const std::byte> texels, const ImageState& finalState);
// Copies the image back as tightly packed texels; `currentState` is the state the last use left it in.
std::vector<std::byte> readbackImage(Context& context, const Image& image, const ImageState& currentState);
// Copies bytes into a device-local buffer through a staging buffer.
void uploadBuffer(Context& context, const Buffer& buffer, std::span<const std::byte> bytes);

}  // namespace s3d::vk

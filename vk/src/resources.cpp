#include "s3d/vk/resources.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "s3d/vk/check.h"

namespace s3d::vk {
namespace {

// Concurrent sharing where the context has a compute queue beside its main one: a resource may then be used on
// either without a queue family ownership transfer.
template <typename CreateInfo>
void shareBetweenQueues(const Context& context, CreateInfo& info) {
  const std::vector<std::uint32_t>& families = context.sharingFamilies();
  info.sharingMode = families.size() > 1 ? VK_SHARING_MODE_CONCURRENT : VK_SHARING_MODE_EXCLUSIVE;
  info.queueFamilyIndexCount = families.size() > 1 ? std::uint32_t(families.size()) : 0u;
  info.pQueueFamilyIndices = families.size() > 1 ? families.data() : nullptr;
}

}  // namespace

Buffer createBuffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryLocation location) {
  VkDevice device = context.device();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  shareBetweenQueues(context, info);
  VkBuffer rawBuffer = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateBuffer(device, &info, context.allocator(), &rawBuffer));
  Buffer buffer;
  buffer.buffer = Unique<VkBuffer>(device, rawBuffer, vkDestroyBuffer, context.allocator());
  buffer.size = size;

  VkMemoryRequirements requirements{};
  vkGetBufferMemoryRequirements(device, rawBuffer, &requirements);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex =
      location == MemoryLocation::HostVisible
          ? context.findMemoryType(requirements.memoryTypeBits,
                                   VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
                                   VK_MEMORY_PROPERTY_HOST_CACHED_BIT)
          : context.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VkDeviceMemory rawMemory = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkAllocateMemory(device, &alloc, context.allocator(), &rawMemory));
  buffer.memory = Unique<VkDeviceMemory>(device, rawMemory, vkFreeMemory, context.allocator());
  S3D_VK_CHECK(vkBindBufferMemory(device, rawBuffer, rawMemory, 0));
  if (location == MemoryLocation::HostVisible) S3D_VK_CHECK(vkMapMemory(device, rawMemory, 0, size, 0, &buffer.mapped));
  return buffer;
}

std::uint32_t texelSize(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_B10G11R11_UFLOAT_PACK32:
    case VK_FORMAT_D24_UNORM_S8_UINT:  // depth aspect copies: 24 bits in the low bits of 32
      return 4;
    case VK_FORMAT_D16_UNORM:
      return 2;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_R32G32_UINT:  // the G-buffer's material target
      return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT:
      return 16;
    default:
      throw std::invalid_argument("texelSize: unsupported VkFormat " + std::to_string(static_cast<int>(format)));
  }
}

static VkImageAspectFlags aspectOf(VkFormat format) {
  const bool depth = format == VK_FORMAT_D32_SFLOAT || format == VK_FORMAT_D16_UNORM || format == VK_FORMAT_D24_UNORM_S8_UINT;
  return depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;  // views and copies: the depth aspect
}

Image borrowImage(VkImage handle, VkImageView view, VkFormat format, std::uint32_t width, std::uint32_t height,
                  std::uint32_t layer) {
  Image image;
  image.layer = layer;
  image.image = Unique<VkImage>(VK_NULL_HANDLE, handle, [](VkDevice, VkImage, const VkAllocationCallbacks*) {});
  image.view = Unique<VkImageView>(VK_NULL_HANDLE, view, [](VkDevice, VkImageView, const VkAllocationCallbacks*) {});
  image.format = format;
  image.aspect = aspectOf(format);
  image.width = width;
  image.height = height;
  return image;
}

Image createImage(const Context& context, VkFormat format, std::uint32_t width, std::uint32_t height,
                  VkImageUsageFlags usage, std::uint32_t layers) {
  if (width == 0 || height == 0) throw std::invalid_argument("createImage: zero-sized image");
  VkDevice device = context.device();
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = layers;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  shareBetweenQueues(context, info);
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkImage rawImage = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateImage(device, &info, context.allocator(), &rawImage));
  Image image;
  image.image = Unique<VkImage>(device, rawImage, vkDestroyImage, context.allocator());
  image.format = format;
  image.aspect = aspectOf(format);
  image.width = width;
  image.height = height;

  VkMemoryRequirements requirements{};
  vkGetImageMemoryRequirements(device, rawImage, &requirements);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = requirements.size;
  alloc.memoryTypeIndex = context.findMemoryType(requirements.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  VkDeviceMemory rawMemory = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkAllocateMemory(device, &alloc, context.allocator(), &rawMemory));
  image.memory = Unique<VkDeviceMemory>(device, rawMemory, vkFreeMemory, context.allocator());
  S3D_VK_CHECK(vkBindImageMemory(device, rawImage, rawMemory, 0));

  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = rawImage;
  viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = format;
  viewInfo.subresourceRange = {image.aspect, 0, 1, 0, 1};
  VkImageView rawView = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateImageView(device, &viewInfo, context.allocator(), &rawView));
  image.view = Unique<VkImageView>(device, rawView, vkDestroyImageView, context.allocator());
  return image;
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2, nullptr, srcStage, srcAccess, dstStage, dstAccess};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

void computeStorageBarrier(VkCommandBuffer cmd) {
  constexpr VkAccessFlags2 storage = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, storage, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, storage);
}

Unique<VkSampler> createNearestClampSampler(const Context& context) {
  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = samplerInfo.minFilter = VK_FILTER_NEAREST;
  samplerInfo.addressModeU = samplerInfo.addressModeV = samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler sampler = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateSampler(context.device(), &samplerInfo, context.allocator(), &sampler));
  return Unique<VkSampler>(context.device(), sampler, vkDestroySampler, context.allocator());
}

void transition(VkCommandBuffer cmd, const Image& image, const ImageState& from, const ImageState& to) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = from.stage == VK_PIPELINE_STAGE_2_NONE ? VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT : from.stage;
  barrier.srcAccessMask = from.access;
  barrier.dstStageMask = to.stage;
  barrier.dstAccessMask = to.access;
  barrier.oldLayout = from.layout;
  barrier.newLayout = to.layout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image.image;
  // A combined depth/stencil image changes layout in both aspects at once (no separateDepthStencilLayouts).
  const VkImageAspectFlags aspect =
      image.format == VK_FORMAT_D24_UNORM_S8_UINT ? VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT : image.aspect;
  barrier.subresourceRange = {aspect, 0, 1, image.layer, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

static VkBufferImageCopy wholeImageCopy(const Image& image) {
  VkBufferImageCopy region{};
  region.imageSubresource = {image.aspect, 0, image.layer, 1};
  region.imageExtent = {image.width, image.height, 1};
  return region;
}

void uploadImage(Context& context, const Image& image, std::span<const std::byte> texels,
                 const ImageState& finalState) {
  std::size_t expected = std::size_t(image.width) * image.height * texelSize(image.format);
  if (texels.size() != expected)
    throw std::invalid_argument("uploadImage: got " + std::to_string(texels.size()) + " bytes, image needs " +
                                std::to_string(expected));
  Buffer staging = createBuffer(context, expected, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryLocation::HostVisible);
  std::memcpy(staging.mapped, texels.data(), expected);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    transition(cmd, image, kUndefined, kTransferDestination);
    VkBufferImageCopy region = wholeImageCopy(image);
    vkCmdCopyBufferToImage(cmd, staging.buffer, image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transition(cmd, image, kTransferDestination, finalState);
  });
}

std::vector<std::byte> readbackImage(Context& context, const Image& image, const ImageState& currentState) {
  std::size_t bytes = std::size_t(image.width) * image.height * texelSize(image.format);
  Buffer staging = createBuffer(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryLocation::HostVisible);
  context.submitAndWait([&](VkCommandBuffer cmd) {
    transition(cmd, image, currentState, kTransferSource);
    VkBufferImageCopy region = wholeImageCopy(image);
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
    // Make the copy visible to the host read below.
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_HOST_READ_BIT);
    transition(cmd, image, kTransferSource, currentState.layout == VK_IMAGE_LAYOUT_UNDEFINED ? kTransferSource : currentState);
  });
  std::vector<std::byte> texels(bytes);
  std::memcpy(texels.data(), staging.mapped, bytes);
  return texels;
}

void uploadBuffer(Context& context, const Buffer& buffer, std::span<const std::byte> bytes) {
  if (bytes.size() > buffer.size) throw std::invalid_argument("uploadBuffer: data larger than the buffer");
  if (bytes.empty()) return;
  Buffer staging = createBuffer(context, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryLocation::HostVisible);
  std::memcpy(staging.mapped, bytes.data(), bytes.size());
  context.submitAndWait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, bytes.size()};
    vkCmdCopyBuffer(cmd, staging.buffer, buffer.buffer, 1, &region);
  });
}

}  // namespace s3d::vk

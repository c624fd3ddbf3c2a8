#pragma once
// One image with two array layers and a 2D view of each: what an OpenXR swapchain or a multiview host hands over as
// a stereo frame's eyes (the host frame's tests and its benchmark).
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>

#include "s3d/vk/check.h"
#include "s3d/vk/context.h"
#include "s3d/vk/resources.h"
#include "s3d/vk/unique.h"

namespace s3d::test {

struct ArrayImage {
  vk::Image image;  // its own view shows layer 0
  std::array<vk::Unique<VkImageView>, 2> views;

  // Layer `layer` seen as an image of its own (borrowed: the array owns it), for transitions and read-backs.
  vk::Image layer(std::uint32_t layer) const {
    return vk::borrowImage(image.image, views[layer], image.format, image.width, image.height, layer);
  }
};

inline ArrayImage createArrayImage(vk::Context& context, VkFormat format, std::uint32_t width, std::uint32_t height,
                                   VkImageUsageFlags usage) {
  ArrayImage result{vk::createImage(context, format, width, height, usage, 2), {}};
  for (std::uint32_t layer = 0; layer < 2; ++layer) {
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = result.image.image;
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, layer, 1};
    VkImageView view = VK_NULL_HANDLE;
    S3D_VK_CHECK(vkCreateImageView(context.device(), &viewInfo, nullptr, &view));
    result.views[layer] = vk::Unique<VkImageView>(context.device(), view, vkDestroyImageView);
  }
  return result;
}

}  // namespace s3d::test

#pragma once
// Internal to the renderer: the sampler its compute passes read other passes' images through (no filtering,
// clamped at the edges: a texel is fetched as written, half-resolution occlusion included).
#include "s3d/vk/check.h"
#include "s3d/vk/context.h"
#include "s3d/vk/unique.h"

namespace s3d::renderer::detail {

inline vk::Unique<VkSampler> createNearestClampSampler(const vk::Context& context) {
  VkSamplerCreateInfo samplerInfo{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  samplerInfo.magFilter = samplerInfo.minFilter = VK_FILTER_NEAREST;
  samplerInfo.addressModeU = samplerInfo.addressModeV = samplerInfo.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  VkSampler sampler = VK_NULL_HANDLE;
  S3D_VK_CHECK(vkCreateSampler(context.device(), &samplerInfo, nullptr, &sampler));
  return vk::Unique<VkSampler>(context.device(), sampler, vkDestroySampler);
}

}  // namespace s3d::renderer::detail

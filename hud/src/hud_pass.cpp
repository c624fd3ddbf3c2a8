#include "s3d/hud/hud_pass.h"

#include <array>
#include <stdexcept>
#include <string>

#include "s3d/hud/hud_pass_shared.h"
#include "s3d/stereo/detail/host_barriers.h"

// clang-format off
#include <s3d_spirv/hud_composite_comp.h>
// clang-format on

namespace s3d::hud {
namespace {

constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkAccessFlags2 kEyeAccess = VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
// s3d's own layers stay in this state from construction on: only sampled, never written again.
constexpr vk::ImageState kLayerReadable{VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kCompute,
                                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

bool isLayerFormat(VkFormat f) { return f == VK_FORMAT_R8G8B8A8_UNORM || f == VK_FORMAT_B8G8R8A8_UNORM; }

void requireImage(const stereo::HostImage& image, const char* what, const std::string* name = nullptr) {
  if (!image.image || !image.view)  // the message is built only on failure: record() allocates nothing otherwise
    throw std::invalid_argument(std::string("HudPass: the ") + what + (name ? " '" + *name + "'" : std::string()) +
                                " image is missing");
}

}  // namespace

HudPass::HudPass(vk::Context& context, const HudPassDesc& desc) : context_(&context), desc_(desc) {
  if (desc.width == 0 || desc.height == 0) throw std::invalid_argument("HudPass: zero eye size");
  if (desc.elements.size() > S3D_HUD_MAX_ELEMENTS)
    throw std::invalid_argument("HudPass: " + std::to_string(desc.elements.size()) + " elements, at most " +
                                std::to_string(S3D_HUD_MAX_ELEMENTS));
  for (const HudPassElement& element : desc.elements) {
    if (element.isHostLayer()) {
      if (element.hostWidth == 0 || element.hostHeight == 0)
        throw std::invalid_argument("HudPass: element '" + element.name + "' has neither pixels nor a host layer size");
      ++hostLayerCount_;
    } else if (element.pixels.width == 0 || element.pixels.height == 0) {
      throw std::invalid_argument("HudPass: element '" + element.name + "' has an empty layer");
    }
  }

  const VkDescriptorSetLayoutBinding bindings[] = {
      {0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {1, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {2, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT, nullptr}};
  layout_ = vk::createPushDescriptorLayout(context, bindings, sizeof(gpu::HudCompositeConstants),
                                           VK_SHADER_STAGE_COMPUTE_BIT);
  pipeline_ = vk::createComputePipeline(context, layout_.layout, spirv_hud_composite_comp);

  sampler_ = vk::createNearestClampSampler(context);  // texelFetch ignores its filter; a sampler is required

  uploaded_.resize(desc.elements.size());
  for (std::size_t i = 0; i < desc.elements.size(); ++i) {
    const HudPassElement& element = desc.elements[i];
    if (element.isHostLayer()) continue;
    uploaded_[i] = vk::createImage(context, VK_FORMAT_R8G8B8A8_UNORM, element.pixels.width, element.pixels.height,
                                   VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT);
    vk::uploadImage(context, *uploaded_[i], std::as_bytes(std::span(element.pixels.pixels)), kLayerReadable);
  }
}

std::array<VkImageLayout, S3D_HUD_MAX_ELEMENTS> HudPass::checkedLayerLayouts(std::span<const HudElementFrame> frames,
                                                                             std::span<const stereo::HostImage> hostLayers,
                                                                             const stereo::HostImage& left,
                                                                             const stereo::HostImage& right) const {
  if (frames.size() != desc_.elements.size())
    throw std::invalid_argument("HudPass: " + std::to_string(frames.size()) + " element states for " +
                                std::to_string(desc_.elements.size()) + " elements");
  if (hostLayers.size() != hostLayerCount_)
    throw std::invalid_argument("HudPass: " + std::to_string(hostLayers.size()) + " host layer images for " +
                                std::to_string(hostLayerCount_) + " host layers");
  for (const stereo::HostImage* eye : {&left, &right}) {
    requireImage(*eye, eye == &left ? "left eye" : "right eye");
    if (eye->format != eyeFormat())
      throw std::invalid_argument("HudPass: the eyes must be R8G8B8A8_UNORM storage images (HDR eyes: tone map first)");
    if (eye->stage == VK_PIPELINE_STAGE_2_NONE && eye->layout != VK_IMAGE_LAYOUT_GENERAL)
      throw std::invalid_argument("HudPass: an eye the host synchronizes itself must be in GENERAL");
  }

  // Each host layer's layout while s3d samples it (its own when readable, else SHADER_READ_ONLY_OPTIMAL).
  std::array<VkImageLayout, S3D_HUD_MAX_ELEMENTS> hostLayouts{};
  std::size_t hostIndex = 0;
  for (const HudPassElement& element : desc_.elements) {
    if (!element.isHostLayer()) continue;
    const stereo::HostImage& image = hostLayers[hostIndex];
    requireImage(image, "layer", &element.name);
    if (!isLayerFormat(image.format))
      throw std::invalid_argument("HudPass: the layer '" + element.name + "' must be R8G8B8A8_UNORM or B8G8R8A8_UNORM");
    hostLayouts[hostIndex] =
        stereo::detail::sampledReadLayout(image.layout, image.stage, "HudPass: the layer '" + element.name + "'");
    ++hostIndex;
  }
  return hostLayouts;
}

void HudPass::record(VkCommandBuffer cmd, std::span<const HudElementFrame> frames,
                     std::span<const stereo::HostImage> hostLayers, const stereo::HostImage& left,
                     const stereo::HostImage& right) const {
  const std::array<VkImageLayout, S3D_HUD_MAX_ELEMENTS> hostLayouts = checkedLayerLayouts(frames, hostLayers, left, right);

  // Into the layouts s3d uses (eyes: GENERAL, read and written by compute; layers: sampled by compute).
  stereo::detail::HostBarriers<2 + S3D_HUD_MAX_ELEMENTS> before, after;
  for (const stereo::HostImage* eye : {&left, &right})
    if (eye->stage != VK_PIPELINE_STAGE_2_NONE) {
      before.image(eye->image, eye->format, eye->layout, eye->stage, eye->access, VK_IMAGE_LAYOUT_GENERAL, kCompute, kEyeAccess,
                   eye->layer);
      after.image(eye->image, eye->format, VK_IMAGE_LAYOUT_GENERAL, kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  eye->layout, eye->stage, eye->access, eye->layer);
    }
  for (std::size_t i = 0; i < hostLayers.size(); ++i) {
    const stereo::HostImage& image = hostLayers[i];
    if (image.stage == VK_PIPELINE_STAGE_2_NONE) continue;
    before.image(image.image, image.format, image.layout, image.stage, image.access, hostLayouts[i], kCompute,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    after.image(image.image, image.format, hostLayouts[i], kCompute, VK_ACCESS_2_NONE, image.layout, image.stage,
                image.access);
  }
  before.record(cmd);

  // Elements overlap in the eyes and blend in order: each one's reads and writes wait for the previous one's.
  stereo::detail::HostBarriers<1> between;
  between.memory = true;
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
  bool first = true;
  std::size_t hostIndex = 0;
  for (std::size_t i = 0; i < desc_.elements.size(); ++i) {
    const HudPassElement& element = desc_.elements[i];
    const bool host = element.isHostLayer();
    const std::size_t layerIndex = host ? hostIndex++ : 0;
    if (frames[i].hidden) continue;
    const std::uint32_t layerWidth = host ? element.hostWidth : element.pixels.width;
    const std::uint32_t layerHeight = host ? element.hostHeight : element.pixels.height;
    const LayerOrigin l = layerOrigin(element.placement, eyeOffsetPx(frames[i].parallaxPx, stereo::Eye::Left));
    const LayerOrigin r = layerOrigin(element.placement, eyeOffsetPx(frames[i].parallaxPx, stereo::Eye::Right));
    gpu::HudCompositeConstants push{l.x, l.y, r.x, r.y, int(layerWidth), int(layerHeight), int(desc_.width),
                                    int(desc_.height), frames[i].fadesBehindWeapon ? 1 : 0};
    const VkDescriptorImageInfo infos[3] = {
        {sampler_, host ? hostLayers[layerIndex].view : uploaded_[i]->view.get(),
         host ? hostLayouts[layerIndex] : kLayerReadable.layout},
        {VK_NULL_HANDLE, left.view, VK_IMAGE_LAYOUT_GENERAL},
        {VK_NULL_HANDLE, right.view, VK_IMAGE_LAYOUT_GENERAL}};
    VkWriteDescriptorSet writes[3] = {vk::sampledImageWrite(0, &infos[0]), vk::storageImageWrite(1, &infos[1]),
                                      vk::storageImageWrite(2, &infos[2])};
    writes[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    if (!first) between.record(cmd);
    first = false;
    context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.layout, 0, 3, writes);
    vkCmdPushConstants(cmd, layout_.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof push, &push);
    vkCmdDispatch(cmd, (layerWidth + S3D_HUD_GROUP_SIZE - 1) / S3D_HUD_GROUP_SIZE,
                  (layerHeight + S3D_HUD_GROUP_SIZE - 1) / S3D_HUD_GROUP_SIZE, 2);
  }
  after.record(cmd);
}

void HudOverlay::recordOnEyes(VkCommandBuffer cmd, const stereo::HostImage& left, const stereo::HostImage& right) const {
  pass_->record(cmd, frames_, hostLayers_, left, right);
}

}  // namespace s3d::hud
